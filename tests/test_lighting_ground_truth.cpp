// The lighting models against the path-traced ground truth of the same particles
// (reference/ScenePathTracer, an independent Monte Carlo of the same medium): the cloud model
// (docs/LIGHTING.md) must bring an isolated ρ = 1 particle and the 9-particle bench cluster
// within bounds that the seed's model (§4.4, §5.3) misses. Both use the default converged
// tables (the test fixture) and the default noise particle.
//
// Metric: relative RMSE over the cloud pixels with the reference's own Monte Carlo variance
// removed (reference/SceneCompare.h, nc_rel_rmse), and the relative bias.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <string>

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
    const scene::Scene s = scene::readScene(std::string(CLOUDLUT_SOURCE_DIR) + "/data/bench_scenes/" + c.scene + ".json");
    const scene::View view = scene::resolveView(s, {});
    reference::ScenePtSettings pt;
    pt.samplesPerPixel = c.spp;
    const io::ExrImage ref = reference::renderReferenceScene(s.particles, view, medium, pt, kWidth, kHeight);

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

// Looking toward the sun, the thin rim of a noise particle glows (silver lining): its single
// scattering against the path tracer's `single` channel (next-event estimation only, so far less
// noisy than the total). The homogeneous sphere at the chord's mean density (the table alone,
// the seed's single term) measured −24% at 96×64 (docs/LIGHTING.md): the particle's thin
// outskirts pass more sunlight than that sphere. The cloud model's singleSunTransmittance
// measured +4% with the default tables at 96×64; with this fixture's coarser optical-depth table
// (32×16×32×16, which blurs the rim) +13%, against −20% for the table alone.
TEST_CASE("lighting: the backlit rim's single scattering against the path tracer", "[render][lighting]") {
  // The rim is a thin crescent: at the bench's 96×64 it covers enough pixel centres for its sum
  // to be stable (at 64×44 the sampled sum moved the ratio by 9 points).
  constexpr int kRimWidth = 96, kRimHeight = 64;
  const Medium medium;
  RenderFixture rig = RenderFixture::defaultMedium(0);
  const scene::Scene s = scene::readScene(std::string(CLOUDLUT_SOURCE_DIR) + "/data/bench_scenes/backlit.json");
  const scene::View view = scene::resolveView(s, {});
  reference::ScenePtSettings pt;
  pt.samplesPerPixel = 64;
  const io::ExrImage ref = reference::renderReferenceScene(s.particles, view, medium, pt, kRimWidth, kRimHeight);
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
  const scene::Scene s = scene::readScene(std::string(CLOUDLUT_SOURCE_DIR) + "/data/bench_scenes/cluster.json");
  scene::View view = scene::resolveView(s, {});
  view.lighting.sunColor = glm::vec3(0.0f);
  view.lighting.skyColor = glm::vec3(1.0f);
  view.lighting.skyBelow = glm::vec3(0.1f);
  reference::ScenePtSettings pt;
  pt.samplesPerPixel = 64;
  const io::ExrImage ref = reference::renderReferenceScene(s.particles, view, medium, pt, kWidth, kHeight);
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
