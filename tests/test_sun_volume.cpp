// The sun optical-depth volume (render/SunVolume, docs/LIGHTING.md) against a direct CPU
// integration of the reference particle's density along the same sun rays: at every node that
// lies outside all particles, the volume's τ toward the sun must equal Σ ∫ ρ σ ρ̂(M⁻¹(x − c)) |M⁻¹ ds|
// over the particles in front of it. The splat builds τ from the optical-depth table's chords;
// the integration here samples the density itself (1/256 of a radius per step), so the two
// share nothing but the particle.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "bake/OpticalDepthBaker.h"
#include "core/Medium.h"
#include "render/GlContext.h"
#include "render/Renderer.h"
#include "scene/Scene.h"
#include "support/RenderLuts.h"
#include "support/TempDir.h"

using namespace cloudlut;
using namespace cloudlut::test;

namespace {

// Optical depth toward the sun from x (dimensionless), midpoint rule in world units.
double integratedSunDepth(const std::vector<scene::Particle>& particles, const ReferenceParticle& ref, double sigma,
                          const glm::vec3& x, const glm::vec3& sun) {
  double tau = 0;
  for (const scene::Particle& p : particles) {
    const glm::mat3 inv = p.toParticle();
    const float reach = std::max({p.radii.x, p.radii.y, p.radii.z});
    // the part of the ray within reach of the centre
    const glm::vec3 oc = x - p.center;
    const float b = glm::dot(oc, sun), c = glm::dot(oc, oc) - reach * reach;
    const float disc = b * b - c;
    if (disc <= 0) continue;
    const float t0 = std::max(0.0f, -b - std::sqrt(disc)), t1 = -b + std::sqrt(disc);
    if (t1 <= t0) continue;
    const float ds = std::min(p.radii.x, std::min(p.radii.y, p.radii.z)) / 256.0f;
    const int n = static_cast<int>(std::ceil((t1 - t0) / ds));
    const double step = static_cast<double>(t1 - t0) / n, unitStep = glm::length(inv * sun) * step;
    double sum = 0;
    for (int i = 0; i < n; ++i) {
      const glm::vec3 y = inv * (x + sun * static_cast<float>(t0 + (i + 0.5) * step) - p.center);
      sum += ref.density(y);
    }
    tau += p.density * sigma * sum * unitStep;
  }
  return tau;
}

}  // namespace

TEST_CASE("sun volume: optical depth toward the sun matches the density integrated along the sun rays",
          "[render][lighting]") {
  TempDir tmp;
  const Medium medium;
  const ReferenceParticle ref(medium.model, medium.seed);
  bake::OpticalDepthSettings ods;
  ods.dims = {64, 32, 64, 32};
  const Table4D od = bake::bakeOpticalDepth(ref, ods);
  const Table4D l1 = syntheticSingle(), lm = syntheticMultiple();
  writeLutSet(tmp / "luts", {&od, &l1, &lm});
  const io::LutSet luts = io::readLutSet(tmp / "luts");
  auto context = render::createHeadlessContext();
  render::Renderer renderer(*context, luts);

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
  const render::Renderer::SunVolumeSnapshot v = renderer.sunVolume(particles, rs);
  const render::SunVolumeGrid& g = v.grid;
  REQUIRE(g.cascades == 1);
  REQUIRE(v.tau.size() == static_cast<std::size_t>(g.dims.x) * g.dims.y * g.dims.z);
  const double sigma = medium.unitOpticalRadius();

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
        const double expected = integratedSunDepth(particles, ref, sigma, x, g.sun);
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
