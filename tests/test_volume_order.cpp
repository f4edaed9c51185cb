// Volume-aware blending beyond kMaxSegmentsPerPixel segments per pixel
// (shaders/volume_resolve.comp.glsl): the resolve takes each pixel's list in chunks in a total
// order of the segments, so the image does not depend on the order in which the particle pass
// pushed the fragments; and the chunks are composited front to back, so a stack of disjoint
// particles deeper than one chunk gives what alpha blending (sorted back to front on the CPU)
// gives.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/Errors.h"
#include "render/GlContext.h"
#include "render/HiddenFragments.h"
#include "render/Renderer.h"
#include "render/VolumeResolve.h"
#include "scene/Scene.h"
#include "support/CliRunner.h"
#include "support/RenderFixture.h"
#include "support/RenderLuts.h"
#include "support/SourceScenes.h"

using namespace cloudlut;
using namespace cloudlut::render;
using namespace cloudlut::scene;
using namespace cloudlut::test;

namespace {

// A column of `count` spheres of radius `radius` along −z from the origin, `spacing` apart, each
// shifted sideways by up to `jitter` (a fixed linear congruential sequence), of density `density`
// (the nearer half) and `farDensity` (the farther half).
std::vector<Particle> column(int count, float radius, float spacing, float jitter, float density, float farDensity) {
  std::vector<Particle> ps;
  unsigned state = 12345u;
  auto next = [&state] {  // uniform in [−1, 1)
    state = state * 1664525u + 1013904223u;
    return float(state >> 8) / float(1u << 23) - 1.0f;
  };
  for (int i = 0; i < count; ++i) {
    Particle p;
    p.center = {jitter * next(), jitter * next(), -spacing * float(i)};
    p.radii = glm::vec3(radius);
    p.density = 2 * i < count ? density : farDensity;
    ps.push_back(p);
  }
  return ps;
}

// Looking down the column from z = 6 with a field of view of `fovDeg`.
RenderSettings columnSettings(float fovDeg) {
  RenderSettings s;
  s.width = 40;
  s.height = 30;
  s.view.camera = Camera{{0.0f, 0.0f, 6.0f}, {0.0f, 0.0f, -10.0f}, {0, 1, 0}, fovDeg};
  s.view.lighting.sunDirection = glm::normalize(glm::vec3(0.4f, 0.8f, 0.3f));
  // Per-particle lighting that does not look at the other particles: nothing else depends on the
  // order of the list.
  s.lighting = LightingModel::Seed;
  s.sunlight = SunlightModel::Particle;
  s.occlusion = false;
  s.fragmentsPerPixel = 128;  // room for every fragment
  // every fragment stored, in the order given: these tests are the resolve's (hidden-fragment
  // culling, which sorts the particles and stores fewer, has its own below)
  s.hiddenCulling = false;
  return s;
}

std::size_t mismatches(const std::vector<float>& a, const std::vector<float>& b) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.size(); ++i) n += !(a[i] == b[i] || (std::isnan(a[i]) && std::isnan(b[i])));
  return n;
}

// The largest differences of `image` from `reference`: in opacity (absolute) and in colour
// (relative to the reference, floored at 10⁻³).
struct WorstDifference {
  double alpha = 0, colour = 0;
};
WorstDifference worstDifference(const Image& image, const Image& reference) {
  WorstDifference w;
  for (std::size_t i = 0; i < image.rgba.size(); ++i) {
    const double d = std::abs(double(image.rgba[i]) - double(reference.rgba[i]));
    if (i % 4 == 3)
      w.alpha = std::max(w.alpha, d);
    else
      w.colour = std::max(w.colour, d / std::max(1e-3, double(reference.rgba[i])));
  }
  return w;
}

}  // namespace

