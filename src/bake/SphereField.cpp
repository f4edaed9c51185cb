#include "bake/SphereField.h"

#include <algorithm>
#include <cmath>

namespace cloudlut::bake {

namespace {
constexpr double kPi = 3.14159265358979323846;
}  // namespace

RadialAxis::RadialAxis(int nodes, double A, double linearShare)
    : n_(nodes), A_(A), alpha_(A > 1e-9 ? linearShare : 1.0), logA_(A > 1e-9 ? std::log1p(A) : 1.0) {
  // Node i: the depth δ with q(δ) = i/(n−1), by bisection.
  radii_.resize(static_cast<std::size_t>(n_));
  for (int i = 0; i < n_; ++i) {
    const double target = static_cast<double>(i) / (n_ - 1);
    double lo = 0.0, hi = 1.0;
    for (int it = 0; it < 80; ++it) {
      const double mid = 0.5 * (lo + hi);
      (qOfDepth(mid) < target ? lo : hi) = mid;
    }
    radii_[static_cast<std::size_t>(i)] = i == 0 ? 1.0 : (i == n_ - 1 ? 0.0 : 1.0 - 0.5 * (lo + hi));
  }
}

double RadialAxis::qOfDepth(double d) const {
  return A_ > 1e-9 ? alpha_ * d + (1.0 - alpha_) * std::log1p(A_ * d) / logA_ : d;
}

void RadialAxis::cubic(float r, int& start, float w[4]) const {
  const float d = std::clamp(1.0f - r, 0.0f, 1.0f);
  const float q = A_ > 1e-9 ? static_cast<float>(alpha_) * d +
                                  static_cast<float>((1.0 - alpha_) / logA_) * std::log(1.0f + static_cast<float>(A_) * d)
                            : d;
  cubicWeights(q * static_cast<float>(n_ - 1), n_, start, w);
}

SphereField::SphereField(int nr, int nt, double grading, double linearShare, double sigma,
                         const DirectionGrid& directions)
    : nr_(nr), nt_(nt), directions_(&directions), radial_(nr, grading * sigma, linearShare) {
  nodes_.resize(static_cast<std::size_t>(nodeCount()));
  for (int ir = 0; ir < nr_; ++ir)
    for (int it = 0; it < nt_; ++it) {
      const double r = radial_.radius(ir), th = kPi * it / (nt_ - 1);
      nodes_[static_cast<std::size_t>(ir * nt_ + it)] = r * glm::dvec3(std::sin(th), 0.0, std::cos(th));
    }
}

FieldPoint SphereField::locate(const glm::dvec3& y, const glm::dvec3& w, double wh) const {
  // Angles and the depth coordinate in single precision (float atan2 and log1p cost about half
  // of double; a node coordinate off by 1e-6 of a cell moves nothing that matters).
  FieldPoint p;
  const double rho2 = y.x * y.x + y.y * y.y;
  const float rho = static_cast<float>(std::sqrt(rho2));
  const float r = static_cast<float>(std::sqrt(rho2 + y.z * y.z));
  int ir, it, ib;
  radial_.cubic(r, ir, p.wr);
  cubicWeights(std::atan2(rho, static_cast<float>(y.z)) * static_cast<float>((nt_ - 1) / kPi), nt_, it, p.wt);
  // Relative azimuth of the direction about l, folded to [0, π].
  float phi = 0.0f;
  if (rho > 1e-12f && wh > 1e-12)
    phi = std::abs(std::atan2(static_cast<float>(w.y * y.x - w.x * y.y), static_cast<float>(w.x * y.x + w.y * y.y)));
  double fb;
  directions_->locatePhi(phi, ib, fb);
  p.fb = static_cast<float>(fb);
  p.offset = static_cast<std::size_t>(ir) * radialStride() + static_cast<std::size_t>(ib) * directionStride() +
             static_cast<std::size_t>(it);
  return p;
}

}  // namespace cloudlut::bake
