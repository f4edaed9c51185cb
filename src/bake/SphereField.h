#pragma once
// The volume grid of the fast multiple-scattering method (MultipleScattering.h) and the
// interpolation of a field on it.
//
// A field J(x, ω) inside the unit sphere lit along −l is symmetric about l, so it is stored
// in the meridian plane: nr depth-graded radial nodes × nt position-zenith nodes (the spatial
// nodes s = ir·nt + it) × the D directions of a light-frame DirectionGrid (d = a·nb + b).
// Value (s, d) sits at (ir·D + d)·nt + it: the position zenith is the fastest axis, so the four
// zenith nodes of an interpolation stencil are contiguous (one short vector per radial node
// and azimuth), and per radial node the field is a D × nt matrix (the phase convolution is one
// matrix product per radial node). A sample at any point y and direction w is rotated about l
// into the meridian plane and interpolated with quadratic-exact four-node weights in depth
// and in position zenith and linearly in the relative azimuth; the direction's zenith node is
// chosen by the caller (it is constant along a ray).
#include <algorithm>
#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

#include "bake/DirectionGrid.h"
#include "core/Float4.h"

namespace cloudlut::bake {

// Four-node interpolation weights at the continuous node coordinate x ∈ [0, n−1] of a uniform
// axis of n ≥ 4 nodes: nodes start … start+3, exact for quadratics — Catmull–Rom inside,
// three-point Lagrange in the first and last intervals. Linear interpolation of a curved field
// in an optically thick medium acts like extra diffusion (it widens every step of the random
// walk to the grid spacing); quadratic exactness removes that leading error.
// Inline: it runs for every point of every transport stencil.
inline void cubicWeights(float x, int n, int& start, float w[4]) {
  const int i = std::clamp(static_cast<int>(x), 0, n - 2);
  const float f = std::clamp(x - static_cast<float>(i), 0.0f, 1.0f);
  if (i == 0) {
    start = 0;
    w[0] = (f - 1) * (f - 2) / 2;
    w[1] = -f * (f - 2);
    w[2] = f * (f - 1) / 2;
    w[3] = 0.0f;
  } else if (i == n - 2) {
    start = n - 4;
    const float y = f + 1.0f;  // relative to node n − 3
    w[0] = 0.0f;
    w[1] = (y - 1) * (y - 2) / 2;
    w[2] = -y * (y - 2);
    w[3] = y * (y - 1) / 2;
  } else {
    start = i - 1;
    const float f2 = f * f, f3 = f2 * f;
    w[0] = (-f3 + 2 * f2 - f) / 2;
    w[1] = (3 * f3 - 5 * f2 + 2) / 2;
    w[2] = (-3 * f3 + 4 * f2 + f) / 2;
    w[3] = (f3 - f2) / 2;
  }
}

// Depth-graded radial axis: node i of n at q = i/(n−1), with
//   q(δ) = α δ + (1 − α) ln(1 + A δ) / ln(1 + A),   δ = 1 − r (depth below the surface):
// logarithmic near the surface (the boundary layer of the field is a few mean free paths thick,
// with a logarithmic-derivative profile) and at least α-linear in the interior.
class RadialAxis {
 public:
  RadialAxis(int nodes, double A, double linearShare);
  double radius(int i) const { return radii_[static_cast<std::size_t>(i)]; }
  // The continuous node coordinate q(1 − r)·(n − 1) at four radii r ∈ [0, 1] (single precision).
  Float4 coordinates(Float4 r) const;
  // The same at as many radii as V has lanes (Float8 in AVX2 code), lane for lane the same;
  // defined in SphereField.cpp, its only user.
  template <class V>
  V coordinatesLanes(V r) const;