TEST_CASE("volume order: more than 32 overlapping segments resolve bit-identically in any submission order",
          "[render][volume]") {
  RenderFixture rig = RenderFixture::synthetic(DensityModel::Noise);
  Renderer& renderer = rig.renderer;
  RenderSettings s = columnSettings(10.0f);
  s.blend = BlendMode::Volume;
  // 90 spheres of radius 1.5, 0.5 apart: each ray near the axis crosses dozens of overlapping ones.
  const std::vector<Particle> ps = column(90, 1.5f, 0.5f, 0.6f, 0.0005f, 0.002f);
  RenderStats stats;
  const Image reference = renderer.render(ps, s, &stats);
  REQUIRE(reference.nonFiniteCount() == 0);
  REQUIRE(stats.fragmentOverflow == 0);
  REQUIRE(stats.truncatedPixels > 100);  // many pixels take more than one chunk
  REQUIRE(1.0f - reference.pixel(s.width / 2, s.height / 2)[3] > 0.05f);  // the far segments show

  std::vector<Particle> reversed(ps.rbegin(), ps.rend());
  std::vector<Particle> interleaved;  // evens, then odds
  for (int start : {0, 1})
    for (std::size_t i = std::size_t(start); i < ps.size(); i += 2) interleaved.push_back(ps[i]);
  const std::vector<std::vector<Particle>> orders = {ps, reversed, interleaved};
  for (std::size_t k = 0; k < orders.size(); ++k) {
    INFO("order " << k);
    RenderStats again;
    const Image image = renderer.render(orders[k], s, &again);
    CHECK(again.truncatedPixels == stats.truncatedPixels);
    CHECK(mismatches(image.rgba, reference.rgba) == 0);
    CHECK(mismatches(image.distance, reference.distance) == 0);
  }
  std::printf("[volume order] %zu fragments, %zu pixels over 32 segments: identical in 3 orders\n", stats.fragments,
              stats.truncatedPixels);
}

TEST_CASE("volume order: the sorting networks resolve lists as the chunked resolve does, in any order",
          "[render][volume]") {
  // Forty spheres of radius 1.5, 0.9 apart along the view: pixels near the axis cross all forty
  // segments, those farther out fewer. The networks take the lists of up to 4, 8, 16 and 32
  // segments, the chunked resolve the rest; with volumeShortList = 0 the chunked one takes every
  // list. All composite a list in one exact sweep (the chunked one has 32 per chunk), so they must
  // agree to rounding; and each must give the same bits whatever order the particles are drawn in.
  RenderFixture rig = RenderFixture::synthetic(DensityModel::Noise);
  Renderer& renderer = rig.renderer;
  RenderSettings s = columnSettings(40.0f);
  s.width = 160;  // enough pixels in every length class
  s.height = 120;
  s.blend = BlendMode::Volume;
  // Drawn in a random order (a fixed shuffle), so that the lists arrive unsorted.
  const std::vector<Particle> inDepthOrder = column(40, 1.5f, 0.9f, 0.8f, 0.3f, 0.6f);
  std::vector<Particle> ps = inDepthOrder;
  unsigned state = 2024u;
  for (std::size_t k = ps.size() - 1; k > 0; --k) {  // Fisher–Yates with a linear congruential sequence
    state = state * 1664525u + 1013904223u;
    std::swap(ps[k], ps[(state >> 8) % (k + 1)]);
  }
  RenderStats stats;
  const Image image = renderer.render(ps, s, &stats);
  REQUIRE(stats.fragmentOverflow == 0);
  REQUIRE(stats.longListPixels > 0);                    // some pixels see more than 32
  REQUIRE(stats.midListPixels > stats.longListPixels);  // some 9 to 32
  REQUIRE(stats.fragments > 9 * stats.midListPixels);   // and many fewer than 9
  RenderSettings chunked = s;
  chunked.volumeShortList = 0;
  RenderStats chunkedStats;
  const Image reference = renderer.render(ps, chunked, &chunkedStats);
  const WorstDifference worst = worstDifference(image, reference);
  std::printf("[volume order] 40 overlapping spheres: %zu fragments, %zu pixels over 8 segments, %zu over %d; "
              "against the chunked resolve opacity %.2e, colour (relative) %.2e\n",
              stats.fragments, stats.midListPixels, stats.longListPixels, kShortListCapacity, worst.alpha,
              worst.colour);
  CHECK(chunkedStats.longListPixels > stats.midListPixels);
  CHECK(worst.alpha < 1e-5);
  CHECK(worst.colour < 1e-4);

  const std::vector<Particle> reversed(ps.rbegin(), ps.rend());
  for (const auto& order : {reversed, inDepthOrder}) {
    const Image again = renderer.render(order, s);
    CHECK(mismatches(again.rgba, image.rgba) == 0);
    CHECK(mismatches(again.distance, image.distance) == 0);
  }

  RenderSettings bad = s;
  bad.volumeShortList = kShortListCapacity + 1;
  CHECK_THROWS_AS(renderer.render(ps, bad), UsageError);
}

