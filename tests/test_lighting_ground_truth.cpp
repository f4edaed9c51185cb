// The lighting models against the path-traced ground truth of the same particles
// (reference/ScenePathTracer, an independent Monte Carlo of the same medium): the cloud model
// (docs/LIGHTING.md) must bring an isolated ρ = 1 particle and the 9-particle bench cluster
// within bounds that the seed's model (§4.4, §5.3) misses. Both use the default converged
// tables (the test fixture) and the default noise particle.
//
// Metric: relative RMSE over the cloud pixels with the reference's own Monte Carlo variance
// removed (reference/SceneCompare.h, nc_rel_rmse), and the relative bias.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "bake/OpticalDepthBaker.h"
#include "core/Medium.h"
#include "reference/ReferenceImage.h"
#include "reference/SceneCompare.h"
#include "render/GlContext.h"
#include "render/Renderer.h"
#include "scene/Scene.h"
#include "support/BakedFixtures.h"
#include "support/RenderFixture.h"
#include "support/RenderLuts.h"
#include "support/SourceScenes.h"
#include "support/TempDir.h"

using namespace cloudlut;
using namespace cloudlut::test;

namespace {

constexpr int kWidth = 64, kHeight = 44;

struct Judged {
  double ncRelRmse = 0, relBias = 0, refNoise = 0;
};

Judged judge(const render::Image& img, const io::ExrImage& ref) {
  const reference::ImageErrors e = reference::compareToReference(img.width, img.height, img.rgba.data(), ref);
  return {e.noiseCorrectedRelativeRmse, e.relativeBias, e.referenceNoise};
}

// The renderer's settings for one lighting model, as the bench renders it (volume-aware).
render::RenderSettings settingsFor(const scene::View& view, int width, int height, render::LightingModel lighting) {
  render::RenderSettings rs;
  rs.width = width;
  rs.height = height;
  rs.view = view;
  rs.blend = render::BlendMode::Volume;
  rs.lighting = lighting;
  rs.sunlight = render::defaultSunlight(lighting);
  return rs;
}

// A bench scene (data/bench_scenes/<name>.json).
scene::Scene benchScene(const std::string& name) {
  return sourceScene("data/bench_scenes/" + name + ".json");
}

// The path tracer's image of the particles seen from `view`, `spp` paths per pixel.
io::ExrImage pathTraced(const scene::Scene& s, const scene::View& view, const Medium& medium, int spp, int width,
                        int height) {
  reference::ScenePtSettings pt;
  pt.samplesPerPixel = spp;
  return reference::renderReferenceScene(s.particles, view, medium, pt, width, height);
}

}  // namespace

TEST_CASE("lighting: the cloud model meets the path tracer where the seed's model misses", "[render][lighting]") {
  const Medium medium;  // the defaults: noise particle, seed 1, CS g 0.9 then 0.7
  RenderFixture rig = RenderFixture::defaultMedium(0);  // its tables, converged
  render::Renderer& renderer = rig.renderer;

  struct Case {
    const char* scene;
    int spp;
    double cloudMax, cloudBiasMax, seedMin;  // bounds on nc_rel_rmse and |rel_bias|
  };
  // Measured at 96×64 (docs/LIGHTING.md): one ρ = 1 particle, seed 30.5% (bias +29%), cloud
  // 7.0% (+3.3%); the 9-particle cluster, seed 19.7% (−13%), cloud 13.7% (−4.6%).
  const Case cases[] = {{"one-rho1", 256, 0.12, 0.07, 0.22}, {"cluster", 128, 0.15, 0.08, 0.15}};
  for (const Case& c : cases) {
    INFO(c.scene);
    const scene::Scene s = benchScene(c.scene);
    const scene::View view = scene::resolveView(s, {});
    const io::ExrImage ref = pathTraced(s, view, medium, c.spp, kWidth, kHeight);

    Judged j[2];
    for (const render::LightingModel lighting : {render::LightingModel::Seed, render::LightingModel::Cloud}) {
      j[lighting == render::LightingModel::Cloud] =
          judge(renderer.render(s.particles, settingsFor(view, kWidth, kHeight, lighting)), ref);
    }
    std::printf("lighting ground truth %-9s ref noise %.3f  seed nc_rel_rmse %.3f bias %+.3f  cloud %.3f bias %+.3f\n",
                c.scene, j[0].refNoise, j[0].ncRelRmse, j[0].relBias, j[1].ncRelRmse, j[1].relBias);
    // The reference is noisy at this size (relative noise 17% and 26% measured); its variance is
    // subtracted per pixel, which over ~1000 cloud pixels reproduced the low-noise 96×64 figures
    // within 2 points (one-rho1: seed 31.7%, cloud 9.1%; cluster: seed 17.4%, cloud 11.4%).
    CHECK(j[0].refNoise < 0.35);
    CHECK(j[1].ncRelRmse <= c.cloudMax);
    CHECK(std::abs(j[1].relBias) <= c.cloudBiasMax);
    CHECK(j[0].ncRelRmse >= c.seedMin);
    CHECK(j[1].ncRelRmse < 0.75 * j[0].ncRelRmse);
  }
}

