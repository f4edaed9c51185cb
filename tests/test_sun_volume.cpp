// The sun optical-depth volume (render/SunVolume, docs/LIGHTING.md) against a direct CPU
// integration of the reference particle's density along the same sun rays: at every node that
// lies outside all particles, the volume's τ toward the sun must equal Σ ∫ ρ σ ρ̂(M⁻¹(x − c)) |M⁻¹ ds|
// over the particles in front of it. The splat builds τ from the optical-depth table's chords;
// the integration here samples the density itself (1/256 of a radius per step), so the two
// share nothing but the particle.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <glm/geometric.hpp>

#include "render/Renderer.h"
#include "scene/Scene.h"
#include "support/SunRays.h"

using namespace cloudlut;
using namespace cloudlut::test;

namespace {

// Four noise particles (radius 1, ρ = 1) side by side across the beam of the unit sun direction
// `sun` (no column crosses two), turned apart.
std::vector<scene::Particle> fourParticlesAcross(const glm::vec3& sun) {
  const glm::vec3 across = glm::normalize(glm::cross(sun, glm::vec3(0.0f, 0.0f, 1.0f)));
  const glm::vec3 across2 = glm::cross(sun, across);
  std::vector<scene::Particle> particles(4);
  for (int n = 0; n < 4; ++n) {
    particles[n].center = 2.5f * (static_cast<float>(n & 1) * across + static_cast<float>(n >> 1) * across2);
    particles[n].radii = glm::vec3(1.0f);
    particles[n].density = 1.0f;
    const float turn = static_cast<float>(n);
    particles[n].rotation = scene::quatFromEulerDegrees({37.0f * turn, 71.0f * turn, -23.0f * turn});
  }
  return particles;
}

// The sun volume of fourParticlesAcross under the sun direction (0.3, 0.9, −0.2), visited at
// every node within `radius` (particle space) of a particle's centre: visit(reference particle,
// the particles, σ, the grid's unit sun direction, the node's world point, the volume's τ there).
template <class Visit>
void visitNodesInsideFourParticles(float radius, Visit visit) {
  SunVolumeRig rig;
  render::RenderSettings rs;
  rs.view.lighting.sunDirection = glm::normalize(glm::vec3(0.3f, 0.9f, -0.2f));
  const std::vector<scene::Particle> particles = fourParticlesAcross(rs.view.lighting.sunDirection);
  const render::Renderer::SunVolumeSnapshot v = rig.renderer->sunVolume(particles, rs);
  const render::SunVolumeGrid& g = v.grid;
  REQUIRE(g.cascades == 1);
  const double sigma = rig.medium.unitOpticalRadius();
  for (int k = 0; k < g.dims.z; ++k)
    for (int j = 0; j < g.dims.y; ++j)
      for (int i = 0; i < g.dims.x; ++i) {
        const glm::vec3 x = glm::vec3(g.toWorld[0] * glm::vec4(i, j, k, 1.0f));
        bool inside = false;
        for (const scene::Particle& p : particles) inside = inside || glm::length(p.toParticle() * (x - p.center)) < radius;
        if (inside) visit(rig.ref, particles, sigma, g.sun, x, v.tau[(static_cast<std::size_t>(k) * g.dims.y + j) * g.dims.x + i]);
      }
}

}  // namespace