TEST_CASE("volume order: a stack of disjoint particles composites front to back like alpha blending",
          "[render][volume]") {
  RenderFixture rig = RenderFixture::synthetic(DensityModel::Noise);
  Renderer& renderer = rig.renderer;
  RenderSettings s = columnSettings(3.0f);
  // Spheres of radius 0.2, 0.45 apart: no two overlap, so no ray's segments do, and volume
  // blending reduces to alpha blending in depth order (seed eqs. 16–17). One: every list holds
  // one segment, which the first resolve composites itself; four: the sorting network of short
  // lists; sixty: the chunked resolve, over more than one chunk.
  for (const int count : {1, 4, 60}) {
    const std::vector<Particle> ps = column(count, 0.2f, 0.45f, 0.03f, 0.001f, 0.02f);
    s.blend = BlendMode::Alpha;
    const Image alpha = renderer.render(ps, s);
    s.blend = BlendMode::Volume;
    RenderStats stats;
    const Image volume = renderer.render(ps, s, &stats);  // front to back: the far ones arrive last
    REQUIRE(stats.fragmentOverflow == 0);
    if (count == 60) REQUIRE(stats.truncatedPixels > 20);
    if (count <= 4) REQUIRE(stats.longListPixels == 0);
    if (count == 1) REQUIRE(stats.fragments > 100);
    const WorstDifference worst = worstDifference(volume, alpha);
    std::printf("[volume order] %d disjoint spheres, %zu pixels over 32 segments: max |volume - alpha| opacity "
                "%.2e, colour (relative) %.2e\n",
                count, stats.truncatedPixels, worst.alpha, worst.colour);
    CHECK(worst.alpha < 1e-4);
    CHECK(worst.colour < 1e-3);
  }
}

TEST_CASE("volume order: the chunked resolve stops behind an opaque chunk, and the image stays alpha blending's",
          "[render][volume]") {
  // Sixty disjoint spheres (as above), the nearer thirty dense: each pixel down the column has
  // more than one chunk of segments, and its first chunk lets through less than
  // kOpaqueTransmittance. The resolve takes no second chunk, and the image is still what alpha
  // blending in depth order gives (the far ones add less than a float's rounding).
  RenderFixture rig = RenderFixture::synthetic(DensityModel::Noise);
  Renderer& renderer = rig.renderer;
  RenderSettings s = columnSettings(3.0f);
  const std::vector<Particle> ps = column(60, 0.2f, 0.45f, 0.03f, 40.0f, 0.02f);
  s.blend = BlendMode::Alpha;
  const Image alpha = renderer.render(ps, s);
  s.blend = BlendMode::Volume;
  RenderStats stats;
  const Image volume = renderer.render(ps, s, &stats);
  REQUIRE(stats.fragmentOverflow == 0);
  REQUIRE(stats.longListPixels > 20);  // lists longer than the sorting networks take, and than a chunk
  // the nearest thirty alone are opaque: what the far ones could add is below kOpaqueTransmittance
  const std::vector<Particle> nearHalf(ps.begin(), ps.begin() + 30);
  s.blend = BlendMode::Alpha;
  const Image nearOnly = renderer.render(nearHalf, s);
  std::size_t opaque = 0;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) opaque += 1.0f - nearOnly.pixel(x, y)[3] < kOpaqueTransmittance ? 1 : 0;
  const WorstDifference worst = worstDifference(volume, alpha);
  std::printf("[volume order] 60 disjoint spheres, the near 30 dense: %zu pixels over 32 segments, %zu opaque "
              "after them, %zu resolved in more than one chunk; max |volume - alpha| opacity %.2e, colour "
              "(relative) %.2e\n",
              stats.longListPixels, opaque, stats.truncatedPixels, worst.alpha, worst.colour);
  REQUIRE(opaque >= 20);
  CHECK(stats.truncatedPixels == 0);
  CHECK(worst.alpha < 1e-4);
  CHECK(worst.colour < 1e-3);
}

