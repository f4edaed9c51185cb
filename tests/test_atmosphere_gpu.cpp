// The GPU sky (render/SkyPass.h through OSMesa/llvmpipe) against the CPU: at a few of the
// bench's check directions (bench/AtmosphereComparison.h; none with the sun's disc in view), the centre pixel of a small frame
// looking along the direction, with no cloud in it, must match
//   - the brute-force single scattering (src/reference, a quadrature) within the 2% goal
//     plus 1% for the sky-view table's interpolation, with --sky-orders 1;
//   - the same shared GLSL evaluated on the CPU (tableSkyRadiance) within 2%, with all orders:
//     the GPU adds only the 192 × 108 sky-view table and float texture filtering.
// Cheap: one atmosphere bake (smaller under the sanitizers), 33 × 33 frames.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "bake/AtmosphereBaker.h"
#include "bench/AtmosphereComparison.h"
#include "core/Glsl.h"
#include "reference/AtmosphereReference.h"
#include "render/GlContext.h"
#include "render/Renderer.h"
#include "support/RenderLuts.h"
#include "support/TempDir.h"

using namespace cloudlut;

namespace {

const bench::AtmosphereCheck& checkNamed(const std::vector<bench::AtmosphereCheck>& checks, const std::string& name,
                                         double elevation) {
  for (const auto& c : checks)
    if (c.name == name && c.sunElevationDeg == elevation) return c;
  throw std::logic_error("no check " + name);
}

// The centre pixel's radiance of a 33 × 33 frame from the check's camera (500 m up) looking along
// its view, under the atmosphere, with one small particle far behind the camera (nothing in view).
glm::dvec3 gpuSky(render::Renderer& renderer, const glsl::AtmosphereParameters& a, const bench::AtmosphereCheck& c,
                  int orders) {
  render::RenderSettings s;
  s.width = s.height = 33;
  const glm::vec3 eye(0.0f, static_cast<float>(bench::kCheckAltitudeMetres), 0.0f);
  const glm::vec3 view(c.view);
  s.view.camera.eye = eye;
  s.view.camera.target = eye + 1000.0f * view;
  s.view.camera.up = std::abs(view.y) > 0.9f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
  s.view.camera.fovDeg = 10.0f;
  s.view.lighting.sunDirection = glm::vec3(c.sun);
  s.view.lighting.sunColor = glm::vec3(1.0f);
  s.view.lighting.atmosphere = true;
  s.view.lighting.atmosphereParameters = a;
  s.skyOrders = orders;
  scene::Particle behind;
  behind.center = eye - 5000.0f * view;
  behind.radii = glm::vec3(10.0f);
  const render::Image image = renderer.render({behind}, s);
  const std::size_t i = 4 * (std::size_t(16) * std::size_t(image.width) + 16);
  return glm::dvec3(image.rgba[i], image.rgba[i + 1], image.rgba[i + 2]);
}

}  // namespace

TEST_CASE("the GPU sky matches the reference and the CPU evaluation of the same GLSL", "[atmosphere][render]") {
  const glsl::AtmosphereParameters a = glsl::defaultAtmosphere();
  bake::AtmosphereBakeSettings settings;
#ifdef CLOUDLUT_SANITIZED
  settings.multipleOrders = 2;  // a cheaper bake; the GPU and CPU read the same tables either way
#endif
  const bake::AtmosphereTables tables = bake::bakeAtmosphere(a, settings);
  test::TempDir tmp;
  test::writeSyntheticLutSet(tmp / "luts");
  auto context = render::createHeadlessContext();
  render::Renderer renderer(*context, io::readLutSet(tmp / "luts"));
  renderer.setAtmosphereTables(a, tables.transmittance, tables.multipleScattering, tables.irradiance);

  const std::vector<bench::AtmosphereCheck> checks = bench::atmosphereChecks();
  const reference::AtmosphereReference ref(a);
  const glm::dvec3 position = bench::checkPosition(a);
  for (const auto* c : {&checkNamed(checks, "zenith", 30.0), &checkNamed(checks, "90 deg from sun", 30.0),
                        &checkNamed(checks, "away from sun", 5.0), &checkNamed(checks, "horizon", 5.0)}) {
    INFO(c->name << ", sun at " << c->sunElevationDeg << " deg");
    const glm::dvec3 single = gpuSky(renderer, a, *c, 1);
    CHECK(bench::relativeError(single, ref.singleScattering(position, c->view, c->sun, 400)) < 0.03);
    const glm::dvec3 all = gpuSky(renderer, a, *c, 0);
    const glm::dvec3 cpu = bench::tableSkyRadiance(tables, a, *c, 0);
    CHECK(bench::relativeError(all, cpu) < 0.02);
    CHECK(all.z > 1.05 * single.z);  // the orders >= 2 reach the GPU sky
  }
}
