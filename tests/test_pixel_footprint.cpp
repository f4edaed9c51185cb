// scene::pixelFootprintBound against the pixels whose centre rays meet each ellipsoid, found by
// solving each ray's quadratic directly; and the bound's effect on a first frame's tile plan.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "render/Renderer.h"
#include "scene/PixelFootprint.h"
#include "scene/Scene.h"
#include "support/RenderFixture.h"
#include "support/SourceScenes.h"

using namespace cloudlut;
using namespace cloudlut::render;
using namespace cloudlut::scene;
using namespace cloudlut::test;

namespace {

// Pixels whose centre ray from the eye meets the ellipsoid ahead of the eye (or starts inside
// it): |M (e + t d − c)|² = 1 with M = diag(1/radii) Rᵀ, solved in double.
std::size_t pixelsMeeting(const Particle& p, const Camera& camera, const CameraFrame& frame) {
  const glm::dmat3 rotation = glm::mat3_cast(glm::dquat(p.rotation));
  std::size_t n = 0;
  for (int y = 0; y < frame.height(); ++y)
    for (int x = 0; x < frame.width(); ++x) {
      const glm::dvec3 d = glm::transpose(rotation) * glm::dvec3(frame.rayDirection(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f));
      const glm::dvec3 o = glm::transpose(rotation) * (glm::dvec3(camera.eye) - glm::dvec3(p.center));
      const glm::dvec3 r(p.radii);
      const glm::dvec3 ds = d / r, os = o / r;
      const double a = glm::dot(ds, ds), b = glm::dot(os, ds), c = glm::dot(os, os) - 1.0;
      const double disc = b * b - a * c;
      if (disc <= 0) continue;
      const double tExit = (-b + std::sqrt(disc)) / a;
      if (tExit > 0) ++n;
    }
  return n;
}

}  // namespace

TEST_CASE("pixel footprint: the bound holds every pixel whose ray meets the particle", "[scene]") {
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  Camera camera;
  camera.eye = {0.0f, 0.0f, 0.0f};
  camera.target = {0.3f, -0.1f, -1.0f};
  camera.up = {0.0f, 1.0f, 0.0f};
  camera.fovDeg = 50.0f;
  const CameraFrame frame(camera, 48, 32);
  std::size_t inView = 0, whole = 0, particles = 0, meetingSum = 0, boundSum = 0;
  for (int i = 0; i < 400; ++i) {
    Particle p;
    // ahead, beside, behind and around the eye, some of them over the image's edges
    p.center = glm::vec3(4.0f * u(rng), 3.0f * u(rng), -3.0f + 4.0f * u(rng));
    p.radii = glm::vec3(0.1f + 0.6f * (u(rng) + 1.0f), 0.1f + 0.4f * (u(rng) + 1.0f), 0.1f + 0.5f * (u(rng) + 1.0f));
    p.rotation = glm::normalize(glm::quat(u(rng), u(rng), u(rng), u(rng)));
    const std::size_t meeting = pixelsMeeting(p, camera, frame);
    const std::size_t bound = pixelFootprintBound(p, frame);
    INFO("particle " << i << " at (" << p.center.x << ", " << p.center.y << ", " << p.center.z << ")");
    CHECK(bound >= meeting);
    CHECK(bound <= std::size_t(48 * 32));
    if (meeting > 0) ++inView;
    if (bound == std::size_t(48 * 32)) ++whole;
    ++particles;
    meetingSum += meeting;
    boundSum += bound;
  }
  std::vector<Particle> list(3);
  list[0].center = {0.0f, 0.0f, -6.0f};
  list[1].center = {1.0f, 0.5f, -8.0f};
  list[2].center = {0.0f, 0.0f, 20.0f};  // behind the eye
  CHECK(pixelFootprintBound(list, frame) == pixelFootprintBound(list[0], frame) + pixelFootprintBound(list[1], frame));
  CHECK(pixelFootprintBound(list[2], frame) == 0);
  std::printf("[pixel footprint] %zu particles, %zu in view, %zu bounded by the whole image: %zu pixels met, bound %zu\n",
              particles, inView, whole, meetingSum, boundSum);
  CHECK(inView > 100);
  CHECK(whole < particles / 2);  // the test covers rectangles, not only the whole image
}