TEST_CASE("volume order: a pixel beyond the GL's loop budget is reported, never silently wrong", "[render][volume]") {
  // N identical particles on one spot against one particle N times as dense: the same optical
  // depth, so the same opacity. A pixel with N segments makes about N²/32 loop passes in the
  // resolve; llvmpipe stops an invocation's loops after 65535, which 1000 reach and 300 do not.
  RenderFixture rig = RenderFixture::synthetic(DensityModel::Noise);
  Renderer& renderer = rig.renderer;
  RenderSettings s = columnSettings(40.0f);
  s.width = 16;
  s.height = 12;
  s.blend = BlendMode::Volume;
  s.fragmentsPerPixel = 1024;
  const float totalDensity = 0.12f;
  const Image one = renderer.render({Particle{glm::vec3(0.0f), glm::vec3(1.0f), glm::quat(1, 0, 0, 0), totalDensity}}, s);
  for (const int n : {300, 1000}) {
    const std::vector<Particle> stack(std::size_t(n), Particle{glm::vec3(0.0f), glm::vec3(1.0f), glm::quat(1, 0, 0, 0),
                                                               totalDensity / float(n)});
    RenderStats stats;
    const Image image = renderer.render(stack, s, &stats);
    REQUIRE(stats.fragmentOverflow == 0);
    std::size_t covered = 0, wrong = 0;
    for (int y = 0; y < s.height; ++y)
      for (int x = 0; x < s.width; ++x) {
        covered += one.pixel(x, y)[3] > 0.01f ? 1 : 0;
        wrong += std::abs(image.pixel(x, y)[3] - one.pixel(x, y)[3]) > 1e-3f ? 1 : 0;
      }
    INFO(n << " stacked: " << covered << " covered pixels, " << wrong << " off the dense particle's opacity, "
           << stats.resolveCutPixels << " reported cut");
    REQUIRE(covered > 10);
    CHECK(wrong <= stats.resolveCutPixels);
    if (n == 300) CHECK(stats.resolveCutPixels == 0);
  }
}

