// A camera inside a particle (particle.frag.glsl: the part of the chord in front of the eye)
// against the path-traced ground truth of the same particles (reference/ScenePathTracer, which
// starts every ray at the eye whatever contains it). The bench cluster with the eye inside one
// particle, looking out of the cluster (the containing particle is all there is to see) and into
// it. The particle used to be discarded; that is the render of the scene without it, which the
// test measures too.
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
#include "support/ImageDifference.h"
#include "support/RenderFixture.h"
#include "support/RenderLuts.h"
#include "support/SourceScenes.h"
#include "support/TempDir.h"

using namespace cloudlut;
using namespace cloudlut::test;

TEST_CASE("camera inside a particle: the front of its chord against the path tracer", "[render][lighting][inside]") {
  constexpr int kWidth = 40, kHeight = 26;
  const Medium medium;  // the defaults: noise particle, seed 1, CS g 0.9 then 0.7
  RenderFixture rig = RenderFixture::defaultMedium(0);  // its tables, converged
  render::Renderer& renderer = rig.renderer;

  const scene::Scene s = sourceScene("data/bench_scenes/cluster.json");
  // Particle 2 (centre (0.156, 0.058, 0.886), radius 0.873) holds the eye; no other one does.
  const std::size_t holder = 2;
  const glm::vec3 eye(0.156f, 0.10f, 1.20f);
  for (std::size_t i = 0; i < s.particles.size(); ++i) {
    const scene::Particle& p = s.particles[i];
    const float r = glm::length(eye - p.center) / p.radii.x;
    REQUIRE((i == holder) == (r < 1.0f));
  }
  std::vector<scene::Particle> without = s.particles;
  without.erase(without.begin() + static_cast<std::ptrdiff_t>(holder));

  struct Case {
    const char* name;
    glm::vec3 target;
    double maxError;  // nc_rel_rmse bound, from the measured figures in docs/LIGHTING.md plus the noise
  };
  const Case cases[] = {{"looking out", {0.156f, 0.4f, 6.0f}, 0.36}, {"looking in", {0.0f, 0.0f, -1.0f}, 0.2}};
  for (const Case& c : cases) {
    INFO(c.name);
    scene::View view = scene::resolveView(s, {});
    view.camera.eye = eye;
    view.camera.target = c.target;
    view.camera.fovDeg = 60.0f;
    reference::ScenePtSettings pt;
    pt.samplesPerPixel = 1024;
    const io::ExrImage ref = reference::renderReferenceScene(s.particles, view, medium, pt, kWidth, kHeight);

    render::RenderSettings rs;
    rs.width = kWidth;
    rs.height = kHeight;
    rs.view = view;
    rs.blend = render::BlendMode::Volume;
    const render::Image inside = renderer.render(s.particles, rs);
    const render::Image discarded = renderer.render(without, rs);
    const reference::ImageErrors e = reference::compareToReference(kWidth, kHeight, inside.rgba.data(), ref);
    const reference::ImageErrors d = reference::compareToReference(kWidth, kHeight, discarded.rgba.data(), ref);
    std::printf("[camera inside] %-11s ref noise %.3f  front segment nc_rel_rmse %.3f bias %+.3f  "
                "discarded nc_rel_rmse %.3f bias %+.3f\n",
                c.name, e.referenceNoise, e.noiseCorrectedRelativeRmse, e.relativeBias, d.noiseCorrectedRelativeRmse,
                d.relativeBias);
    CHECK(inside.nonFiniteCount() == 0);
    CHECK(e.noiseCorrectedRelativeRmse <= c.maxError);
    CHECK(std::abs(e.relativeBias) <= 0.15);
    CHECK(std::abs(e.relativeBias) < 0.5 * std::abs(d.relativeBias));
    CHECK(e.noiseCorrectedRelativeRmse < 0.5 * d.noiseCorrectedRelativeRmse);
  }
}

// The camera flying into a particle: the light along a view ray is continuous in the eye's
// position (a path tracer's images an instant before and after differ by their noise only), so the
// render with the eye just inside the holder's surface matches the one with it just outside. The
// first matter of the seen part used to jump to the eye as it entered (4.1% relative RMSE, bias
// −3.7%, between the two at 160×104).
TEST_CASE("camera inside a particle: no step as the eye enters it", "[render][lighting][inside]") {
  constexpr int kWidth = 80, kHeight = 52;
  RenderFixture rig = RenderFixture::defaultMedium(0);
  const scene::Scene s = sourceScene("data/bench_scenes/cluster.json");
  const scene::Particle& holder = s.particles[2];  // a sphere: centre (0.156, 0.058, 0.886), radius 0.873
  REQUIRE(holder.radii.x == holder.radii.y);
  REQUIRE(holder.radii.x == holder.radii.z);
  // the view of the first test's "looking in", its eye moved back along the view to the surface
  const glm::vec3 inner(0.156f, 0.10f, 1.20f);
  const glm::vec3 dir = glm::normalize(glm::vec3(0.0f, 0.0f, -1.0f) - inner);
  const glm::vec3 o = inner - holder.center;
  const float b = glm::dot(o, dir), c = glm::dot(o, o) - holder.radii.x * holder.radii.x;
  const glm::vec3 surface = inner - (b + std::sqrt(b * b - c)) * dir;  // |surface − centre| = radius
  REQUIRE(std::abs(glm::length(surface - holder.center) - holder.radii.x) < 1e-4f);

  const auto renderFrom = [&](float along) {
    scene::View view = scene::resolveView(s, {});
    view.camera.eye = surface + along * dir;
    view.camera.target = view.camera.eye + dir;
    view.camera.fovDeg = 60.0f;
    render::RenderSettings rs;
    rs.width = kWidth;
    rs.height = kHeight;
    rs.view = view;
    rs.blend = render::BlendMode::Volume;
    return rig.renderer.render(s.particles, rs);
  };
  const render::Image outside = renderFrom(-1e-3f), inside = renderFrom(1e-3f);
  const ColourDifference e = colourDifference(inside, outside);
  REQUIRE(e.pixels > static_cast<std::size_t>(kWidth * kHeight / 2));
  const double step = e.relativeRmse, bias = e.relativeBias;
  std::printf("[camera inside] entering the particle: step %.4f (relative RMSE), bias %+.4f\n", step, bias);
  CHECK(inside.nonFiniteCount() == 0);
  CHECK(step < 0.005);
  CHECK(std::abs(bias) < 0.005);
}
