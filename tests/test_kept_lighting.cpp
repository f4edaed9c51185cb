// The light-space volumes kept from one frame to the next (RenderSettings::keepLighting,
// render/LightSpaceInputs.h) against the same frame with the volumes built again
// (keepLighting false): a frame that reuses them must be the built frame bit for bit, and any
// change to what the volumes are built from (the sun, a particle, the solve) must build them
// again. A moved sun over the same particles keeps the volumes that do not depend on it (bit for
// bit), and its diffusion solve, started from the last one, must stay at least as close to a
// converged solve as the whole solve is. The cloud lighting with its sun and diffusion volumes,
// volume blending, the bench clusters.
#include <catch2/catch.hpp>

#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "render/HiddenFragments.h"
#include "render/Renderer.h"
#include "scene/PixelFootprint.h"
#include "scene/Scene.h"
#include "support/ImageDifference.h"
#include "support/RenderFixture.h"
#include "support/SourceScenes.h"

using namespace cloudlut;
using namespace cloudlut::test;

namespace {

struct Frame {
  render::Image image;
  bool kept = false;
  bool sunOnly = false;  // only the sun's volume was built again
  bool warm = false;     // the diffusion solve started from the frame before's
};

Frame frame(render::Renderer& renderer, const std::vector<scene::Particle>& particles, render::RenderSettings s,
            bool keep) {
  s.keepLighting = keep;
  render::RenderStats stats;
  Frame f;
  f.image = renderer.render(particles, s, &stats);
  f.kept = stats.lightSpaceKept;
  f.sunOnly = stats.lightSpaceSunOnly;
  f.warm = stats.diffusionWarm;
  return f;
}

bool sameImage(const render::Image& a, const render::Image& b) { return a.rgba == b.rgba; }

// The settings with the sun turned by about 20°.
render::RenderSettings withMovedSun(render::RenderSettings s) {
  s.view.lighting.sunDirection = glm::normalize(s.view.lighting.sunDirection + glm::vec3(0.3f, 0.0f, -0.2f));
  return s;
}

// The settings with the sun turned by `degrees` about the vertical.
render::RenderSettings withSunTurned(render::RenderSettings s, float degrees) {
  s.view.lighting.sunDirection = glm::vec3(glm::rotate(glm::mat4(1.0f), glm::radians(degrees), glm::vec3(0, 1, 0)) *
                                           glm::vec4(s.view.lighting.sunDirection, 0.0f));
  return s;
}

}  // namespace

TEST_CASE("kept lighting: a frame that reuses the light-space volumes is the frame that builds them",
          "[render][lighting][kept]") {
  RenderFixture rig = RenderFixture::synthetic();
  render::Renderer& renderer = rig.renderer;
  const scene::Scene scene = sourceScene("data/bench_scenes/cluster.json");
  const render::RenderSettings base = sceneSettings(scene, 96, 64, render::BlendMode::Volume);
  REQUIRE(base.lighting == render::LightingModel::Cloud);
  REQUIRE(base.diffusionShare > 0.0f);

  const Frame first = frame(renderer, scene.particles, base, true);
  const Frame again = frame(renderer, scene.particles, base, true);
  const Frame built = frame(renderer, scene.particles, base, false);
  CHECK_FALSE(first.kept);
  CHECK(again.kept);
  CHECK_FALSE(built.kept);
  CHECK(sameImage(again.image, built.image));
  CHECK(sameImage(first.image, built.image));

  SECTION("the camera turns: the volumes do not depend on it") {
    render::RenderSettings turned = base;
    turned.view.camera.target += glm::vec3(0.3f, -0.1f, 0.0f);
    const Frame kept = frame(renderer, scene.particles, turned, true);
    const Frame rebuilt = frame(renderer, scene.particles, turned, false);
    CHECK(kept.kept);
    CHECK(sameImage(kept.image, rebuilt.image));
    CHECK_FALSE(sameImage(kept.image, built.image));  // the view did change
  }

  SECTION("the sun moves: its volume built again, the others kept, the whole solve the same image") {
    render::RenderSettings moved = withMovedSun(base);
    moved.diffusionWarmCycles = 0;
    const Frame kept = frame(renderer, scene.particles, moved, true);
    const Frame rebuilt = frame(renderer, scene.particles, moved, false);
    CHECK_FALSE(kept.kept);
    CHECK(kept.sunOnly);
    CHECK_FALSE(kept.warm);
    CHECK_FALSE(rebuilt.sunOnly);
    CHECK(sameImage(kept.image, rebuilt.image));
    CHECK_FALSE(sameImage(kept.image, built.image));
  }

  SECTION("the sun moves: the warm-started solve is close to the whole one") {
    const render::RenderSettings moved = withMovedSun(base);
    const Frame warm = frame(renderer, scene.particles, moved, true);
    const Frame rebuilt = frame(renderer, scene.particles, moved, false);
    CHECK(warm.sunOnly);
    CHECK(warm.warm);
    CHECK_FALSE(rebuilt.warm);
    CHECK(colourDifference(warm.image, rebuilt.image).relativeRmse < 0.01);
  }

  SECTION("a particle moves and the sun too: built again") {
    std::vector<scene::Particle> shifted = scene.particles;
    shifted[2].center.x += 0.05f;
    const render::RenderSettings moved = withMovedSun(base);
    const Frame kept = frame(renderer, shifted, moved, true);
    const Frame rebuilt = frame(renderer, shifted, moved, false);
    CHECK_FALSE(kept.kept);
    CHECK_FALSE(kept.sunOnly);
    CHECK_FALSE(kept.warm);
    CHECK(sameImage(kept.image, rebuilt.image));
  }

  SECTION("a particle changes: built again") {
    std::vector<scene::Particle> denser = scene.particles;
    denser[3].density *= 2.0f;
    const Frame kept = frame(renderer, denser, base, true);
    const Frame rebuilt = frame(renderer, denser, base, false);
    CHECK_FALSE(kept.kept);
    CHECK(sameImage(kept.image, rebuilt.image));
    CHECK_FALSE(sameImage(kept.image, built.image));
  }

  SECTION("the solve changes: built again") {
    render::RenderSettings fewer = base;
    fewer.diffusionCycles = 1;
    const Frame kept = frame(renderer, scene.particles, fewer, true);
    const Frame rebuilt = frame(renderer, scene.particles, fewer, false);
    CHECK_FALSE(kept.kept);
    CHECK(sameImage(kept.image, rebuilt.image));
  }

  SECTION("a frame without the diffusion, then one with it: built again") {
    render::RenderSettings tablesOnly = base;
    tablesOnly.diffusionShare = 0.0f;
    CHECK_FALSE(frame(renderer, scene.particles, tablesOnly, true).kept);
    const Frame back = frame(renderer, scene.particles, base, true);
    CHECK_FALSE(back.kept);
    CHECK(sameImage(back.image, built.image));
  }
}

