#include "bake/EnergyBalance.h"

#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <tbb/parallel_for.h>

#include "bake/Quadrature.h"
#include "core/Glsl.h"
#include "core/TableLookup.h"

namespace cloudlut::bake {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

double unscatteredShareExact(double sigma) {
  if (sigma < 1e-4) return 1.0 - 4.0 * sigma / 3.0;
  return (1.0 - std::exp(-2.0 * sigma) * (1.0 + 2.0 * sigma)) / (2.0 * sigma * sigma);
}

nlohmann::json EnergyBalance::toJson() const {
  nlohmann::json arr = nlohmann::json::array();
  for (const EnergySlice& s : slices) {
    nlohmann::json j = {{"rho", s.rho}, {"sigma", s.sigma}, {"unscattered", s.unscattered}, {"total", s.total}};
    if (s.single >= 0) j["single"] = s.single;
    if (s.multiple >= 0) j["multiple"] = s.multiple;
    arr.push_back(j);
  }
  return {{"slices", arr}};
}

EnergyInputs energyInputsFromParameters(const Table4D* single, const Table4D* multiple) {
  const Table4D* t = single ? single : multiple;
  if (!t) throw std::invalid_argument("energy balance: no scattering table given");
  EnergyInputs in;
  const auto& p = t->parameters();
  in.unitOpticalRadius = p.value("extinction_per_m", defaults::kExtinctionPerMetre) *
                         p.value("radius_m", defaults::kParticleRadiusMetres);
  in.firstPhase = recordedPhase(single ? single->parameters() : p, "first_phase", defaults::kFirstPhase);
  return in;
}

EnergyBalance computeEnergyBalance(const Table4D* single, const Table4D* multiple,
                                   const EnergyInputs& in) {
  const Table4D* t = single ? single : multiple;
  if (!t) throw std::invalid_argument("energy balance: no scattering table given");
  if (single && multiple && single->axes()[3].size != multiple->axes()[3].size)
    throw std::invalid_argument("energy balance: the single and multiple tables have different density slices");
  // storage resolved (and validated) once, not per sample
  const ScatteringStorage storage1 = single ? scatteringStorage(*single) : ScatteringStorage::Log2MeanSource;
  const ScatteringStorage storageM = multiple ? scatteringStorage(*multiple) : ScatteringStorage::MeanSource;
  const Axis& dAx = t->axes()[3];
  // axes records (density range irrelevant: the slice is addressed by its node fraction below)
  const glm::vec4 axes1 = single ? scatteringAxesRecord(*single) : glm::vec4(0.0f);
  const glm::vec4 axesM = multiple ? scatteringAxesRecord(*multiple) : glm::vec4(0.0f);
  const int nSlices = dAx.size;
  // Quadrature: θS composite Gauss 8×8; α (angle between v and l) = π ξ², composite 12×8 in ξ;
  // β (azimuth of v about l) midpoints over [0, π], doubled by symmetry.
  const GaussRule& g = gaussLegendre(8);
  std::vector<double> thS, wS, alpha, wA;
  for (int c = 0; c < 8; ++c)
    for (int k = 0; k < 8; ++k) {
      const double th = kPi * (c + g.x[k]) / 8.0;
      thS.push_back(th);
      wS.push_back(kPi / 8.0 * g.w[k] * 2.0 * kPi * std::sin(th));
    }
  for (int c = 0; c < 12; ++c)
    for (int k = 0; k < 8; ++k) {
      const double xi = (c + g.x[k]) / 12.0, a = kPi * xi * xi;
      alpha.push_back(a);
      wA.push_back(g.w[k] / 12.0 * 2.0 * kPi * xi * std::sin(a));
    }
  const int nBeta = 64;
  EnergyBalance out;
  out.slices.resize(nSlices);
  for (int k = 0; k < nSlices; ++k) {
    const double s = dAx.value(k);
    const double rho = std::exp2(s), sigma = in.unitOpticalRadius * rho;
    const float wFrac = nSlices > 1 ? static_cast<float>(k) / static_cast<float>(nSlices - 1) : 0.0f;
    std::vector<double> p1(thS.size(), 0.0), pm(thS.size(), 0.0);
    tbb::parallel_for(std::size_t(0), thS.size(), [&](std::size_t i) {
      const glm::vec3 S(static_cast<float>(std::sin(thS[i])), 0.0f, static_cast<float>(std::cos(thS[i])));
      const glm::vec3 l(0.0f, 0.0f, 1.0f);
      double a1 = 0.0, am = 0.0;
      for (std::size_t j = 0; j < alpha.size(); ++j) {
        const double ca = std::cos(alpha[j]), sa = std::sin(alpha[j]);
        const double ph = static_cast<double>(phaseValue(in.firstPhase, static_cast<float>(ca)));
        double b1 = 0.0, bm = 0.0;
        for (int b = 0; b < nBeta; ++b) {
          const double beta = kPi * (b + 0.5) / nBeta;
          const glm::vec3 v(static_cast<float>(sa * std::cos(beta)), static_cast<float>(sa * std::sin(beta)),
                            static_cast<float>(ca));
          const float cosV = -glm::dot(v, S);
          if (!(cosV > 0.0f)) continue;
          const float tau = static_cast<float>(sigma) * 2.0f * cosV;
          float val = 0.0f;
          if (single) {
            const glm::vec4 x = glsl::scatteringAxes(S, v, l, 1.0f, axes1, 2.0f);
            single->sample({x.x, x.y, x.z, wFrac}, &val);
            b1 += static_cast<double>(scatteringFromStored(storage1, val, tau)) * cosV;
          }
          if (multiple) {
            const glm::vec4 x = glsl::scatteringAxes(S, v, l, 1.0f, axesM, 2.0f);
            multiple->sample({x.x, x.y, x.z, wFrac}, &val);
            bm += static_cast<double>(scatteringFromStored(storageM, val, tau)) * cosV;
          }
        }
        const double wb = kPi / nBeta * 2.0;
        a1 += wA[j] * ph * b1 * wb;
        am += wA[j] * bm * wb;
      }
      p1[i] = wS[i] * a1;
      pm[i] = wS[i] * am;
    });
    EnergySlice e;
    e.rho = rho;
    e.sigma = sigma;
    e.unscattered = unscatteredShareExact(sigma);
    e.total = e.unscattered;
    double s1 = 0.0, sm = 0.0;
    for (std::size_t i = 0; i < thS.size(); ++i) {
      s1 += p1[i];
      sm += pm[i];
    }
    if (single) {
      e.single = s1 / kPi;
      e.total += e.single;
    }
    if (multiple) {
      e.multiple = sm / kPi;
      e.total += e.multiple;
    }
    out.slices[k] = e;
  }
  return out;
}

}  // namespace cloudlut::bake