TEST_CASE("volume order: fragments hidden behind the stored segments are not shaded, and the image stays alpha "
          "blending's",
          "[render][volume]") {
  // Hidden-fragment culling (render/HiddenFragments.h) against alpha blending in depth order, an
  // independent path that stores no lists and culls nothing: sixty disjoint spheres down the
  // view, (a) the nearer thirty dense, each of them alone letting through less than
  // kHiddenTransmittance; (b) all sixty alike and thin, so that only the sum of the segments in
  // front hides the rest. In both the culled image stays within kHiddenTransmittance of the
  // farther light, and fewer than half the fragments are stored that are without culling.
  RenderFixture rig = RenderFixture::synthetic(DensityModel::Noise);
  Renderer& renderer = rig.renderer;
  RenderSettings s = columnSettings(3.0f);
  struct Case {
    const char* name;
    float nearDensity, farDensity;
  };
  for (const Case c : {Case{"opaque front", 40.0f, 0.02f}, Case{"thin stack", 0.25f, 0.25f}}) {
    INFO(c.name);
    const std::vector<Particle> ps = column(60, 0.2f, 0.45f, 0.03f, c.nearDensity, c.farDensity);
    s.blend = BlendMode::Alpha;
    const Image alpha = renderer.render(ps, s);
    const Image first = renderer.render({ps.front()}, s);
    s.blend = BlendMode::Volume;
    s.hiddenCulling = false;
    RenderStats all;
    renderer.render(ps, s, &all);
    s.hiddenCulling = true;
    RenderStats culled;
    const Image volume = renderer.render(ps, s, &culled);
    REQUIRE(all.fragmentOverflow == 0);
    REQUIRE(culled.fragmentOverflow == 0);
    double firstOpacity = 0;
    for (int y = 0; y < s.height; ++y)
      for (int x = 0; x < s.width; ++x) firstOpacity = std::max(firstOpacity, double(first.pixel(x, y)[3]));
    const WorstDifference worst = worstDifference(volume, alpha);
    std::printf("[volume order] hidden fragments, %s: the nearest sphere's opacity up to %.6f; %zu fragments "
                "stored of %zu; max |culled volume - alpha| opacity %.2e, colour (relative) %.2e\n",
                c.name, firstOpacity, culled.fragments, all.fragments, worst.alpha, worst.colour);
    if (c.nearDensity == c.farDensity)
      REQUIRE(firstOpacity < 1.0 - kHiddenTransmittance);  // no single segment hides anything
    else
      REQUIRE(firstOpacity > 1.0 - kHiddenTransmittance);
    CHECK(2 * culled.fragments < all.fragments);
    CHECK(worst.alpha < kHiddenTransmittance + 1e-5);  // the bound, and the resolve's rounding
    CHECK(worst.colour < 2.0 * kHiddenTransmittance);
  }
}

TEST_CASE("volume order: with the eye inside a particle, culling hidden fragments keeps the image",
          "[render][volume]") {
  // Under culling every proxy is rasterised at the depth of its particle's nearest point, which
  // is 0 for the particle that holds the eye (particle.vert.glsl): its back faces are then clipped
  // at the eye's plane, not the near plane. The 36-particle cluster seen from inside two of its
  // particles: the culled image stays within kHiddenTransmittance of every fragment shaded.
  RenderFixture rig = RenderFixture::synthetic(DensityModel::Noise);
  const Scene scene = sourceScene("data/bench_scenes/cluster36.json");
  RenderSettings s = sceneSettings(scene, 80, 45, BlendMode::Volume);
  for (const glm::vec3 eye : {glm::vec3(1.49f, 0.085f, 0.6f), glm::vec3(1.49f, 0.3f, 0.405f)}) {
    INFO("eye " << eye.x << ", " << eye.y << ", " << eye.z);
    s.view.camera.eye = eye;  // inside particle 5: centre (1.49, 0.085, 0.405), radius 0.542
    s.view.camera.target = {0.0f, 0.1f, 0.0f};
    s.hiddenCulling = false;
    RenderStats all;
    const Image reference = rig.renderer.render(scene.particles, s, &all);
    s.hiddenCulling = true;
    RenderStats culled;
    const Image image = rig.renderer.render(scene.particles, s, &culled);
    REQUIRE(all.fragmentOverflow == 0);
    const WorstDifference worst = worstDifference(image, reference);
    std::printf("[volume order] eye inside a particle of cluster36: %zu fragments stored of %zu; max |culled - all| "
                "opacity %.2e, colour (relative) %.2e\n",
                culled.fragments, all.fragments, worst.alpha, worst.colour);
    CHECK(2 * culled.fragments < all.fragments);
    CHECK(worst.alpha < kHiddenTransmittance + 1e-5);  // the bound, and the resolve's rounding
    CHECK(worst.colour < 2.0 * kHiddenTransmittance);
  }
}