TEST_CASE("kept lighting: the camera moves through a culled scene whose draw order changes, the volumes hold",
          "[render][lighting][kept]") {
  RenderFixture rig = RenderFixture::synthetic();
  render::Renderer& renderer = rig.renderer;
  const scene::Scene scene = sourceScene("data/bench_scenes/cluster36.json");
  render::RenderSettings base = sceneSettings(scene, 96, 64, render::BlendMode::Volume);
  render::RenderSettings moved = base;
  moved.view.camera.eye = base.view.camera.target +
                          glm::vec3(glm::rotate(glm::mat4(1.0f), 1.2f, glm::vec3(0.0f, 1.0f, 0.0f)) *
                                    glm::vec4(base.view.camera.eye - base.view.camera.target, 0.0f));
  // both frames cull hidden fragments, so both draw back to front, and the order differs
  for (const render::RenderSettings* s : {&base, &moved})
    REQUIRE(render::hiddenCullingPays(
        scene::pixelFootprintBound(scene.particles, scene::CameraFrame(s->view.camera, s->width, s->height)),
        static_cast<std::size_t>(s->width) * s->height));
  REQUIRE(render::backToFrontOrder(scene.particles, base.view.camera.eye) !=
          render::backToFrontOrder(scene.particles, moved.view.camera.eye));

  CHECK_FALSE(frame(renderer, scene.particles, base, true).kept);
  const Frame kept = frame(renderer, scene.particles, moved, true);
  const Frame rebuilt = frame(renderer, scene.particles, moved, false);
  CHECK(kept.kept);
  CHECK(sameImage(kept.image, rebuilt.image));
}


// A sun that turns 5° about the vertical every frame over `cluster36`: each frame's diffusion
// solve starts from the one before and runs one correction cycle (diffusionWarmCycles 1). Against a
// converged solve of the same frame (twelve cycles, built from nothing), the warm-started image must
// be at least as close as the whole solve's (three cycles) is, to within 0.1% of the colour, and
// within 1% in any case: the warm start must not drift as the frames go.
TEST_CASE("kept lighting: under a turning sun the warm-started diffusion solve stays converged",
          "[render][lighting][kept]") {
  RenderFixture rig = RenderFixture::synthetic();
  render::Renderer& renderer = rig.renderer;
  const scene::Scene scene = sourceScene("data/bench_scenes/cluster36.json");
  const render::RenderSettings base = sceneSettings(scene, 96, 64, render::BlendMode::Volume);
  REQUIRE(base.diffusionWarmCycles == 1);
  constexpr int kFrames = 5;
  const auto sunAt = [&](int k) { return withSunTurned(base, 5.0f * static_cast<float>(k)); };
  std::vector<Frame> warm;
  for (int k = 0; k < kFrames; ++k) warm.push_back(frame(renderer, scene.particles, sunAt(k), true));
  CHECK_FALSE(warm[0].warm);
  for (int k = 1; k < kFrames; ++k) {
    INFO("frame " << k);
    CHECK(warm[k].warm);
    const Frame whole = frame(renderer, scene.particles, sunAt(k), false);
    render::RenderSettings many = sunAt(k);
    many.diffusionCycles = 12;
    const Frame converged = frame(renderer, scene.particles, many, false);
    const double warmError = colourDifference(warm[k].image, converged.image).relativeRmse;
    const double wholeError = colourDifference(whole.image, converged.image).relativeRmse;
    INFO("warm " << warmError << ", whole solve " << wholeError);
    CHECK(warmError <= wholeError + 1e-3);
    CHECK(warmError < 0.01);
  }
}
