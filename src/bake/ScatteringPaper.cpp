#include "bake/ScatteringPaper.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/geometric.hpp>
#include <tbb/parallel_for.h>

#include "bake/Quadrature.h"
#include "bake/SingleScattering.h"
#include "core/Glsl.h"
#include "cloudlut_quadrilinear.h"

namespace cloudlut::bake {

namespace {

constexpr double kPi = 3.14159265358979323846;

struct Volume {
  int nS, nP, nV, nR;
  std::size_t size() const { return static_cast<std::size_t>(nS) * nP * nV * nR; }
  std::size_t index(int iS, int iP, int iV, int iR) const {
    return ((static_cast<std::size_t>(iR) * nV + iV) * nP + iP) * nS + iS;
  }
  double thetaS(int i) const { return kPi * i / (nS - 1); }
  double phiV(int i) const { return 2.0 * kPi * i / (nP - 1); }
  double thetaV(int i) const { return kPi * i / (nV - 1); }
  double radius(int i) const { return static_cast<double>(i) / (nR - 1); }
};

// Point and view direction of a cell, in the light frame (l = +z, point in the xz plane).
void cellGeometry(const Volume& vol, int iS, int iP, int iV, int iR, glm::dvec3& P, glm::dvec3& v) {
  const double ts = vol.thetaS(iS), pv = vol.phiV(iP), tv = vol.thetaV(iV);
  const glm::dvec3 n(std::sin(ts), 0.0, std::cos(ts));
  const glm::dvec3 x(std::cos(ts), 0.0, -std::sin(ts)), y(0.0, 1.0, 0.0);
  P = vol.radius(iR) * n;
  v = std::sin(tv) * (std::cos(pv) * x + std::sin(pv) * y) - std::cos(tv) * n;
}

// 4D interpolation of a volume field at point Q (|Q| ≤ 1) for view direction v.
float sampleVolume(const Volume& vol, const std::vector<float>& f, const glm::dvec3& Q, const glm::dvec3& v) {
  const double r = std::min(1.0, glm::length(Q));
  const glm::vec3 n = r > 1e-6 ? glm::vec3(Q / r) : glm::vec3(0.0f, 0.0f, 1.0f);
  const glm::vec3 a = glsl::scatteringAngles(n, glm::vec3(v), glm::vec3(0.0f, 0.0f, 1.0f));
  const double c[4] = {a.x / kPi * (vol.nS - 1), a.y / (2.0 * kPi) * (vol.nP - 1), a.z / kPi * (vol.nV - 1),
                       r * (vol.nR - 1)};
  const std::uint32_t n4[4] = {static_cast<std::uint32_t>(vol.nS), static_cast<std::uint32_t>(vol.nP),
                               static_cast<std::uint32_t>(vol.nV), static_cast<std::uint32_t>(vol.nR)};
  std::uint32_t i[4];
  float fr[4];
  for (int k = 0; k < 4; ++k) {
    const double cc = std::clamp(c[k], 0.0, static_cast<double>(n4[k] - 1));
    i[k] = std::min(static_cast<std::uint32_t>(cc), n4[k] - 2);
    fr[k] = static_cast<float>(cc - i[k]);
  }
  float out = 0.0f;
  cloudlut_reader::interpolateCell(f.data(), n4, 1, i, fr, &out);
  return out;
}

}  // namespace

void bakePaperMultipleScattering(const ScatteringSettings& settings, Table4D& table,
                                 nlohmann::json& slices, const ProgressFn& progress,
                                 double progressBase, double progressSpan) {
  const auto& d = settings.dims;
  // The seed's volume covers φv ∈ [0, 2π]: a folded table's dims[1] nodes over [0, π] become
  // 2·(dims[1] − 1) + 1 at the same spacing.
  const int nPhi = table.axes()[1].folded ? 2 * (d[1] - 1) + 1 : d[1];
  const Volume vol{d[0], nPhi, 2 * (d[2] - 1) + 1, d[2]};
  const int steps = 2 * d[2];
  const glm::dvec3 l(0, 0, 1);
  const std::size_t N = vol.size();
  const int nRho = d[3];
  const Phase p1 = settings.firstPhase, pm = settings.laterPhase;

  // Gather directions: the table's own (φv, θv) nodes (periodic φ node counted once), with
  // weights ∫ hat(θ) sinθ dθ · Δφ.
  std::vector<double> wTheta(vol.nV, 0.0);
  const GaussRule& g = gaussLegendre(8);
  for (int a = 0; a + 1 < vol.nV; ++a) {
    const double t0 = vol.thetaV(a), t1 = vol.thetaV(a + 1);
    for (int k = 0; k < 8; ++k) {
      const double w = g.w[k] * (t1 - t0) * std::sin(t0 + (t1 - t0) * g.x[k]);
      wTheta[a] += w * (1.0 - g.x[k]);
      wTheta[a + 1] += w * g.x[k];
    }
  }
  const double dPhi = 2.0 * kPi / (vol.nP - 1);

  for (int k = 0; k < nRho; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    const double s = settings.sMin + (settings.sMax - settings.sMin) * k / (nRho - 1);
    const double sigma = settings.extinction * settings.radius * std::exp2(s);
    std::vector<float> L(N), J(N), sum(N, 0.0f);
    // Fixed-step marching from the cell along its view direction; `source(Q, v)` per step.
    const auto march = [&](const auto& source, std::vector<float>& out) {
      tbb::parallel_for(std::size_t(0), N, [&](std::size_t c) {
        const int iS = static_cast<int>(c % vol.nS);
        const int iP = static_cast<int>((c / vol.nS) % vol.nP);
        const int iV = static_cast<int>((c / (static_cast<std::size_t>(vol.nS) * vol.nP)) % vol.nV);
        const int iR = static_cast<int>(c / (static_cast<std::size_t>(vol.nS) * vol.nP * vol.nV));
        glm::dvec3 P, v;
        cellGeometry(vol, iS, iP, iV, iR, P, v);
        const double len = distanceToSphere(P, v);
        double acc = 0.0;
        if (len > 0.0) {
          const double h = len / steps;
          for (int st = 0; st < steps; ++st) {
            const double ta = st * h, tb = ta + h;
            const double w = std::exp(-sigma * ta) - std::exp(-sigma * tb);
            acc += w * source(P + (ta + 0.5 * h) * v, v);
          }
        }
        out[c] = static_cast<float>(acc);
      });
    };
    // L(1): without the phase function.
    march([&](const glm::dvec3& Q, const glm::dvec3&) { return std::exp(-sigma * sunPath(Q, l)); }, L);
    const int orders = settings.orders;
    for (int n = 2; n <= orders; ++n) {
      // J(n): brute-force gather over the directions of the cell's own point.
      tbb::parallel_for(std::size_t(0), N, [&](std::size_t c) {
        const int iS = static_cast<int>(c % vol.nS);
        const int iP = static_cast<int>((c / vol.nS) % vol.nP);
        const int iV = static_cast<int>((c / (static_cast<std::size_t>(vol.nS) * vol.nP)) % vol.nV);
        const int iR = static_cast<int>(c / (static_cast<std::size_t>(vol.nS) * vol.nP * vol.nV));
        glm::dvec3 P, v;
        cellGeometry(vol, iS, iP, iV, iR, P, v);
        double acc = 0.0;
        for (int jV = 0; jV < vol.nV; ++jV)
          for (int jP = 0; jP + 1 < vol.nP; ++jP) {
            glm::dvec3 Pw, w;
            cellGeometry(vol, iS, jP, jV, iR, Pw, w);
            double value = L[vol.index(iS, jP, jV, iR)];
            if (n == 2) value *= phaseValue(p1, static_cast<float>(glm::dot(w, l)));
            acc += wTheta[jV] * dPhi * value *
                   phaseValue(pm, static_cast<float>(glm::dot(w, v)));
          }
        J[c] = static_cast<float>(acc);
      });
      // L(n): marching through J(n) with 4D interpolation.
      march([&](const glm::dvec3& Q, const glm::dvec3& v) { return sampleVolume(vol, J, Q, v); }, L);
      for (std::size_t c = 0; c < N; ++c) sum[c] += L[c];
      reportProgress(progress, "multiple scattering (paper)",
                     progressBase + progressSpan * (k + static_cast<double>(n - 1) / orders) / nRho);
    }
    // Output: r = 1, θv ≤ π/2, interpolated from the seed's uniform θS nodes to the table's
    // (which concentrate about the terminator), stored as the mean source L / (1 − e^{−σc})
    // (cloudlut_shading.glsl). A grazing node (c = 0) takes the mean source of its neighbour,
    // the limit this fixed-step baseline can give.
    const auto& ax = table.axes();
    for (int iS = 0; iS < ax[0].size; ++iS)
      for (int iP = 0; iP < ax[1].size; ++iP) {
        float meanSource = 0.0f;
        for (int iV = 0; iV < ax[2].size; ++iV) {
          const ScatteringNode n = scatteringNode(ax[0].value(iS), ax[1].value(iP), ax[2].value(iV));
          const double opacity = -std::expm1(-sigma * std::max(0.0, -2.0 * glm::dot(n.S, n.v)));
          if (opacity > 1e-9)
            meanSource = static_cast<float>(std::max(0.0f, sampleVolume(vol, sum, n.S, n.v)) / opacity);
          table.at(table.index(iS, iP, iV, k), 0) = meanSource;
        }
      }
    slices.push_back({{"sigma", sigma},
                      {"orders", orders},
                      {"volume", {vol.nS, vol.nP, vol.nV, vol.nR}},
                      {"steps", steps},
                      {"seconds", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()}});
  }
}

}  // namespace cloudlut::bake