TEST_CASE("pixel footprint: a sphere ahead is bounded within its square and two pixels", "[scene]") {
  Camera camera;
  camera.eye = {0.0f, 0.0f, 0.0f};
  camera.target = {0.0f, 0.0f, -1.0f};
  camera.up = {0.0f, 1.0f, 0.0f};
  camera.fovDeg = 60.0f;
  const CameraFrame frame(camera, 400, 300);
  Particle p;
  p.center = {0.0f, 0.0f, -40.0f};
  p.radii = glm::vec3(1.0f);
  // seen from 40 radii the disc's radius is 1/(40·tan 30°) of half the image's height, ≈ 6.5 pixels
  const double discRadius = 150.0 / (std::sqrt(40.0 * 40.0 - 1.0) * std::tan(glm::radians(30.0)));
  const std::size_t bound = pixelFootprintBound(p, frame), meeting = pixelsMeeting(p, camera, frame);
  std::printf("[pixel footprint] sphere of disc radius %.2f pixels: %zu pixels met, bound %zu\n", discRadius, meeting,
              bound);
  CHECK(std::abs(static_cast<double>(meeting) - M_PI * discRadius * discRadius) < 2.0 * M_PI * discRadius);
  CHECK(bound >= meeting);
  CHECK(static_cast<double>(bound) <= std::pow(2.0 * discRadius * 1.03 + 4.0, 2));
}

TEST_CASE("pixel footprint: a first frame that fits one tile is not counted", "[render][volume]") {
  RenderFixture rig = RenderFixture::synthetic(DensityModel::Noise);
  const Scene scene = sourceScene("data/scenes/small.json");
  RenderSettings s = sceneSettings(scene, 96, 64, BlendMode::Volume);
  s.view.camera.eye = {0.0f, 1.0f, 5.0f};
  s.tilePlan = VolumeTilePlan::Expected;
  s.fragmentsPerPixel = 4;
  s.volumePoolBytes = 16.0L + 28.0L * 4 * 96 * 16;  // bands of 16 rows, 6144 nodes each
  RenderStats expected;
  const Image reference = rig.renderer.render(scene.particles, s, &expected);
  REQUIRE(expected.volumeTiles == 4);
  REQUIRE(expected.volumeRedrawnTiles == 0);
  // the bound holds the stored fragments
  CHECK(expected.fragmentBound >= expected.fragments);
  std::printf("[pixel footprint] small scene at 96x64: %zu fragments, bound %zu\n", expected.fragments,
              expected.fragmentBound);

  // A Renderer's first frame under the automatic plan: a pool that the bound fits is not counted
  // (4 tiles of 6144 nodes, as the expected plan); one it does not fit is (1 fragment a pixel).
  s.tilePlan = VolumeTilePlan::Auto;
  s.volumePoolBytes = 16.0L + 28.0L * 4 * 96 * 32;  // bands of 32 rows, 12288 nodes
  RenderFixture fresh = RenderFixture::synthetic(DensityModel::Noise);
  RenderStats roomy;
  const Image roomyImage = fresh.renderer.render(scene.particles, s, &roomy);
  INFO("bound " << roomy.fragmentBound << ", tile of 12288 nodes");
  REQUIRE(roomy.fragmentBound <= 12288);
  CHECK(!roomy.volumeTilesCounted);
  CHECK(roomy.countedFragments == 0);
  CHECK(roomy.volumeTiles == 2);
  CHECK(roomy.volumeRedrawnTiles == 0);
  CHECK(roomyImage.rgba == reference.rgba);
}