// The diffusion volume (render/DiffusionVolume.h, docs/LIGHTING.md): on the bench's 40-particle
// cloudscape (three heaps) the tables' spheres leave each heap's shadowed half too dark; the
// flux-limited diffusion solve over the particles lets the light through. Measured at 96×64
// (the ground-truth suite): 14.8% (bias −7.8%) without, 7.7% (+0.2%) with; at this fixture's
// 64×44 the reference's noise (23% at 128 paths) hid the error with it, hence 384 paths.
TEST_CASE("lighting: the diffusion volume brings a cloud of heaps closer to the path tracer", "[render][lighting]") {
  const Medium medium;
  RenderFixture rig = RenderFixture::defaultMedium(0);
  const scene::Scene s = benchScene("cloudscape");
  const scene::View view = scene::resolveView(s, {});
  const io::ExrImage ref = pathTraced(s, view, medium, 384, kWidth, kHeight);
  Judged j[2];
  for (int diffusion = 0; diffusion < 2; ++diffusion) {
    render::RenderSettings rs = settingsFor(view, kWidth, kHeight, render::LightingModel::Cloud);
    rs.diffusionShare = diffusion ? 1.0f : 0.0f;
    j[diffusion] = judge(rig.renderer.render(s.particles, rs), ref);
  }
  std::printf("lighting ground truth cloudscape ref noise %.3f  tables nc_rel_rmse %.3f bias %+.3f  diffusion %.3f bias %+.3f\n",
              j[0].refNoise, j[0].ncRelRmse, j[0].relBias, j[1].ncRelRmse, j[1].relBias);
  CHECK(j[1].refNoise < 0.35);
  CHECK(j[1].ncRelRmse < 0.8 * j[0].ncRelRmse);
  CHECK(std::abs(j[1].relBias) < 0.5 * std::abs(j[0].relBias));
}