TEST_CASE("sun volume: optical depth toward the sun matches the density integrated along the sun rays",
          "[render][lighting]") {
  SunVolumeRig rig;

  // Three particles in a row under a slanted sun, one rotated ellipsoid, so that columns cross
  // one, two or three of them.
  std::vector<scene::Particle> particles(3);
  particles[0].center = {0.0f, 0.0f, 0.0f};
  particles[0].radii = glm::vec3(1.0f);
  particles[0].density = 1.0f;
  particles[1].center = {0.5f, 1.2f, 0.3f};
  particles[1].radii = glm::vec3(0.8f);
  particles[1].density = 0.6f;
  particles[2].center = {1.1f, 2.3f, 0.2f};
  particles[2].radii = {1.0f, 0.6f, 0.8f};
  particles[2].rotation = scene::quatFromEulerDegrees({25.0f, 40.0f, -15.0f});
  particles[2].density = 1.5f;
  render::RenderSettings rs;
  rs.view.lighting.sunDirection = glm::normalize(glm::vec3(0.4f, 0.85f, 0.2f));
  const render::Renderer::SunVolumeSnapshot v = rig.renderer->sunVolume(particles, rs);
  const render::SunVolumeGrid& g = v.grid;
  REQUIRE(g.cascades == 1);
  REQUIRE(v.tau.size() == static_cast<std::size_t>(g.dims.x) * g.dims.y * g.dims.z);
  const double sigma = rig.medium.unitOpticalRadius();

  int compared = 0, within = 0, dense = 0;
  double worst = 0;
  for (int k = 0; k < g.dims.z; k += 2)
    for (int j = 0; j < g.dims.y; j += 2)
      for (int i = 0; i < g.dims.x; i += 2) {
        const glm::vec3 x = glm::vec3(g.toWorld[0] * glm::vec4(i, j, k, 1.0f));
        bool outside = true;
        for (const scene::Particle& p : particles)
          if (glm::length(p.toParticle() * (x - p.center)) < 1.02f) outside = false;
        if (!outside) continue;
        const double expected = integratedSunDepth(particles, rig.ref, sigma, x, g.sun);
        const double got = v.tau[(static_cast<std::size_t>(k) * g.dims.y + j) * g.dims.x + i];
        const double error = std::abs(got - expected);
        ++compared;
        if (expected > 1.0) ++dense;
        // table interpolation across the particles' edges: 3% of τ, plus 0.05 absolute
        if (error <= 0.03 * expected + 0.05) ++within;
        worst = std::max(worst, error / (expected + 1.0));
      }
  INFO("nodes compared " << compared << ", with tau > 1: " << dense << ", within: " << within
                         << ", worst |error|/(tau + 1) " << worst);
  REQUIRE(compared > 1000);
  REQUIRE(dense > 40);
  CHECK(within >= 0.98 * compared);
  CHECK(worst < 0.15);
}

TEST_CASE("sun volume: a low sun's cascades over a cloud layer hold every particle and match the integration",
          "[render][lighting]") {
  SunVolumeRig rig;

  // A 4 × 4 patch of overlapping unit particles in a layer y ∈ [1.8, 5.2], one of them a rotated
  // ellipsoid, under a sun 4° above the horizon: on a square grid of 0.1-unit columns a particle's
  // shadow would cover 20 × 287 columns, over the footprint limit of the finest cascade.
  std::vector<scene::Particle> particles;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      scene::Particle p;
      p.center = {1.5f * static_cast<float>(i) - 2.25f, 3.2f + 0.3f * static_cast<float>((i + j) % 3),
                  1.5f * static_cast<float>(j) - 2.25f};
      p.radii = glm::vec3(1.0f);
      p.density = 0.5f + 0.25f * static_cast<float>((i * 3 + j) % 4);
      particles.push_back(p);
    }
  particles[5].radii = {1.0f, 0.6f, 0.8f};
  particles[5].rotation = scene::quatFromEulerDegrees({25.0f, 40.0f, -15.0f});
  const float elevation = 4.0f * 3.14159265f / 180.0f;
  const glm::vec3 sun(std::cos(elevation) * 0.8f, std::sin(elevation), std::cos(elevation) * 0.6f);
  render::RenderSettings rs;
  rs.view.lighting.sunDirection = sun;
  const render::SunVolumeGrid layer = render::sunVolumeGridForLayer(glm::vec3(0.0f, 3.5f, 0.0f), 1.8f, 5.2f, sun, 0.1f, 3);
  const render::Renderer::SunVolumeSnapshot v = rig.renderer->sunVolume(particles, rs, &layer);
  const render::SunVolumeGrid& g = v.grid;
  REQUIRE(g.cascades == 3);
  CHECK(v.footprintOverflow == 0);
  const std::size_t perCascade = static_cast<std::size_t>(g.dims.x) * g.dims.y * g.dims.z;
  REQUIRE(v.tau.size() == perCascade * 3);
  const double sigma = rig.medium.unitOpticalRadius();
  for (int c = 0; c < g.cascades; ++c) {
    int compared = 0, within = 0, dense = 0;
    double worst = 0, worstExpected = 0, worstGot = 0;
    glm::ivec3 worstNode(0);
    const int step = c + 1 < g.cascades ? 3 : 1;  // the coarsest cascade: every column
    for (int k = 0; k < g.dims.z; k += 2)
      for (int j = 0; j < g.dims.y; j += step)
        for (int i = 0; i < g.dims.x; i += step) {
          const glm::vec3 x = glm::vec3(g.toWorld[c] * glm::vec4(i, j, k, 1.0f));
          bool outside = true;
          for (const scene::Particle& p : particles)
            if (glm::length(p.toParticle() * (x - p.center)) < 1.02f) outside = false;
          if (!outside) continue;
          const double expected = integratedSunDepth(particles, rig.ref, sigma, x, g.sun);
          const double got = v.tau[perCascade * c + (static_cast<std::size_t>(k) * g.dims.y + j) * g.dims.x + i];
          const double error = std::abs(got - expected);
          ++compared;
          if (expected > 1.0) ++dense;
          if (error <= 0.03 * expected + 0.05) ++within;
          if (error / (expected + 1.0) > worst) {
            worst = error / (expected + 1.0);
            worstExpected = expected;
            worstGot = got;
            worstNode = {i, j, k};
          }
        }
    INFO("cascade " << c << ": nodes compared " << compared << ", with tau > 1: " << dense << ", within: " << within
                    << ", worst |error|/(tau + 1) " << worst << " at node " << worstNode.x << ","
                    << worstNode.y << "," << worstNode.z << ": " << worstGot << " for " << worstExpected);
    CHECK(dense > 40);
    CHECK(within >= 0.98 * compared);
    // A handful of columns graze a particle where the optical-depth table (32 θv nodes) rounds a
    // thin chord's τ ≈ 0.3 to 0; under the low sun more columns graze than in the test above.
    CHECK(worst < 0.35);
  }
}

