// Light shafts (issue 13, seed §5.6; render/shaders/sky_shafts.glsl): the clouds' shadow on the
// air's single scattering of sunlight. A large opaque particle 1.5–3.5 km up casts its shadow
// across the view of a camera 50 m up looking level, away from a sun 50° high (the ray stays
// below the particle). The centre pixel's radiance with light shafts minus without them must
// equal, within 3%, the loss a direct CPU integration gives: the brute-force reference's single
// scattering along the pixel's ray (src/reference, a quadrature) with the sunlight at each point
// scaled by the clouds' share slabTransmittance(τ) — τ from the sun volume the GPU built, read
// back and interpolated here — against the same without the shadow. The CPU shares nothing with
// the shafts but that volume: neither the aerial table nor the march. The 33 × 33 frame has 5 × 5
// shaft cells of 8 pixels, the centre pixel's ray that of the centre cell. A ray that meets no
// shadow (looking toward the sun's side, the shadow behind) must not change.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "bake/AtmosphereBaker.h"
#include "core/Defaults.h"
#include "core/Glsl.h"
#include "reference/AtmosphereReference.h"
#include "support/RenderFixture.h"

using namespace cloudlut;

namespace {

// τ toward the sun at world point x from the read-back volume, as sunOpticalDepth samples it:
// the finest cascade whose columns hold x, trilinear between nodes, w clamped to the slices.
double volumeDepth(const render::Renderer::SunVolumeSnapshot& v, const glm::dvec3& x) {
  const render::SunVolumeGrid& g = v.grid;
  const std::size_t perCascade = std::size_t(g.dims.x) * g.dims.y * g.dims.z;
  for (int k = 0; k < g.cascades; ++k) {
    const glm::dvec3 p = glm::dvec3(glm::dmat4(g.toGrid[k]) * glm::dvec4(x, 1.0));
    if (p.x < 0 || p.y < 0 || p.x > g.dims.x - 1 || p.y > g.dims.y - 1) continue;
    const double w = std::clamp(p.z, 0.0, double(g.dims.z - 1));
    const int i = std::min(int(p.x), g.dims.x - 2), j = std::min(int(p.y), g.dims.y - 2), l = std::min(int(w), g.dims.z - 2);
    const double fx = p.x - i, fy = p.y - j, fz = w - l;
    double tau = 0;
    for (int n = 0; n < 8; ++n) {
      const int di = n & 1, dj = (n >> 1) & 1, dl = n >> 2;
      const double weight = (di ? fx : 1 - fx) * (dj ? fy : 1 - fy) * (dl ? fz : 1 - fz);
      tau += weight * v.tau[k * perCascade + (std::size_t(l + dl) * g.dims.y + (j + dj)) * g.dims.x + (i + di)];
    }
    return tau;
  }
  return 0.0;
}

// Eddington total transmittance of a slab (cloudlut_shading.glsl's slabTransmittance), restated.
double slab(double tau, double g) { return std::min(1.0, (1.25 - 0.25 * std::exp(-tau)) / (1.0 + 0.75 * (1.0 - g) * tau)); }

}  // namespace

TEST_CASE("light shafts: the clouds' shadow takes from the air what a direct integration says", "[atmosphere][render]") {
  test::RenderFixture f = test::RenderFixture::synthetic();
  const glsl::AtmosphereParameters a = glsl::defaultAtmosphere();
  bake::AtmosphereBakeSettings bs;
  bs.multipleOrders = 2;  // cheaper; the shafts touch the single scattering only
  const bake::AtmosphereTables tables = bake::bakeAtmosphere(a, bs);
  f.renderer.setAtmosphereTables(a, tables.transmittance, tables.multipleScattering, tables.irradiance);

  const double elevation = 50.0 * 3.14159265358979 / 180.0;
  const glm::vec3 sun(0.0f, float(std::sin(elevation)), float(std::cos(elevation)));  // toward +z, up
  std::vector<scene::Particle> particles(1);
  particles[0].center = {0.0f, 2500.0f, -2000.0f};
  particles[0].radii = glm::vec3(1000.0f);
  particles[0].density = 1.0f;
  const glm::vec3 eye(0.0f, 50.0f, 0.0f);

  render::RenderSettings s;
  s.width = s.height = 33;
  s.view.camera.eye = eye;
  s.view.camera.up = glm::vec3(0.0f, 1.0f, 0.0f);
  s.view.camera.fovDeg = 10.0f;
  s.view.lighting.sunDirection = sun;
  s.view.lighting.sunColor = glm::vec3(1.0f);
  s.view.lighting.atmosphere = true;
  s.view.lighting.atmosphereParameters = a;
  const auto centre = [&](const glm::vec3& view, bool shafts) {
    render::RenderSettings r = s;
    r.view.camera.target = eye + 1000.0f * view;
    r.lightShafts = shafts;
    const render::Image image = f.renderer.render(particles, r);
    const std::size_t i = 4 * (std::size_t(16) * std::size_t(image.width) + 16);
    CHECK(image.rgba[i + 3] == 0.0f);  // the ray meets no particle
    return glm::dvec3(image.rgba[i], image.rgba[i + 1], image.rgba[i + 2]);
  };

  const glm::vec3 away(0.0f, 0.0f, -1.0f);  // level, away from the sun, under the particle's shadow
  const glm::dvec3 loss = centre(away, false) - centre(away, true);

  const render::Renderer::SunVolumeSnapshot volume = f.renderer.sunVolume(particles, s);
  const reference::AtmosphereReference ref(a);
  const glm::dvec3 centreOffset(0.0, a.bottomRadius, 0.0);  // world → planet frame
  const glm::dvec3 position = glm::dvec3(eye) + centreOffset;
  // the synthetic tables state no later phase: the default Cornette–Shanks g 0.7, whose mean
  // cosine is 3g(4 + g²)/(5(2 + g²))
  const double gl = defaults::kMultipleScatteringG, asymmetry = 3.0 * gl * (4.0 + gl * gl) / (5.0 * (2.0 + gl * gl));
  const auto visibility = [&](const glm::dvec3& x) { return slab(volumeDepth(volume, x - centreOffset), asymmetry); };
  const glm::dvec3 clear = ref.singleScattering(position, glm::dvec3(away), glm::dvec3(sun), 8000);
  const glm::dvec3 shadowed = ref.singleScattering(position, glm::dvec3(away), glm::dvec3(sun), 8000, visibility);
  const glm::dvec3 expected = clear - shadowed;
  for (int c = 0; c < 3; ++c) {
    INFO("channel " << c << ": GPU loss " << loss[c] << ", CPU " << expected[c] << " of single scattering " << clear[c]);
    CHECK(expected[c] > 0.005 * clear[c]);  // the shadow takes a real share of the ray's single scattering
    CHECK(std::abs(loss[c] - expected[c]) < 0.03 * expected[c]);
  }

  // toward the sun's side the ray leaves the shadow behind: no change
  const glm::vec3 toward(0.0f, 0.0f, 1.0f);
  const glm::dvec3 unchanged = centre(toward, false) - centre(toward, true);
  for (int c = 0; c < 3; ++c) CHECK(std::abs(unchanged[c]) < 1e-6 * centre(toward, false)[c] + 1e-9);
}
