#include "bake/Quadrature.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <mutex>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "core/Float4.h"

namespace cloudlut::bake {

namespace {

GaussRule computeGauss(int n) {
  GaussRule r;
  r.x.resize(n);
  r.w.resize(n);
  const double pi = 3.14159265358979323846;
  for (int i = 0; i < n; ++i) {
    double z = std::cos(pi * (i + 0.75) / (n + 0.5));
    double dp = 1.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = 0.0;
      for (int k = 1; k <= n; ++k) {
        const double p2 = p1;
        p1 = p0;
        p0 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p2) / k;
      }
      dp = n * (z * p0 - p1) / (z * z - 1.0);
      const double dz = p0 / dp;
      z -= dz;
      if (std::abs(dz) < 1e-16) break;
    }
    // Recompute the derivative at the converged root for the weight.
    double p0 = 1.0, p1 = 0.0;
    for (int k = 1; k <= n; ++k) {
      const double p2 = p1;
      p1 = p0;
      p0 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p2) / k;
    }
    dp = n * (z * p0 - p1) / (z * z - 1.0);
    r.x[n - 1 - i] = 0.5 * (1.0 + z);
    r.w[n - 1 - i] = 1.0 / ((1.0 - z * z) * dp * dp);  // 2/((1-z²)P'²) halved for [0, 1]
  }
  return r;
}

}  // namespace

const GaussRule& gaussLegendre(int n) {
  if (n < 1 || n > 64) throw std::invalid_argument("gaussLegendre: n must be in [1, 64]");
  static std::array<GaussRule, 65> cache;
  static std::array<std::once_flag, 65> once;
  std::call_once(once[n], [n] { cache[n] = computeGauss(n); });
  return cache[n];
}

double distanceToSphere(const glm::dvec3& x, const glm::dvec3& d) {
  const double b = glm::dot(x, d);
  const double c = glm::dot(x, x) - 1.0;
  const double disc = std::max(b * b - c, 0.0);
  // Stable form: for b < 0 the root -b + sqrt(disc) has no cancellation; for b > 0 use
  // -c / (b + sqrt(disc)).
  const double s = std::sqrt(disc);
  const double t = b <= 0.0 ? -b + s : (c < 0.0 ? -c / (b + s) : 0.0);
  return std::max(t, 0.0);
}

double sunlitRayIntegral(const glm::dvec3& x, const glm::dvec3& d, const glm::dvec3& l,
                         double sigma, double length) {
  if (!(length > 0.0) || !(sigma > 0.0)) return 0.0;
  const GaussRule& g = gaussLegendre(8);
  const auto f = [&](double t) {
    return sigma * std::exp(-sigma * (t + sunPath(x + t * d, l)));
  };
  const auto panel = [&](double a, double b) {
    double s = 0.0;
    for (int i = 0; i < 8; ++i) s += g.w[i] * f(a + (b - a) * g.x[i]);
    return s * (b - a);
  };
  // Geometric grading toward both ends: first panel 10⁻³/σ, each next one twice as long (the
  // sun path has a square-root singularity where a chord end lies on the terminator).
  const double half = 0.5 * length;
  const double h0 = std::min(half, 1e-3 / sigma);
  double sum = 0.0;
  double a = 0.0, h = h0;
  while (a < half) {
    const double b = std::min(half, a + h);
    sum += panel(a, b) + panel(length - b, length - a);
    a = b;
    h *= 2.0;
  }
  return sum;
}