// The particle's own multiple-scattering term closed per exit direction (core/AngularClosure.h):
// a dense noise particle seen from its sunlit side. The homogeneous sphere at the chords' mean
// density reflects too much of the light back toward the sun: at 96×64 the cloud model measured
// nc_rel_rmse 11.6%, bias +7.9% without the closure and 8.3%, +1.5% with it (docs/LIGHTING.md).
// Issue 17's bound (10%, |bias| 3%) must hold with the closure and the bias bound fail without it.
TEST_CASE("lighting: the angular closure brings a dense particle within the issue's bounds", "[render][lighting]") {
  const Medium medium;
  const scene::Scene s = benchScene("one-rho4");
  const scene::View view = scene::resolveView(s, {});
  const io::ExrImage ref = pathTraced(s, view, medium, 256, kWidth, kHeight);
  Judged j[2];
  for (const bool closure : {false, true}) {
    RenderFixture rig = RenderFixture::defaultMedium(0, closure);
    render::RenderSettings rs = settingsFor(view, kWidth, kHeight, render::LightingModel::Cloud);
    rs.diffusionShare = 0.0f;  // the closure is the tables' (with the diffusion volume: 6.8%, bias −2.4%)
    j[closure] = judge(rig.renderer.render(s.particles, rs), ref);
  }
  std::printf("one-rho4: ref noise %.3f  without the closure nc_rel_rmse %.3f bias %+.3f  with it %.3f bias %+.3f\n",
              j[0].refNoise, j[0].ncRelRmse, j[0].relBias, j[1].ncRelRmse, j[1].relBias);
  CHECK(j[1].refNoise < 0.25);  // its variance is removed per pixel (the first test case)
  CHECK(j[1].ncRelRmse <= 0.10);
  CHECK(std::abs(j[1].relBias) <= 0.03);
  CHECK(j[0].relBias > 0.05);
}

// The particle's own core shadow (ownCoreShadow, docs/LIGHTING.md): seen toward the sun, the
// reference's rim is bright on the side toward the sun and dark behind the particle's dense core,
// where the own term's homogeneous sphere of the chord's mean density lights it all round. At
// 96×64 with the default tables the cloud model measured nc_rel_rmse 16.8% (bias −0.7%) without
// the core shadow and 9.5% (−1.5%) with it (brightening by at most 1.2), each with its own
// closure; this fixture (half the closure's photons, a 512-path reference) 17.1% and 9.8%. The
// core shadow must lower the error by at least a third, and the bias stay within 3%.
TEST_CASE("lighting: the own core shadow darkens the backlit particle's far rim as the path tracer does",
          "[render][lighting]") {
  constexpr int kRimWidth = 96, kRimHeight = 64;
  const Medium medium;
  const scene::Scene s = benchScene("backlit");
  const scene::View view = scene::resolveView(s, {});
  const io::ExrImage ref = pathTraced(s, view, medium, 512, kRimWidth, kRimHeight);
  Judged j[2];
  for (const bool coreShadow : {false, true}) {
    RenderFixture rig = RenderFixture::defaultMedium(0, true, 8000, coreShadow);
    j[coreShadow] =
        judge(rig.renderer.render(s.particles, settingsFor(view, kRimWidth, kRimHeight, render::LightingModel::Cloud)), ref);
  }
  std::printf("backlit: ref noise %.3f  without the core shadow nc_rel_rmse %.3f bias %+.3f  with it %.3f bias %+.3f\n",
              j[0].refNoise, j[0].ncRelRmse, j[0].relBias, j[1].ncRelRmse, j[1].relBias);
  CHECK(j[1].refNoise < 0.3);
  CHECK(j[1].ncRelRmse < 0.67 * j[0].ncRelRmse);
  CHECK(std::abs(j[1].relBias) <= 0.03);
}

