// The sun volume's chord map (render/SunVolume, shaders/sun_chord_map.glsl): the particle shader
// takes each particle's own ramp out of the sun volume with the chords the splat kept, instead
// of intersecting and looking them up again (RenderSettings::sunChordMap = false, the path the
// lighting tests measured against the path tracer). The two must give the same image, and the
// map must hold every chord of these scenes, so that the map is what was read.
// (A frame whose chords pass the GPU buffer budget, 128 MiB on llvmpipe, computes them: the
// second path; no test scene is that large.)
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "render/GlContext.h"
#include "render/Renderer.h"
#include "scene/Cloudscape.h"
#include "scene/Scene.h"
#include "support/RenderFixture.h"

using namespace cloudlut;
using namespace cloudlut::render;
using namespace cloudlut::scene;
using namespace cloudlut::test;

namespace {

// Largest |a − b| over every channel and pixel, over the largest |b| (the image's scale).
double relativeMaxDifference(const Image& a, const Image& b) {
  REQUIRE(a.rgba.size() == b.rgba.size());
  double worst = 0, scale = 0;
  for (std::size_t i = 0; i < a.rgba.size(); ++i) {
    worst = std::max(worst, static_cast<double>(std::abs(a.rgba[i] - b.rgba[i])));
    scale = std::max(scale, static_cast<double>(std::abs(b.rgba[i])));
  }
  return scale > 0 ? worst / scale : worst;
}

}  // namespace

TEST_CASE("sun chord map: overlapping particles render the same from the splat's chords as from computed ones",
          "[render][lighting]") {
  RenderFixture rig = RenderFixture::synthetic(DensityModel::Noise);
  // A tilted stack of overlapping particles, some turned and stretched, under a low sun: the
  // removal subtracts a particle's own ramp where others shadow it too.
  std::vector<Particle> particles;
  for (int n = 0; n < 12; ++n) {
    Particle p;
    p.center = {0.55f * static_cast<float>(n % 4) - 0.8f, 0.45f * static_cast<float>(n / 4) - 0.4f,
                0.3f * static_cast<float>((n * 7) % 5) - 0.6f};
    p.radii = {0.7f + 0.05f * static_cast<float>(n % 3), 0.6f, 0.8f - 0.04f * static_cast<float>(n % 2)};
    p.rotation = quatFromEulerDegrees({11.0f * static_cast<float>(n), -23.0f + 7.0f * static_cast<float>(n), 5.0f});
    p.density = 0.5f + 0.25f * static_cast<float>(n % 4);
    particles.push_back(p);
  }
  RenderSettings s;
  s.width = 128;
  s.height = 96;
  s.view.camera = Camera{{0.9f, 1.4f, 6.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, 45.0f};
  s.view.lighting.sunDirection = glm::normalize(glm::vec3(-0.7f, 0.35f, 0.3f));
  for (const BlendMode mode : {BlendMode::Volume, BlendMode::Alpha}) {
    INFO("blend " << toString(mode));
    s.blend = mode;
    s.sunChordMap = true;
    RenderStats mapped;
    const Image fromMap = rig.renderer.render(particles, s, &mapped);
    s.sunChordMap = false;
    RenderStats computed;
    const Image fromShader = rig.renderer.render(particles, s, &computed);
    REQUIRE(fromMap.nonFiniteCount() == 0);
    std::size_t covered = 0;
    for (std::size_t i = 3; i < fromMap.rgba.size(); i += 4) covered += fromMap.rgba[i] > 0.5f;
    CHECK(covered > fromMap.rgba.size() / 4 / 10);
    CHECK(mapped.sunChordsNeeded > 0);
    CHECK(mapped.sunChordMap);
    CHECK_FALSE(computed.sunChordMap);
    const double difference = relativeMaxDifference(fromMap, fromShader);
    std::printf("[chord map] %s: %zu chords, max difference %.2e of the image's largest value\n",
                toString(mode), mapped.sunChordsNeeded, difference);
    // the same chords through the same ramps: equal up to the compute and fragment stages'
    // rounding (llvmpipe gives bit-identical images)
    CHECK(difference < 1e-5);
  }
}

TEST_CASE("sun chord map: the default cloudscape's cascades render the same from the map", "[render][cloudscape]") {
  RenderFixture rig = RenderFixture::synthetic(DensityModel::Noise);
  const CloudscapeScene scene = loadCloudscape(kDefaultCloudscape);
  RenderSettings s;
  s.width = 128;
  s.height = 72;
  Scene empty;
  empty.view = scene.view;
  s.view = resolveView(empty, {});
  RenderStats mapped;
  s.sunChordMap = true;
  const Image fromMap = rig.renderer.renderCloudscape(scene.cloud, qualityPreset("low"), s, &mapped);
  s.sunChordMap = false;
  const Image fromShader = rig.renderer.renderCloudscape(scene.cloud, qualityPreset("low"), s);
  CHECK(mapped.particles > 100);
  CHECK(mapped.sunChordsNeeded > 0);
  CHECK(mapped.sunChordMap);
  const double difference = relativeMaxDifference(fromMap, fromShader);
  std::printf("[chord map] default cloudscape (low): %zu particles, %zu chords, max difference %.2e\n",
              mapped.particles, mapped.sunChordsNeeded, difference);
  CHECK(difference < 1e-5);
}