 private:
  double qOfDepth(double d) const;
  int n_ = 2;
  double A_ = 0.0, alpha_ = 1.0, logA_ = 1.0;
  std::vector<double> radii_;
};

// Where a point and a direction fall in a field: the first node (radial start, zenith start,
// direction zenith 0, azimuth node b), four radial and four zenith weights and the azimuth
// fraction.
struct FieldPoint {
  std::size_t offset = 0;
  float wr[4] = {0, 0, 0, 0};
  float wt[4] = {0, 0, 0, 0};
  float fb = 0.0f;
};

// The terms wt[t] · Σ_c wr[c] · (p[c, t] + fb · (p[c, t, b+1] − p[c, t])), t = 0 … 3, for p
// pointing at the first node of the stencil (its direction already chosen): radial node c at
// p + c·strideR, zenith node t at p + t (contiguous), the next azimuth node at + strideB. Their
// sum (sumFloat4) is the field interpolated at the point.
inline Float4 interpolateFieldTerms(const float* p, std::size_t strideR, std::size_t strideB, const float wr[4],
                                    const float wt[4], float fb) {
  Float4 v = {0.0f, 0.0f, 0.0f, 0.0f};
  for (int c = 0; c < 4; ++c, p += strideR) {
    const Float4 a = loadFloat4(p), b = loadFloat4(p + strideB);
    v += wr[c] * (a + fb * (b - a));
  }
  return loadFloat4(wt) * v;
}

// The grid of one density slice (optical radius σ): layout, radial axis and node positions.
class SphereField {
 public:
  // nr radial nodes graded with A = grading·σ, nt position-zenith nodes over [0, π], the
  // directions of `directions`.
  SphereField(int nr, int nt, double grading, double linearShare, double sigma, const DirectionGrid& directions);

  int radialCount() const { return nr_; }
  int zenithCount() const { return nt_; }
  int nodeCount() const { return nr_ * nt_; }  // NS
  int directionCount() const { return directions_->count(); }  // D
  std::size_t size() const { return static_cast<std::size_t>(nodeCount()) * directionCount(); }
  // Offsets in the layout of the header comment: one radial node, one direction (d → d + 1).
  std::size_t radialStride() const { return static_cast<std::size_t>(nt_) * directionCount(); }
  std::size_t directionStride() const { return static_cast<std::size_t>(nt_); }
  // Index of value (spatial node s, direction d).
  std::size_t index(int s, int d) const {
    return (static_cast<std::size_t>(s / nt_) * directionCount() + static_cast<std::size_t>(d)) * nt_ +
           static_cast<std::size_t>(s % nt_);
  }
  const DirectionGrid& directions() const { return *directions_; }
  // Position of spatial node s = ir·nt + it in the meridian plane (y = 0).
  const glm::dvec3& node(int s) const { return nodes_[static_cast<std::size_t>(s)]; }

  // The interpolation stencil of the field at the point y (|y| ≤ 1) for the direction w, whose
  // length in the plane perpendicular to l is wh = hypot(w.x, w.y) (passed in: it is constant
  // along a ray). Its offset excludes the direction zenith: add a·nb·directionStride() for
  // zenith node a.
  FieldPoint locate(const glm::dvec3& y, const glm::dvec3& w, double wh) const;
  // locate at the n ≤ 4 points x − s[k]·w of one ray (their angles and depths four at a time).
  void locateRay(const glm::dvec3& x, const glm::dvec3& w, double wh, const double* s, int n, FieldPoint* out) const;
  // The same for n ≤ 8 points: eight lanes at once where the processor has AVX2, else two
  // locateRay calls (the same values either way).
  void locateRay8(const glm::dvec3& x, const glm::dvec3& w, double wh, const double* s, int n, FieldPoint* out) const;
  // locate(y[k], w, wh) at n ≤ 8 points for one direction (the same values), eight lanes at once
  // where the processor has AVX2.
  void locatePoints8(const glm::dvec3* y, const glm::dvec3& w, double wh, int n, FieldPoint* out) const;

 private:
  // The points x − s[k]·w, or y[k] − s[k]·w where origins y is given (then s holds zeros).
  template <class V>
  void locateRayLanes(const glm::dvec3& x, const glm::dvec3& w, double wh, const double* s, int n, FieldPoint* out,
                      const glm::dvec3* origins = nullptr) const;
  void locateRayAvx2(const glm::dvec3& x, const glm::dvec3& w, double wh, const double* s, int n, FieldPoint* out,
                     const glm::dvec3* origins) const;
  int nr_, nt_;
  const DirectionGrid* directions_;
  RadialAxis radial_;
  std::vector<glm::dvec3> nodes_;
};

}  // namespace cloudlut::bake