// Looking toward the sun, the thin rim of a noise particle glows (silver lining): its single
// scattering against the path tracer's `single` channel (next-event estimation only, so far less
// noisy than the total). The homogeneous sphere at the chord's mean density (the table alone,
// the seed's single term) measured −24% at 96×64 (docs/LIGHTING.md): the particle's thin
// outskirts pass more sunlight than that sphere. The cloud model's singleSunTransmittance
// measured +4% with the default tables at 96×64 (2026-12-02); with this fixture's coarser
// optical-depth table (32×16×32×16, which blurs the rim) −3.1% since the chords end at their last
// matter (2026-12-03), against −20% for the table alone.
TEST_CASE("lighting: the backlit rim's single scattering against the path tracer", "[render][lighting]") {
  // The rim is a thin crescent: at the bench's 96×64 it covers enough pixel centres for its sum
  // to be stable (at 64×44 the sampled sum moved the ratio by 9 points).
  constexpr int kRimWidth = 96, kRimHeight = 64;
  const Medium medium;
  RenderFixture rig = RenderFixture::defaultMedium(0);
  const scene::Scene s = benchScene("backlit");
  const scene::View view = scene::resolveView(s, {});
  const io::ExrImage ref = pathTraced(s, view, medium, 64, kRimWidth, kRimHeight);
  const std::vector<float>& refSingle = ref.channel("single");
  const std::vector<float>& refAlpha = ref.channel("A");

  double bias[2] = {0, 0};
  for (const render::LightingModel lighting : {render::LightingModel::Seed, render::LightingModel::Cloud}) {
    render::RenderSettings rs = settingsFor(view, kRimWidth, kRimHeight, lighting);
    rs.terms = render::kTermSingle;
    const render::Image img = rig.renderer.render(s.particles, rs);
    double sumRender = 0, sumRef = 0;
    for (std::size_t i = 0; i < refSingle.size(); ++i) {
      if (refAlpha[i] <= 0.01f && img.rgba[4 * i + 3] <= 0.01f) continue;
      sumRender += img.rgba[4 * i + 1];  // green: the sun colour is white, so every channel is the term
      sumRef += refSingle[i];
    }
    REQUIRE(sumRef > 0);
    bias[lighting == render::LightingModel::Cloud] = sumRender / sumRef - 1.0;
  }
  std::printf("backlit single scattering: relative bias seed %+.3f, cloud %+.3f\n", bias[0], bias[1]);
  CHECK(std::abs(bias[1]) <= 0.17);
  CHECK(bias[0] <= -0.15);
}

// The ambient under a sky from above (docs/LIGHTING.md, item 5): sky radiance 1 above the
// horizon, 0.1 below (the ground's return), no sun, against the path tracer's sky of the same
// shape. The uniform-sky formula sky·(1 − e^{−τ}) (what the cloud model gives with skyBelow 1)
// measured +80% (nc_rel_rmse 81%) on the 9-particle cluster at 64×44, 128 paths; the layered
// ambient +6.0% (9.0%), the reference's noise 6.5%.
TEST_CASE("lighting: the ambient under a sky from above against the path tracer", "[render][lighting]") {
  const Medium medium;
  RenderFixture rig = RenderFixture::defaultMedium(0);
  const scene::Scene s = benchScene("cluster");
  scene::View view = scene::resolveView(s, {});
  view.lighting.sunColor = glm::vec3(0.0f);
  view.lighting.skyColor = glm::vec3(1.0f);
  view.lighting.skyBelow = glm::vec3(0.1f);
  const io::ExrImage ref = pathTraced(s, view, medium, 64, kWidth, kHeight);
  Judged j[2];
  for (const float below : {1.0f, 0.1f}) {
    scene::View rendered = view;
    rendered.lighting.skyBelow = glm::vec3(below);
    j[below < 1.0f] = judge(rig.renderer.render(s.particles, settingsFor(rendered, kWidth, kHeight,
                                                                          render::LightingModel::Cloud)), ref);
  }
  std::printf("ambient under a sky from above: ref noise %.3f  uniform-sky formula nc_rel_rmse %.3f bias %+.3f  layered "
              "%.3f bias %+.3f\n", j[0].refNoise, j[0].ncRelRmse, j[0].relBias, j[1].ncRelRmse, j[1].relBias);
  CHECK(j[0].ncRelRmse >= 0.5);
  CHECK(j[1].ncRelRmse <= 0.15);
  CHECK(std::abs(j[1].relBias) <= 0.10);
}

