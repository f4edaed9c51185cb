// The ray-marched baseline (render/RayMarchRenderer.h) against closed forms and the scene path
// tracer on the same particle list.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include "support/CliRunner.h"
#include "core/Defaults.h"
#include "reference/ScenePathTracer.h"
#include "render/GlContext.h"
#include "render/RayMarchRenderer.h"

using namespace cloudlut;
using namespace cloudlut::render;
using namespace cloudlut::scene;

namespace {

RayMarchSettings sphereSettings(int steps) {
  RayMarchSettings s;
  s.width = 24;
  s.height = 16;
  s.view.camera.eye = glm::vec3(0.0f, 0.3f, 5.0f);
  s.view.camera.target = glm::vec3(0.0f);
  s.view.camera.fovDeg = 30.0f;
  s.view.lighting.sunDirection = glm::normalize(glm::vec3(0.5f, 0.7f, 0.4f));
  s.view.lighting.sunColor = glm::vec3(1.0f);
  s.view.lighting.skyColor = glm::vec3(0.0f);
  s.steps = steps;
  return s;
}

}  // namespace

TEST_CASE("raymarch: transmittance of a homogeneous sphere is Beer-Lambert along the exact chord", "[raymarch]") {
  auto context = createHeadlessContext();
  const ReferenceParticle model(DensityModel::Sphere, 1);
  RayMarchRenderer marcher(*context, model);
  const Particle p{glm::vec3(0.0f), glm::vec3(1.3f), glm::quat(1, 0, 0, 0), 0.3f};
  RayMarchSettings s = sphereSettings(8);
  const Image img = marcher.render({p}, s, nullptr);
  const CameraFrame camera(s.view.camera, s.width, s.height);
  int inside = 0;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      const glm::vec3 d = camera.rayDirection(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
      const glm::vec3 o = camera.eye() / 1.3f, du = d / 1.3f;  // the ray in unit-sphere space
      const float a = glm::dot(du, du), b = glm::dot(o, du), c = glm::dot(o, o) - 1.0f;
      const float disc = b * b - a * c;
      float expected = 0.0f;
      if (disc > 0.0f) {
        const float chordUnit = 2.0f * std::sqrt(disc) / a * std::sqrt(a);  // unit-sphere chord length
        expected = 1.0f - std::exp(-static_cast<float>(defaults::kUnitOpticalRadius) * 0.3f * chordUnit);
        ++inside;
      }
      INFO("pixel " << x << "," << y);
      CHECK(img.pixel(x, y)[3] == Approx(expected).margin(2e-4));
    }
  CHECK(inside > 20);
}

TEST_CASE("raymarch: sky only gives sky·alpha; single scattering agrees with the path tracer", "[raymarch]") {
  auto context = createHeadlessContext();
  const ReferenceParticle model(DensityModel::Radial, 1);
  RayMarchRenderer marcher(*context, model);
  const Particle p{glm::vec3(0.0f), glm::vec3(1.0f, 0.8f, 0.9f), glm::quat(1, 0, 0, 0), 0.2f};

  RayMarchSettings sky = sphereSettings(128);
  sky.terms = kTermAmbient;
  sky.view.lighting.skyColor = glm::vec3(0.1f, 0.2f, 0.4f);
  const Image a = marcher.render({p}, sky, nullptr);
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x)
      for (int c = 0; c < 3; ++c)
        CHECK(a.pixel(x, y)[c] == Approx(sky.view.lighting.skyColor[c] * a.pixel(x, y)[3]).margin(1e-5));

  RayMarchSettings single = sphereSettings(256);
  single.terms = kTermSingle;
  single.octaves = 1;
  single.shadowSteps = 64;
  const Image b = marcher.render({p}, single, nullptr);
  reference::SceneMedium medium;
  medium.model = &model;
  medium.particles.push_back({glm::dvec3(0.0), glm::dmat3(p.toParticle()), 0.2});
  reference::SceneLight light;
  light.sunDirection = glm::dvec3(single.view.lighting.sunDirection);
  reference::ScenePtSettings st;
  st.maxOrder = 1;
  const CameraFrame camera(single.view.camera, single.width, single.height);
  int checked = 0;
  for (const auto& [x, y] : {std::pair{12, 8}, std::pair{9, 6}, std::pair{14, 10}, std::pair{11, 5}}) {
    const glm::dvec3 d(camera.rayDirection(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f));
    const reference::RayEstimate e =
        reference::estimateRay(medium, light, st, glm::dvec3(camera.eye()), d, 20000, static_cast<std::uint64_t>(x * 100 + y));
    if (e.transmittance > 0.99) continue;
    ++checked;
    INFO("pixel " << x << "," << y << ": raymarch " << b.pixel(x, y)[1] << ", path traced " << e.single << " ± "
                  << e.singleSe);
    CHECK(std::abs(b.pixel(x, y)[1] - e.single) < 4.0 * e.singleSe + 0.01 * e.single);
    CHECK(b.pixel(x, y)[3] == Approx(1.0 - e.transmittance).margin(5.0 * e.transmittanceSe + 1e-3));
  }
  CHECK(checked >= 3);
}

