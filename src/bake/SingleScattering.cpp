#include "bake/SingleScattering.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <tbb/parallel_for.h>

#include "bake/Quadrature.h"
#include "core/Glsl.h"

namespace cloudlut::bake {

double singleScatteringL1(const glm::dvec3& S, const glm::dvec3& v, const glm::dvec3& l, double sigma) {
  const double chord = -2.0 * glm::dot(S, v);
  if (!(chord > 0.0)) return 0.0;
  return sunlitRayIntegral(S, v, l, sigma, chord);
}

double singleScatteringMeanSource(const glm::dvec3& S, const glm::dvec3& v, const glm::dvec3& l, double sigma) {
  const double chord = std::max(0.0, -2.0 * glm::dot(S, v));
  const double opacity = -std::expm1(-sigma * chord);
  if (opacity < 1e-9) return std::exp(-sigma * sunPath(S, l));
  return std::clamp(sunlitRayIntegral(S, v, l, sigma, chord) / opacity, 0.0, 1.0);
}

ScatteringNode scatteringNode(double thetaS, double phiV, double thetaV) {
  const glm::dvec3 S(std::sin(thetaS), 0.0, std::cos(thetaS));
  const glm::dvec3 x(std::cos(thetaS), 0.0, -std::sin(thetaS)), y(0.0, 1.0, 0.0);
  const glm::dvec3 v = std::sin(thetaV) * (std::cos(phiV) * x + std::sin(phiV) * y) - std::cos(thetaV) * S;
  return {S, v, glm::dvec3(0.0, 0.0, 1.0)};
}

void bakeSingleScatteringSlice(double sigma, int slice, Table4D& table) {
  const auto& ax = table.axes();
  const int nS = ax[0].size, nP = ax[1].size, nV = ax[2].size;
  tbb::parallel_for(0, nS * nP, [&](int row) {
    const int iS = row % nS, iP = row / nS;
    for (int iV = 0; iV < nV; ++iV) {
      const ScatteringNode n = scatteringNode(ax[0].value(iS), ax[1].value(iP), ax[2].value(iV));
      const double meanSource = singleScatteringMeanSource(n.S, n.v, n.l, sigma);
      table.at(table.index(iS, iP, iV, slice), 0) = glsl::singleScatteringToTable(static_cast<float>(meanSource));
    }
  });
}

}  // namespace cloudlut::bake
