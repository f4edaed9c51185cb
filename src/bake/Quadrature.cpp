#include "bake/Quadrature.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
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

namespace {

// What the fast sunlit-ray rule needs of one ray, in single precision (sunlitRayIntegralFast):
// with l's frame (e_z = l), the point at distance t is y = x + t d, its sun path d_sun = −y_z +
// √(1 − |y_⊥|²), |y_⊥|² = p0 + t (p1 + t p2); U = 1 − e^{−σ·length}; one or two panels in u.
struct SunlitRay {
  float p0, p1, p2, fz, gz, s, invS, tMax;
  int panels;
  float edges[3];
};

// The 8 Gauss nodes and weights of a panel on [0, 1] in single precision.
struct Gauss8 {
  float x[8], w[8];
};
const Gauss8& gauss8() {
  static const Gauss8 g8 = [] {
    const GaussRule& g = gaussLegendre(8);
    Gauss8 r{};
    for (int i = 0; i < 8; ++i) {
      r.x[i] = static_cast<float>(g.x[i]);
      r.w[i] = static_cast<float>(g.w[i]);
    }
    return r;
  }();
  return g8;
}

// The rule's sum, four Gauss nodes per SIMD step: per panel, lanes k and k + 4 are added first,
// then the four partial sums as (0 + 1) + (2 + 3) (sumFloat4).
float sunlitPanels4(const SunlitRay& q) {
  const Gauss8& g = gauss8();
  float sum = 0.0f;
  for (int p = 0; p < q.panels; ++p) {
    const float a = q.edges[p], w = q.edges[p + 1] - q.edges[p];
    Float4 part = {0.0f, 0.0f, 0.0f, 0.0f};
    for (int h = 0; h < 2; ++h) {  // four nodes at a time
      const Float4 u = a + w * loadFloat4(&g.x[4 * h]);
      Float4 t = -logFloat4(1.0f - u) * q.invS;
      t = t < q.tMax ? t : Float4{q.tMax, q.tMax, q.tMax, q.tMax};
      Float4 perp = 1.0f - (q.p0 + t * (q.p1 + t * q.p2));
      perp = perp > 0.0f ? perp : Float4{0.0f, 0.0f, 0.0f, 0.0f};
      const Float4 root = sqrtFloat4(perp);
      Float4 sun = root - (q.fz + t * q.gz);
      sun = sun > 0.0f ? sun : Float4{0.0f, 0.0f, 0.0f, 0.0f};
      part += loadFloat4(&g.w[4 * h]) * expFloat4(-q.s * sun);
    }
    sum += w * sumFloat4(part);
  }
  return sum;
}

#if CLOUDLUT_AVX2_LANES
// sunlitPanels4 with the eight nodes of a panel in one AVX2 vector: every lane by the same
// operations (no fused multiply-add), the same sums in the same order, so the same bits.
__attribute__((target("avx2"))) float sunlitPanels8(const SunlitRay& q) {
  using namespace float4_detail;
  const Gauss8& g = gauss8();
  Float8 gx, gw;
  std::memcpy(&gx, g.x, sizeof gx);
  std::memcpy(&gw, g.w, sizeof gw);
  float sum = 0.0f;
  for (int p = 0; p < q.panels; ++p) {
    const float a = q.edges[p], w = q.edges[p + 1] - q.edges[p];
    const Float8 u = a + w * gx;
    Float8 t = -logLanes(1.0f - u) * q.invS;
    t = t < q.tMax ? t : splatLanes<Float8>(q.tMax);
    Float8 perp = 1.0f - (q.p0 + t * (q.p1 + t * q.p2));
    perp = perp > 0.0f ? perp : splatLanes<Float8>(0.0f);
    const Float8 root = __builtin_ia32_sqrtps256(perp);
    Float8 sun = root - (q.fz + t * q.gz);
    sun = sun > 0.0f ? sun : splatLanes<Float8>(0.0f);
    const Float8 terms = gw * expLanes(-q.s * sun);
    const Float4 part = Float4{terms[0], terms[1], terms[2], terms[3]} + Float4{terms[4], terms[5], terms[6], terms[7]};
    sum += w * sumFloat4(part);
  }
  return sum;
}
#endif

}  // namespace

double sunlitRayIntegralFast(const glm::dvec3& x, const glm::dvec3& d, const glm::dvec3& l,
                             double sigma, double length) {
  if (!(length > 0.0) || !(sigma > 0.0)) return 0.0;
  // In single precision, by expFloat4, logFloat4 (their ~1e-7 is far below the rule's ~1e-3),
  // eight nodes at once where the processor has AVX2, four otherwise (the same bits).
  const double xz = glm::dot(x, l), dz = glm::dot(d, l);
  SunlitRay q;
  q.p0 = static_cast<float>(glm::dot(x, x) - xz * xz);
  q.p1 = static_cast<float>(2.0 * (glm::dot(x, d) - xz * dz));
  q.p2 = static_cast<float>(glm::dot(d, d) - dz * dz);
  q.fz = static_cast<float>(xz), q.gz = static_cast<float>(dz), q.s = static_cast<float>(sigma);
  q.invS = 1.0f / q.s, q.tMax = static_cast<float>(length);
  const float U = static_cast<float>(-std::expm1(-sigma * length));
  // Panels in u: [0, U/4] and [U/4, U]; one panel [0, U] when the ray's optical depth is at
  // most 1 (measured on the default bake: the table moves by ≤ 2e-5 relative against the earlier
  // three panels [0, U/16, U/4, U], whose first split changed nothing above float rounding).
  q.panels = q.s * q.tMax <= 1.0f ? 1 : 2;
  q.edges[0] = 0.0f;
  q.edges[1] = q.panels == 1 ? U : U / 4.0f;
  q.edges[2] = U;
#if CLOUDLUT_AVX2_LANES
  if (cpuHasAvx2Lanes()) return sunlitPanels8(q);
#endif
  return sunlitPanels4(q);
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