TEST_CASE("raymarch: through 3000 particles the march is Beer-Lambert; pixels the GL cuts short are reported",
          "[raymarch]") {
  // 3000 homogeneous spheres (radius 0.04, optical diameter 0.5) scattered in a cube, lit by the
  // sun: every pixel's shadow rays look for particles at every step. (Before the cell grid each
  // shadow ray tested all 3000 particles, and llvmpipe, which ends an invocation's loops after
  // 65535 passes, cut the march short after about 20 of the 32 steps.)
  auto context = createHeadlessContext();
  const ReferenceParticle model(DensityModel::Sphere, 1);
  RayMarchRenderer marcher(*context, model);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const float radius = 0.04f, density = 0.25f / static_cast<float>(defaults::kUnitOpticalRadius);
  std::vector<Particle> field;
  for (int i = 0; i < 3000; ++i) field.push_back({glm::vec3(u(rng), u(rng), u(rng)), glm::vec3(radius), glm::quat(1, 0, 0, 0), density});
  RayMarchSettings s = sphereSettings(32);
  s.width = 32;
  s.height = 24;
  s.view.camera.fovDeg = 20.0f;
  s.view.lighting.skyColor = glm::vec3(0.2f);
  s.adaptive = true;
  RenderStats stats;
  const Image img = marcher.render(field, s, &stats);
  CHECK(stats.rayMarchBudgetPixels == 0);
  CHECK(stats.rayMarchDroppedPixels == 0);

  // Beer–Lambert along the exact chords, summed over the spheres.
  const CameraFrame camera(s.view.camera, s.width, s.height);
  const auto exactAlpha = [&](int x, int y) {
    const glm::vec3 d = camera.rayDirection(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f), o = camera.eye();
    double tau = 0.0;
    for (const Particle& p : field) {
      const float b = glm::dot(o - p.center, d), c = glm::dot(o - p.center, o - p.center) - radius * radius;
      if (b * b - c > 0.0f) tau += defaults::kUnitOpticalRadius * density * 2.0 * std::sqrt(b * b - c) / radius;
    }
    return 1.0 - std::exp(-tau);
  };
  double sumError = 0.0, sumAlpha = 0.0;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      const double expected = exactAlpha(x, y);
      INFO("pixel " << x << "," << y);
      CHECK(img.pixel(x, y)[3] == Approx(expected).margin(0.03));
      sumError += std::abs(img.pixel(x, y)[3] - expected);
      sumAlpha += expected;
    }
  CHECK(sumAlpha > 0.3 * s.width * s.height);  // the field covers the view, mostly translucent
  CHECK(sumError < 0.01 * sumAlpha);

  // Far more steps than llvmpipe's loop budget allows: every pixel whose march comes out wrong is
  // one the renderer reports (none on a GL without the limit).
  s.steps = 4096;
  const Image cut = marcher.render(field, s, &stats);
  int wrong = 0;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) wrong += std::abs(cut.pixel(x, y)[3] - exactAlpha(x, y)) > 0.03 ? 1 : 0;
  INFO(wrong << " pixels off Beer-Lambert, " << stats.rayMarchBudgetPixels << " reported");
  CHECK(static_cast<std::size_t>(wrong) <= stats.rayMarchBudgetPixels);
}

TEST_CASE("raymarch: render --method raymarch writes an image; bad settings are usage errors", "[raymarch]") {
  using namespace cloudlut::test;
  TempDir dir;
  const std::string scene = std::string(CLOUDLUT_SOURCE_DIR) + "/data/bench_scenes/three.json";
  const auto ok = runCli("render --method raymarch --particles '" + scene + "' --out '" + (dir / "r.exr").string() +
                         "' --width 32 --height 24 --steps 16 --adaptive --density-model radial");
  INFO(ok.err);
  CHECK(ok.exitCode == 0);
  CHECK(ok.out.find("raymarch 16 steps adaptive") != std::string::npos);
  CHECK(std::filesystem::exists(dir / "r.exr"));
  CHECK(runCli("render --method raymarch --particles '" + scene + "' --out '" + (dir / "r.png").string() +
               "' --steps 0 --quiet").exitCode == 2);
  CHECK(runCli("render --method marching --particles '" + scene + "' --out '" + (dir / "r.png").string() +
               "' --quiet").exitCode == 2);
  CHECK(runCli("render --method raymarch --particles '" + scene + "' --out '" + (dir / "r.png").string() +
               "' --octave-abc 2,0.5,0.5 --quiet").exitCode == 2);
}