// Continuity (issue 17): where one particle's disc lies over another's, the rendered radiance
// must not step where the path-traced radiance of the same particles is smooth. On the bench's
// two overlapping particles, both images are smoothed by the same 3×3 box (which averages the
// reference's Monte Carlo noise down by 3 and spreads a step over three pixel pairs); then every
// pair of neighbouring pixels inside the cloud (reference opacity > 0.5, across and down) is
// compared: the render's step |ΔL| may exceed the reference's |ΔL_ref| only by 3 standard errors
// of the smoothed reference's difference plus 0.002 (2% of the cloud's radiance). The seed's
// model, each particle lit by one sunlight value and its own sphere, steps at its inner disc
// edges; the bound is set where the cloud model passes and the seed's model does not (counts in
// docs/LIGHTING.md).
namespace {

// The 3×3 box mean of a row-major image channel (clamped at the borders), and the standard error
// of that mean from per-pixel standard errors (independent pixels).
std::vector<double> boxMean(const std::vector<float>& v, int w, int h, std::size_t stride, bool errors) {
  std::vector<double> out(static_cast<std::size_t>(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double sum = 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int xx = std::clamp(x + dx, 0, w - 1), yy = std::clamp(y + dy, 0, h - 1);
          const double s = v[stride * (static_cast<std::size_t>(yy) * w + xx)];
          sum += errors ? s * s : s;
        }
      out[static_cast<std::size_t>(y) * w + x] = errors ? std::sqrt(sum) / 9.0 : sum / 9.0;
    }
  return out;
}

}  // namespace

TEST_CASE("lighting: no step between overlapping particles that the path tracer does not have", "[render][lighting]") {
  constexpr int kW = 96, kH = 64;
  const Medium medium;
  RenderFixture rig = RenderFixture::defaultMedium(0);
  const scene::Scene s = benchScene("two");
  const scene::View view = scene::resolveView(s, {});
  const io::ExrImage ref = pathTraced(s, view, medium, 512, kW, kH);
  const std::vector<double> refR = boxMean(ref.channel("R"), kW, kH, 1, false);
  const std::vector<double> refSe = boxMean(ref.channel("stderr.R"), kW, kH, 1, true);
  const std::vector<float>& refA = ref.channel("A");

  // the seed's model, the cloud model's tables alone, and the cloud model with the diffusion volume
  int steps[3] = {0, 0, 0}, pairs = 0;
  double worst[3] = {-1, -1, -1};
  for (int m = 0; m < 3; ++m) {
    render::RenderSettings rs =
        settingsFor(view, kW, kH, m == 0 ? render::LightingModel::Seed : render::LightingModel::Cloud);
    if (m == 1) rs.diffusionShare = 0.0f;
    const std::vector<double> r = boxMean(rig.renderer.render(s.particles, rs).rgba, kW, kH, 4, false);
    pairs = 0;
    for (int y = 0; y < kH; ++y) {
      for (int x = 0; x < kW; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * kW + x;
        for (const std::size_t j : {x + 1 < kW ? i + 1 : i, y + 1 < kH ? i + kW : i}) {
          if (j == i || refA[i] <= 0.5f || refA[j] <= 0.5f) continue;
          ++pairs;
          const double excess = std::abs(r[j] - r[i]) - std::abs(refR[j] - refR[i]) -
                                3.0 * std::hypot(refSe[i], refSe[j]) - 0.002;
          worst[m] = std::max(worst[m], excess);
          steps[m] += excess > 0.0;
        }
      }
    }
  }
  std::printf("steps beyond the path tracer's (of %d neighbour pairs): seed %d (worst excess %+.4f), cloud tables %d "
              "(%+.4f), cloud with diffusion %d (%+.4f)\n", pairs, steps[0], worst[0], steps[1], worst[1], steps[2],
              worst[2]);
  REQUIRE(pairs > 500);
  CHECK(steps[1] == 0);
  // The diffusion's share changes with each particle's cloud weight (diffusionShareOfMultiple), so
  // where the two overlap it may step a little: measured one pair, by 0.0006 beyond the margin.
  CHECK(worst[2] < 0.002);
  CHECK(steps[2] <= 3);
  CHECK(steps[0] >= 5);
}
