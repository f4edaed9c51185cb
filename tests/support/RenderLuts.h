#pragma once
// LUT sets for the renderer's tests, built without the scattering baker: the optical-depth
// table is baked (small, through bake::bakeOpticalDepth) and the single- and
// multiple-scattering tables are smooth synthetic functions on the documented axes
// (θS, φv, θv, log2 ρ) — the renderer's job is to reproduce the lookup, whatever the values.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <string>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "bake/OpticalDepthBaker.h"
#include "core/Defaults.h"
#include "core/Glsl.h"
#include "core/ReferenceParticle.h"
#include "core/Table4D.h"
#include "core/TableLookup.h"
#include "io/LutIo.h"
#include "scene/Scene.h"

namespace cloudlut::test {

inline constexpr double kPi = 3.14159265358979323846;

// A scattering table over (θS, φv, θv, log2 ρ ∈ [-4, 3]) whose mean source is value(θS, φv,
// θv, s), stored as the tables store it (cloudlut_shading.glsl), on a θS axis with
// concentrated nodes (warp 3) so that the renderer's handling of the warp is exercised.
// The values are consistent at the poles (θS = 0, π; θv = 0) and periodic in φv.
template <typename F>
Table4D syntheticScatteringTable(const std::string& name, const std::array<int, 4>& dims, F value) {
  const bool single = name == "single_scattering";
  std::array<Axis, 4> axes = {Axis{"theta_s", "rad", 0.0, kPi, dims[0], false, 3.0},
                              Axis{"phi_v", "rad", 0.0, 2.0 * kPi, dims[1], true},
                              Axis{"theta_v", "rad", 0.0, 0.5 * kPi, dims[2], false},
                              Axis{"log2_density", "log2", -4.0, 3.0, dims[3], false}};
  Table4D t(name, axes, {Channel{single ? kSingleScatteringChannel : kMultipleScatteringChannel, "synthetic mean source"}});
  for (int i3 = 0; i3 < dims[3]; ++i3)
    for (int i2 = 0; i2 < dims[2]; ++i2)
      for (int i1 = 0; i1 < dims[1]; ++i1)
        for (int i0 = 0; i0 < dims[0]; ++i0) {
          const float j = static_cast<float>(value(axes[0].value(i0), axes[1].value(i1), axes[2].value(i2), axes[3].value(i3)));
          t.at(t.index(i0, i1, i2, i3), 0) = single ? glsl::singleScatteringToTable(j) : j;
        }
  // built first, then moved in: clang 14 leaks the old value of `json& = {init-list}`
  nlohmann::json parameters = {{"extinction_per_m", defaults::kExtinctionPerMetre},
                               {"radius_m", defaults::kParticleRadiusMetres},
                               {"synthetic", true}};
  t.parameters() = std::move(parameters);
  return t;
}

inline Table4D syntheticSingle(const std::array<int, 4>& dims = {16, 24, 8, 8}) {
  Table4D t = syntheticScatteringTable("single_scattering", dims, [](double ts, double pv, double tv, double s) {
    return 0.05 * std::exp2(0.25 * s) * (1.0 + 0.4 * std::cos(ts) + 0.3 * std::sin(ts) * std::sin(tv) * std::cos(pv)) *
           (0.6 + 0.4 * std::cos(tv));
  });
  t.parameters()["first_phase"] = {{"kind", 2}, {"param", 0.9}};
  return t;
}

inline Table4D syntheticMultiple(const std::array<int, 4>& dims = {16, 24, 8, 8}) {
  Table4D t = syntheticScatteringTable("multiple_scattering", dims, [](double ts, double pv, double tv, double s) {
    return 0.08 * (1.0 + 0.5 * std::tanh(0.5 * s)) *
           (1.0 + 0.5 * std::cos(ts) + 0.2 * std::sin(ts) * std::sin(tv) * std::cos(pv)) * (0.7 + 0.3 * std::cos(tv));
  });
  return t;
}

inline Table4D smallOpticalDepth(DensityModel model = DensityModel::Radial,
                                 const std::array<int, 4>& dims = {24, 12, 24, 12}) {
  bake::OpticalDepthSettings s;
  s.dims = dims;
  return bake::bakeOpticalDepth(ReferenceParticle(model, 1), s);
}

// Writes manifest.json and one float binary file per table into `dir` (created).
inline void writeLutSet(const std::filesystem::path& dir, const std::vector<const Table4D*>& tables) {
  std::filesystem::create_directories(dir);
  nlohmann::json entries = nlohmann::json::object();
  for (const Table4D* t : tables) {
    const std::string file = t->name() + ".bin";
    io::writeBinaryLut(*t, io::SampleType::Float, dir / file);
    nlohmann::json entry = io::describeTable(*t, io::SampleType::Float);
    entry["files"] = {{"bin", file}};
    entries[t->name()] = entry;
  }
  io::writeManifest(dir, {{"format", "cloudlut-lut-set"}, {"version", 1}, {"generator", "cloudlut tests"},
                          {"tables", entries}});
}

// The standard synthetic set: radial optical depth + synthetic single and multiple tables.
inline void writeSyntheticLutSet(const std::filesystem::path& dir, DensityModel model = DensityModel::Radial) {
  const Table4D od = smallOpticalDepth(model), l1 = syntheticSingle(), lm = syntheticMultiple();
  writeLutSet(dir, {&od, &l1, &lm});
}

// The ray against a particle in its unit-sphere space, computed independently of the shader.
struct Hit {
  bool hit = false;
  float tEnter = 0, tExit = 0;
  glm::vec3 S{0.0f}, v{0.0f};
  float closest = 0;  // distance of the ray from the centre in particle space (1 = grazing)
};

// The ray (eye, unit dir) against the particle, scaled by `inflate`, in its unit-sphere space.
inline Hit intersect(const scene::Particle& p, const glm::vec3& eye, const glm::vec3& dir, float inflate = 1.0f) {
  const glm::mat3 inv = p.toParticle();
  const glm::vec3 o = inv * (eye - p.center) / inflate, d = inv * dir / inflate;
  const double a = glm::dot(d, d), b = glm::dot(o, d), c = double(glm::dot(o, o)) - 1.0;
  Hit h;
  h.closest = static_cast<float>(std::sqrt(std::max(0.0, double(glm::dot(o, o)) - b * b / a)));
  const double disc = b * b - a * c;
  if (c <= 0 || b >= 0 || disc <= 0) return h;
  const double q = -b + std::sqrt(disc);
  h.hit = true;
  h.tEnter = static_cast<float>(c / q);
  h.tExit = static_cast<float>(q / a);
  h.S = glm::normalize(o + h.tEnter * d);
  h.v = glm::normalize(d);
  return h;
}

}  // namespace cloudlut::test
