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

// Float8 instances below run only inside SphereField::locateRayAvx2 (-Wpsabi: Float4.h).

template <class V>
[[gnu::always_inline]] inline V RadialAxis::coordinatesLanes(V r) const {
  V d = 1.0f - r;
  d = d < 0.0f ? V{} : d;
  d = d > 1.0f ? V{} + 1.0f : d;
  const V q = A_ > 1e-9 ? static_cast<float>(alpha_) * d +
                              static_cast<float>((1.0 - alpha_) / logA_) *
                                  float4_detail::logLanes(1.0f + static_cast<float>(A_) * d)
                        : d;
  return q * static_cast<float>(n_ - 1);
}

Float4 RadialAxis::coordinates(Float4 r) const { return coordinatesLanes(r); }

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
  const double zero = 0.0;
  FieldPoint p;
  locateRay(y, w, wh, &zero, 1, &p);
  return p;
}

namespace {
// cubicWeights at every lane of x: the same operations lane by lane (each of its three cases
// computed and the lane's own chosen), so the same bits; start per lane in `start`, weight c of
// lane k in w[c][k].
template <class V>
[[gnu::always_inline]] inline void cubicWeightsLanes(V x, int n, decltype(V{} < V{})& start, V w[4]) {
  using I = decltype(V{} < V{});
  I i = __builtin_convertvector(x, I);
  i = i < 0 ? I{} : i;
  i = i > n - 2 ? I{} + (n - 2) : i;
  V f = x - __builtin_convertvector(i, V);
  f = f < 0.0f ? V{} : f;
  f = 1.0f < f ? V{} + 1.0f : f;
  const I first = i == 0, last = i == n - 2;
  const V y = f + 1.0f;  // relative to node n − 3
  const V f2 = f * f, f3 = f2 * f;
  const V m0 = (-f3 + 2 * f2 - f) / 2, m1 = (3 * f3 - 5 * f2 + 2) / 2, m2 = (-3 * f3 + 4 * f2 + f) / 2,
          m3 = (f3 - f2) / 2;
  const V a0 = (f - 1) * (f - 2) / 2, a1 = -f * (f - 2), a2 = f * (f - 1) / 2;
  const V b1 = (y - 1) * (y - 2) / 2, b2 = -y * (y - 2), b3 = y * (y - 1) / 2;
  w[0] = first ? a0 : (last ? V{} : m0);
  w[1] = first ? a1 : (last ? b1 : m1);
  w[2] = first ? a2 : (last ? b2 : m2);
  w[3] = first ? V{} : (last ? b3 : m3);
  start = first ? I{} : (last ? I{} + (n - 4) : i - 1);
}
}  // namespace

template <class V>
[[gnu::always_inline]] inline void SphereField::locateRayLanes(const glm::dvec3& x, const glm::dvec3& w, double wh,
                                                               const double* s, int n, FieldPoint* out,
                                                               const glm::dvec3* origins) const {
  // The points in double, their angles and depth coordinates in single precision, as many
  // lanes at once as V has (a node coordinate off by 1e-6 of a cell moves nothing that
  // matters); unused lanes repeat the last point.
  constexpr int N = floatLanes<V>();
  V rho, z, r, num, den;
  for (int k = 0; k < N; ++k) {
    const int kk = std::min(k, n - 1);
    const double sk = s[kk];
    const glm::dvec3 y = (origins ? origins[kk] : x) - sk * w;
    const double rho2 = y.x * y.x + y.y * y.y;
    rho[k] = static_cast<float>(std::sqrt(rho2));
    r[k] = static_cast<float>(std::sqrt(rho2 + y.z * y.z));
    z[k] = static_cast<float>(y.z);
    // the relative azimuth of the direction about l: atan2(w × y · l, w_h · y_h)
    num[k] = static_cast<float>(w.y * y.x - w.x * y.y);
    den[k] = static_cast<float>(w.x * y.x + w.y * y.y);
  }
  const V qr = radial_.coordinatesLanes(r);
  const V qt = float4_detail::atan2Lanes(rho, z) * static_cast<float>((nt_ - 1) / kPi);
  const V phi = float4_detail::atan2Lanes(num, den);
  using I = decltype(V{} < V{});
  I irs, its;
  V wr[4], wt[4];
  cubicWeightsLanes(qr, nr_, irs, wr);
  cubicWeightsLanes(qt, nt_, its, wt);
  for (int k = 0; k < n; ++k) {
    FieldPoint& p = out[k];
    const int ir = irs[k], it = its[k];
    int ib;
    for (int c = 0; c < 4; ++c) {
      p.wr[c] = wr[c][k];
      p.wt[c] = wt[c][k];
    }
    // folded to [0, π]; 0 on the axis or for a direction along l
    const float phik = rho[k] > 1e-12f && wh > 1e-12 ? std::abs(phi[k]) : 0.0f;
    double fb;
    directions_->locatePhi(phik, ib, fb);
    p.fb = static_cast<float>(fb);
    p.offset = static_cast<std::size_t>(ir) * radialStride() + static_cast<std::size_t>(ib) * directionStride() +
               static_cast<std::size_t>(it);
  }
}

void SphereField::locateRay(const glm::dvec3& x, const glm::dvec3& w, double wh, const double* s, int n,
                            FieldPoint* out) const {
  locateRayLanes<Float4>(x, w, wh, s, n, out);
}

#if CLOUDLUT_AVX2_LANES
__attribute__((target("avx2"))) void SphereField::locateRayAvx2(const glm::dvec3& x, const glm::dvec3& w, double wh,
                                                                const double* s, int n, FieldPoint* out,
                                                                const glm::dvec3* origins) const {
  locateRayLanes<Float8>(x, w, wh, s, n, out, origins);
}
#endif

void SphereField::locateRay8(const glm::dvec3& x, const glm::dvec3& w, double wh, const double* s, int n,
                             FieldPoint* out) const {
#if CLOUDLUT_AVX2_LANES
  if (cpuHasAvx2Lanes()) return locateRayAvx2(x, w, wh, s, n, out, nullptr);
#endif
  locateRayLanes<Float4>(x, w, wh, s, std::min(n, 4), out);
  if (n > 4) locateRayLanes<Float4>(x, w, wh, s + 4, n - 4, out + 4);
}

void SphereField::locatePoints8(const glm::dvec3* y, const glm::dvec3& w, double wh, int n, FieldPoint* out) const {
  // locate(y, w, wh) reads the point y − 0·w: the same zeros here, so the same bits.
  const double zeros[8] = {};
#if CLOUDLUT_AVX2_LANES
  if (cpuHasAvx2Lanes()) return locateRayAvx2(y[0], w, wh, zeros, n, out, y);
#endif
  locateRayLanes<Float4>(y[0], w, wh, zeros, std::min(n, 4), out, y);
  if (n > 4) locateRayLanes<Float4>(y[4], w, wh, zeros, n - 4, out + 4, y + 4);
}

}  // namespace cloudlut::bake
