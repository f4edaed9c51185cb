#pragma once
// The reference particle of the optical-depth table (seed §4.1, fig. 4): a normalised density
// ρ̂(p) ∈ [0, 1] on the unit ball, zero outside it. Extinction at p is σ·ρ·ρ̂(p) with
// σ = β·R in unit-sphere units and ρ the particle's density scale.
//
// Models:
//   sphere       ρ̂ = 1 (homogeneous)
//   radial       ρ̂ = (1 - r²)², the metaball fall-off alone
//   noise        fall-off modulated by fBm noise (the seed's "radial fall-off + 3D noise")
//   threshold    fBm noise pushed through a smooth threshold, faded out at the surface
//   pyroclastic  a sphere whose radius is displaced by turbulent noise, with a soft edge
// The three noise models are defined as the trilinear interpolation of the procedural density
// on a regular grid of `gridResolution`³ nodes spanning [-1, 1]³: that grid *is* the particle,
// so any integration of it can be checked against a finer integration of the same field.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "core/Float4.h"

namespace cloudlut {

enum class DensityModel { Noise, Threshold, Pyroclastic, Radial, Sphere };

std::optional<DensityModel> parseDensityModel(std::string_view name);
std::string toString(DensityModel model);

class ReferenceParticle {
 public:
  // 64³ nodes (spacing 1/31.5 of the radius) resolve the same detail as the default
  // 64×32×64×32 table and keep the grid (1 MiB) in a core's cache while chords are integrated.
  static constexpr int kDefaultGridResolution = 64;

  ReferenceParticle(DensityModel model, std::uint64_t seed,
                    int gridResolution = kDefaultGridResolution);

  DensityModel model() const { return model_; }
  std::uint64_t seed() const { return seed_; }
  int gridResolution() const { return res_; }
  bool isGridded() const { return !grid_.empty(); }

  // Normalised density ρ̂(p) ∈ [0, 1] (dimensionless); 0 outside the unit ball.
  float density(const glm::vec3& p) const {
    const float r2 = p.x * p.x + p.y * p.y + p.z * p.z;
    if (r2 > 1.0f) return 0.0f;
    switch (model_) {
      case DensityModel::Sphere: return 1.0f;
      case DensityModel::Radial: return radialFalloff(r2);
      default: return gridDensity<float, int>(p.x, p.y, p.z);
    }
  }

  // ρ̂ at four points (x, y, z per lane): density() lane by lane, bit for bit (the same
  // arithmetic in the same order, four lanes per instruction).
  Float4 density4(Float4 x, Float4 y, Float4 z) const { return densityLanes<Float4>(x, y, z); }

  // density4 for a float vector V of any width (Float8 in AVX2 code): the same per lane.
  // Always inlined, so a wide instance runs in its caller's instruction set (-Wpsabi: Float4.h).
  CLOUDLUT_WIDE_VECTORS_BEGIN
  template <class V>
  [[gnu::always_inline]] V densityLanes(V x, V y, V z) const {
    using I = decltype(x < x);
    const V r2 = x * x + y * y + z * z;
    V d;
    switch (model_) {
      case DensityModel::Sphere: d = V{} + 1.0f; break;
      case DensityModel::Radial:
        for (int k = 0; k < floatLanes<V>(); ++k) d[k] = radialFalloff(r2[k]);
        break;
      default: d = gridDensity<V, I>(x, y, z);
    }
    return r2 > 1.0f ? V{} : d;
  }
  CLOUDLUT_WIDE_VECTORS_END

  // The metaball fall-off (1 - r²)², r² = |p|² (dimensionless).
  static float radialFalloff(float r2) {
    const float a = 1.0f - r2;
    return a > 0.0f ? a * a : 0.0f;
  }

 private:
  // The trilinear interpolation of the grid at (x, y, z) ∈ [−1, 1]³, for one point (V float,
  // I int) or several (V a float vector, I its int vector); the lane helpers below differ only
  // in how they convert, clamp and fetch (the V argument only chooses the overload).
  CLOUDLUT_WIDE_VECTORS_BEGIN
  static int truncate(float v) { return static_cast<int>(v); }
  template <class V>
  [[gnu::always_inline]] static auto truncate(V v) {
    return __builtin_convertvector(v, decltype(v < v));
  }
  static float toFloat(int v, float) { return static_cast<float>(v); }
  template <class I, class V>
  [[gnu::always_inline]] static V toFloat(I v, V) {
    return __builtin_convertvector(v, V);
  }
  static int clampIndex(int i, int last) { return i < 0 ? 0 : (i > last ? last : i); }
  template <class I>
  [[gnu::always_inline]] static I clampIndex(I i, int last) {
    const I lo = I{}, hi = I{} + last;
    i = i < 0 ? lo : i;
    return i > last ? hi : i;
  }
  static float fetch(const float* c, int o, float) { return c[o]; }
  template <class I, class V>
  [[gnu::always_inline]] static V fetch(const float* c, I o, V) {
    V v;
    for (int k = 0; k < floatLanes<V>(); ++k) v[k] = c[o[k]];
    return v;
  }

  template <class V, class I>
  [[gnu::always_inline]] V gridDensity(V x, V y, V z) const {
    const float s = 0.5f * static_cast<float>(res_ - 1);
    const V gx = (x + 1.0f) * s, gy = (y + 1.0f) * s, gz = (z + 1.0f) * s;
    const int last = res_ - 2;
    const I ix = clampIndex(truncate(gx), last), iy = clampIndex(truncate(gy), last), iz = clampIndex(truncate(gz), last);
    const V fx = gx - toFloat(ix, V{}), fy = gy - toFloat(iy, V{}), fz = gz - toFloat(iz, V{});
    const int sy = res_, sz = res_ * res_;  // at most 1024³ nodes: offsets fit an int
    const I o = iz * sz + iy * sy + ix;
    const float* c = grid_.data();
    const V k{};
    const V c00 = fetch(c, o, k) + fx * (fetch(c + 1, o, k) - fetch(c, o, k));
    const V c10 = fetch(c + sy, o, k) + fx * (fetch(c + sy + 1, o, k) - fetch(c + sy, o, k));
    const V c01 = fetch(c + sz, o, k) + fx * (fetch(c + sz + 1, o, k) - fetch(c + sz, o, k));
    const V c11 = fetch(c + sz + sy, o, k) + fx * (fetch(c + sz + sy + 1, o, k) - fetch(c + sz + sy, o, k));
    const V c0 = c00 + fy * (c10 - c00), c1 = c01 + fy * (c11 - c01);
    return c0 + fz * (c1 - c0);
  }
CLOUDLUT_WIDE_VECTORS_END

  DensityModel model_;
  std::uint64_t seed_;
  int res_;
  std::vector<float> grid_;
};

}  // namespace cloudlut
