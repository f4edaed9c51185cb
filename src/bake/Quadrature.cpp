#include "bake/Quadrature.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <mutex>
#include <stdexcept>

#include <glm/geometric.hpp>

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
  const GaussRule& g = gaussLegendre(8);
  const double U = -std::expm1(-sigma * length);
  const double edges[4] = {0.0, U / 16.0, U / 4.0, U};
  double sum = 0.0;
  for (int p = 0; p < 3; ++p) {
    const double a = edges[p], w = edges[p + 1] - edges[p];
    for (int i = 0; i < 8; ++i) {
      const double u = a + w * g.x[i];
      const double t = -std::log1p(-u) / sigma;
      sum += w * g.w[i] * std::exp(-sigma * sunPath(x + t * d, l));
    }
  }
  return sum;
}

}  // namespace cloudlut::bake