double sunlitRayIntegralFast(const glm::dvec3& x, const glm::dvec3& d, const glm::dvec3& l,
                             double sigma, double length) {
  if (!(length > 0.0) || !(sigma > 0.0)) return 0.0;
  // In single precision, four Gauss nodes per SIMD step (expFloat4, logFloat4: their ~1e-7 is
  // far below the rule's ~1e-3): the point at distance t is
  // y = x + t d; with l's frame (e_z = l) its sun path is d_sun = −y_z + √(1 − |y_⊥|²), where
  // |y_⊥|² = |x_⊥|² + 2t (x_⊥·d_⊥) + t²|d_⊥|² is a quadratic in t.
  // The 8 Gauss nodes and weights of a panel as two four-lane vectors.
  struct Weights {
    Float4 x[2], w[2];
  };
  static const Weights g8 = [] {
    const GaussRule& g = gaussLegendre(8);
    Weights r{};
    for (int i = 0; i < 8; ++i) {
      r.x[i / 4][i % 4] = static_cast<float>(g.x[i]);
      r.w[i / 4][i % 4] = static_cast<float>(g.w[i]);
    }
    return r;
  }();
  const double xz = glm::dot(x, l), dz = glm::dot(d, l);
  const float p0 = static_cast<float>(glm::dot(x, x) - xz * xz);
  const float p1 = static_cast<float>(2.0 * (glm::dot(x, d) - xz * dz));
  const float p2 = static_cast<float>(glm::dot(d, d) - dz * dz);
  const float fz = static_cast<float>(xz), gz = static_cast<float>(dz), s = static_cast<float>(sigma);
  const float invS = 1.0f / s, tMax = static_cast<float>(length);
  const float U = static_cast<float>(-std::expm1(-sigma * length));
  // Panels in u: [0, U/4] and [U/4, U]; one panel [0, U] when the ray's optical depth is at
  // most 1 (measured on the default bake: the table moves by ≤ 2e-5 relative against the earlier
  // three panels [0, U/16, U/4, U], whose first split changed nothing above float rounding).
  const int panels = s * tMax <= 1.0f ? 1 : 2;
  const float edges[3] = {0.0f, panels == 1 ? U : U / 4.0f, U};
  float sum = 0.0f;
  for (int p = 0; p < panels; ++p) {
    const float a = edges[p], w = edges[p + 1] - edges[p];
    Float4 part = {0.0f, 0.0f, 0.0f, 0.0f};
    for (int h = 0; h < 2; ++h) {  // four nodes at a time
      const Float4 u = a + w * g8.x[h];
      Float4 t = -logFloat4(1.0f - u) * invS;
      t = t < tMax ? t : Float4{tMax, tMax, tMax, tMax};
      Float4 perp = 1.0f - (p0 + t * (p1 + t * p2));
      perp = perp > 0.0f ? perp : Float4{0.0f, 0.0f, 0.0f, 0.0f};
      const Float4 root = sqrtFloat4(perp);
      Float4 sun = root - (fz + t * gz);
      sun = sun > 0.0f ? sun : Float4{0.0f, 0.0f, 0.0f, 0.0f};
      part += g8.w[h] * expFloat4(-s * sun);
    }
    sum += w * sumFloat4(part);
  }
  return sum;
}

namespace {
// Optical depth of the near part of a ray (attenuatedRayRule).
constexpr double kNearOpticalDepth = 6.0;

// Gauss–Legendre panels [edges[p], edges[p+1]] in u = 1 − e^{−σs}, pts[p] points each, appended
// as s = −ln(1 − u)/σ (at most `length`) with weights du: ∫ σe^{−σs} f ds = ∫ f du.
void appendAttenuationPanels(const double* edges, const int* pts, int panels, double sigma, double length,
                             std::vector<double>& s, std::vector<double>& w) {
  for (int p = 0; p < panels; ++p) {
    const GaussRule& g = gaussLegendre(pts[p]);
    const double a = edges[p], h = edges[p + 1] - edges[p];
    for (int k = 0; k < pts[p]; ++k) {
      const double u = a + h * g.x[k];
      s.push_back(std::min(-std::log1p(-u) / sigma, length));
      w.push_back(h * g.w[k]);
    }
  }
}
}  // namespace

void attenuatedRayRule(double sigma, double length, int total, std::vector<double>& s, std::vector<double>& w) {
  s.clear();
  w.clear();
  length = std::max(length, 0.0);
  const double tau = sigma * length;
  int pts[3];
  if (sigma >= kFarPanelMaxSigma) {
    // Dense: the far part carries nothing but a leak; all points in u (its far mass sits
    // within a few mean free paths, where it belongs for the diffusion modes).
    pts[0] = std::max(2, total / 4);
    pts[1] = std::max(2, total / 4);
    pts[2] = std::max(2, total - pts[0] - pts[1]);
    const double U = -std::expm1(-tau);
    const double edges[4] = {0.0, U / 16.0, U / 4.0, U};
    appendAttenuationPanels(edges, pts, 3, sigma, length, s, w);
    return;
  }
  pts[0] = std::max(2, total / 5);
  pts[2] = std::max(2, total / 4);
  pts[1] = std::max(2, total - pts[0] - pts[2]);
  const double tauNear = std::min(tau, kNearOpticalDepth);
  const double U1 = -std::expm1(-tauNear);
  const double edges[3] = {0.0, U1 / 8.0, U1};
  appendAttenuationPanels(edges, pts, 2, sigma, length, s, w);
  const GaussRule& g = gaussLegendre(pts[2]);
  const double s0 = tauNear / sigma, h = length - s0;
  const std::size_t first = w.size();
  double sum = 0.0;
  for (int k = 0; k < pts[2]; ++k) {
    const double sk = s0 + h * g.x[k];
    s.push_back(sk);
    w.push_back(tau > tauNear ? h * g.w[k] * sigma * std::exp(-sigma * sk) : 0.0);
    sum += w.back();
  }
  // The far weights must carry exactly the far mass e^{−τ_near} − e^{−τ}: conservation of the
  // discrete operator (a lost 10⁻³ per order would drain dense particles' slow modes).
  const double mass = tau > tauNear ? std::exp(-tauNear) - std::exp(-tau) : 0.0;
  if (sum > 0.0)
    for (std::size_t k = first; k < w.size(); ++k) w[k] *= mass / sum;
  else if (mass > 0.0)
    w[first] = mass;
}

}  // namespace cloudlut::bake