TEST_CASE("sun volume: past a particle's last matter its whole chord lies toward the sun", "[render][lighting]") {
  // Inside a noise particle, between the last matter of a sun ray's chord and the particle's
  // edge, the density integrated from the node away from the sun is zero: all the chord's
  // matter lies toward the sun, so the volume must hold the whole chord there. (The ramp used to
  // run on to the edge, short of the chord there by up to the outskirts' share of it.)
  int compared = 0, within = 0;
  double worst = 0;
  visitNodesInsideFourParticles(0.98f, [&](const ReferenceParticle& ref, const std::vector<scene::Particle>& particles,
                                           double sigma, const glm::vec3& sun, const glm::vec3& x, double got) {
    if (integratedSunDepth(particles, ref, sigma, x, -sun) > 1e-3) return;  // matter away from the sun
    const double expected = integratedSunDepth(particles, ref, sigma, x, sun);
    if (expected < 0.5) return;  // a chord with matter enough to tell
    ++compared;
    if (std::abs(got - expected) <= 0.03 * expected + 0.05) ++within;
    worst = std::max(worst, std::abs(got - expected) / expected);
  });
  INFO("nodes past the last matter " << compared << ", within 3% + 0.05: " << within << ", worst relative " << worst);
  REQUIRE(compared > 50);
  CHECK(within >= 0.95 * compared);
}

TEST_CASE("sun volume: inside a particle the volume lays the chord's matter where the particle holds it",
          "[render][lighting]") {
  // Inside a noise particle, with matter both toward and away from the sun, the volume's τ toward
  // the sun against the density integrated from the node toward the sun. The particle's matter
  // is densest at its centre (the metaball fall-off, core/ReferenceParticle.h); a chord laid
  // evenly from its first matter to its last puts too much of it near its ends (relative RMS
  // error 10.1% here), laid by the table's chord_outer_third_share (chordMatterShare) 6.1%.
  int compared = 0;
  double squared = 0, reference = 0;
  visitNodesInsideFourParticles(0.9f, [&](const ReferenceParticle& ref, const std::vector<scene::Particle>& particles,
                                          double sigma, const glm::vec3& sun, const glm::vec3& x, double got) {
    const double expected = integratedSunDepth(particles, ref, sigma, x, sun);
    const double away = integratedSunDepth(particles, ref, sigma, x, -sun);
    if (expected < 0.5 || away < 0.5) return;  // within the chord's matter
    ++compared;
    squared += (got - expected) * (got - expected);
    reference += expected * expected;
  });
  const double relative = std::sqrt(squared / std::max(reference, 1e-30));
  INFO("nodes inside the chords' matter " << compared << ", relative RMS error " << relative);
  REQUIRE(compared > 200);
  CHECK(relative < 0.07);
}
