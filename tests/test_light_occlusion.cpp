// Light-space occlusion binned on the GPU (render/LightOcclusion.h): for a layer of many
// particles (a grid above its minimum size), every particle's sunlight equals exp(−ξ Σ τ) of the
// brute-force sum over all other particles computed on the CPU (the bins are conservative, so
// none is missed), and the result does not depend on the order of the particle list.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include "core/TableLookup.h"
#include "render/GlContext.h"
#include "render/LightOcclusion.h"
#include "render/Renderer.h"
#include "support/CliRunner.h"
#include "support/RenderLuts.h"

using namespace cloudlut;
using namespace cloudlut::render;
using namespace cloudlut::scene;
using namespace cloudlut::test;

namespace {

// `count` ellipsoids (semi-axes 0.4–1.6, random rotation, density 0.2–2) uniform in a layer
// `side` × 6 × `side` (world units), fixed seed.
std::vector<Particle> layer(std::size_t count, float side) {
  std::mt19937 rng(2024u);
  std::uniform_real_distribution<float> across(-0.5f * side, 0.5f * side), up(0.0f, 6.0f), axis(0.4f, 1.6f),
      angle(0.0f, 360.0f), rho(0.2f, 2.0f);
  std::vector<Particle> ps(count);
  for (Particle& p : ps) {
    p.center = {across(rng), up(rng), across(rng)};
    p.radii = {axis(rng), axis(rng), axis(rng)};
    p.rotation = quatFromEulerDegrees({angle(rng), angle(rng), angle(rng)});
    p.density = rho(rng);
  }
  return ps;
}

// exp(−ξ Σ_j τ_j): the ray from particle i's centre toward the sun `l` through every other
// particle j, τ_j = ρ_j σ · (chord in unit-sphere units) · |toParticle_j · l| (double precision).
double bruteForceSunlight(const std::vector<Particle>& ps, std::size_t i, const glm::vec3& l, double sigma) {
  double tau = 0.0;
  for (std::size_t j = 0; j < ps.size(); ++j) {
    if (j == i) continue;
    const glm::dmat3 inv = glm::dmat3(ps[j].toParticle());
    const glm::dvec3 o = inv * glm::dvec3(ps[i].center - ps[j].center), d = inv * glm::dvec3(l);
    const double a = glm::dot(d, d), b = glm::dot(o, d), c = glm::dot(o, o) - 1.0;
    const double disc = b * b - a * c;
    if (disc <= 0) continue;
    const double t0 = std::max(0.0, (-b - std::sqrt(disc)) / a), t1 = (-b + std::sqrt(disc)) / a;
    if (t1 > t0) tau += ps[j].density * sigma * (t1 - t0) * std::sqrt(a);
  }
  return std::exp(-kOcclusionXi * tau);
}

}  // namespace

TEST_CASE("light occlusion: binned sunlight of 20000 particles equals the brute-force sum, in any list order",
          "[render][occlusion]") {
  TempDir tmp;
  writeSyntheticLutSet(tmp / "luts");
  const io::LutSet luts = io::readLutSet(tmp / "luts");
  const double sigma = unitOpticalRadius(luts.tables.at("optical_depth").table);
  auto context = createHeadlessContext();
  Renderer renderer(*context, luts);
  RenderSettings s;
  s.width = 32;
  s.height = 32;
  s.view.lighting.sunDirection = glm::normalize(glm::vec3(0.5f, 0.8f, 0.3f));
  s.smoothOcclusion = false;
  const std::size_t n = 20000;
  REQUIRE(lightTilesFor(n) > kLightTiles);  // the grid grows with the count here
  const std::vector<Particle> ps = layer(n, 120.0f);
  const std::vector<float> sun = renderer.sunlight(ps, s);
  REQUIRE(sun.size() == n);

  double worst = 0.0;
  int shadowed = 0;
  for (std::size_t i = 0; i < n; i += 40) {  // 500 particles against all 20000
    const double expected = bruteForceSunlight(ps, i, s.view.lighting.sunDirection, sigma);
    shadowed += expected < 0.9;
    worst = std::max(worst, std::abs(double(sun[i]) - expected) / expected);
  }
  std::printf("[light occlusion] %zu particles, %d tiles per side: %d of 500 shadowed below 0.9, max relative "
              "difference to brute force %.2e\n",
              n, lightTilesFor(n), shadowed, worst);
  CHECK(shadowed > 100);
  CHECK(worst < 1e-3);

  // The list reversed: the same sunlight per particle, bit for bit, with and without smoothing.
  const std::vector<Particle> reversed(ps.rbegin(), ps.rend());
  for (const bool smooth : {false, true}) {
    INFO("smoothing " << smooth);
    s.smoothOcclusion = smooth;
    const std::vector<float> forward = renderer.sunlight(ps, s), backward = renderer.sunlight(reversed, s);
    std::size_t mismatches = 0;
    for (std::size_t i = 0; i < n; ++i) mismatches += forward[i] != backward[n - 1 - i];
    CHECK(mismatches == 0);
  }
}
