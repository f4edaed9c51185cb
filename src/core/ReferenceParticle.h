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
      default: return gridDensity(p);
    }
  }

  // The metaball fall-off (1 - r²)², r² = |p|² (dimensionless).
  static float radialFalloff(float r2) {
    const float a = 1.0f - r2;
    return a > 0.0f ? a * a : 0.0f;
  }

 private:
  float gridDensity(const glm::vec3& p) const {
    const float s = 0.5f * static_cast<float>(res_ - 1);
    const float gx = (p.x + 1.0f) * s, gy = (p.y + 1.0f) * s, gz = (p.z + 1.0f) * s;
    const int last = res_ - 2;
    int ix = static_cast<int>(gx), iy = static_cast<int>(gy), iz = static_cast<int>(gz);
    ix = ix < 0 ? 0 : (ix > last ? last : ix);
    iy = iy < 0 ? 0 : (iy > last ? last : iy);
    iz = iz < 0 ? 0 : (iz > last ? last : iz);
    const float fx = gx - static_cast<float>(ix), fy = gy - static_cast<float>(iy),
                fz = gz - static_cast<float>(iz);
    const std::size_t sy = static_cast<std::size_t>(res_), sz = sy * sy;
    const float* c = grid_.data() + (iz * sz + iy * sy + ix);
    const float c00 = c[0] + fx * (c[1] - c[0]);
    const float c10 = c[sy] + fx * (c[sy + 1] - c[sy]);
    const float c01 = c[sz] + fx * (c[sz + 1] - c[sz]);
    const float c11 = c[sz + sy] + fx * (c[sz + sy + 1] - c[sz + sy]);
    const float c0 = c00 + fy * (c10 - c00), c1 = c01 + fy * (c11 - c01);
    return c0 + fz * (c1 - c0);
  }

  DensityModel model_;
  std::uint64_t seed_;
  int res_;
  std::vector<float> grid_;
};

}  // namespace cloudlut
