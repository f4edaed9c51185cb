// The particle pass's proxies (shaders/particle.vert.glsl): a particle seen from afar is
// rasterised as a polygon around its outline, one close by as its bounding box. The fragment
// shader intersects each view ray with the ellipsoid itself, so the proxy changes which pixels
// run the shader, never what they compute: the polygon must give every pixel the box gives a
// fragment (the box, whose back faces cover the ellipsoid from any eye, is the reference).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "render/Renderer.h"
#include "scene/Scene.h"
#include "support/RenderFixture.h"

using namespace cloudlut;
using namespace cloudlut::render;
using namespace cloudlut::scene;
using namespace cloudlut::test;

namespace {

// Ellipsoids of unequal semi-axes, turned every way, at distances from the eye of 1.3 to 40
// bounding radii, some across the image's border; the last one holds the eye (box only).
std::vector<Particle> turnedEllipsoids() {
  std::vector<Particle> ps;
  const glm::vec3 radii[] = {{1.0f, 0.35f, 0.6f}, {0.4f, 1.2f, 0.5f}, {0.7f, 0.7f, 0.2f}, {1.5f, 0.3f, 0.3f}};
  for (int i = 0; i < 24; ++i) {
    Particle p;
    const float a = 0.9f * float(i), distance = 2.0f + 1.6f * float(i);
    p.center = {std::sin(a) * 0.45f * distance, std::cos(1.3f * a) * 0.3f * distance, 6.0f - distance};
    p.radii = radii[i % 4];
    p.rotation = quatFromEulerDegrees({37.0f * float(i), 71.0f * float(i), 13.0f * float(i)});
    p.noiseRotation = quatFromEulerDegrees({11.0f * float(i), 5.0f * float(i), 29.0f * float(i)});
    p.density = 0.5f + 0.25f * float(i % 5);
    ps.push_back(p);
  }
  Particle around;  // the eye inside
  around.center = {0.2f, -0.1f, 5.8f};
  around.radii = {0.8f, 0.6f, 0.7f};
  around.density = 0.002f;
  ps.push_back(around);
  return ps;
}

RenderSettings proxySettings(BlendMode blend, bool polygons) {
  RenderSettings s;
  s.width = 160;
  s.height = 120;
  s.blend = blend;
  s.view.camera = Camera{{0.0f, 0.0f, 6.0f}, {0.0f, 0.0f, -10.0f}, {0, 1, 0}, 60.0f};
  s.view.lighting.sunDirection = glm::normalize(glm::vec3(0.4f, 0.8f, 0.3f));
  s.fragmentsPerPixel = 128;
  s.outlinePolygons = polygons;
  return s;
}

}  // namespace

TEST_CASE("particle proxy: the outline polygons give the box's image and fragments", "[render][proxy]") {
  RenderFixture rig = RenderFixture::synthetic(DensityModel::Noise);
  const std::vector<Particle> ps = turnedEllipsoids();
  for (BlendMode blend : {BlendMode::Volume, BlendMode::Alpha}) {
    INFO((blend == BlendMode::Volume ? "volume" : "alpha"));
    RenderStats boxStats, polygonStats;
    const Image box = rig.renderer.render(ps, proxySettings(blend, false), &boxStats);
    const Image polygon = rig.renderer.render(ps, proxySettings(blend, true), &polygonStats);
    REQUIRE(box.nonFiniteCount() == 0);
    double worstAlpha = 0, worstColour = 0, squares = 0, covered = 0;
    for (std::size_t i = 0; i < box.rgba.size(); ++i) {
      const double d = std::abs(double(polygon.rgba[i]) - double(box.rgba[i]));
      squares += d * d;
      if (i % 4 == 3) {
        worstAlpha = std::max(worstAlpha, d);
        covered += box.rgba[i] > 0.2f;  // the eye's own particle adds little everywhere
      } else {
        worstColour = std::max(worstColour, d / std::max(1e-2, double(box.rgba[i])));
      }
    }
    const double rms = std::sqrt(squares / double(box.rgba.size()));
    std::printf("[particle proxy] %s: %.0f pixels over 0.2 opacity, fragments box %zu polygon %zu; difference rms "
                "%.2e, worst opacity %.2e, colour (relative) %.2e\n",
                blend == BlendMode::Volume ? "volume" : "alpha", covered, boxStats.fragments, polygonStats.fragments,
                rms, worstAlpha, worstColour);
    CHECK(covered > 0.1 * box.width * box.height);  // the scene fills a good part of the image
    // The view rays differ in their last bits (interpolated over other triangles); llvmpipe
    // filters textures with 8-bit weights, so a few pixels move by a step of a table's filter
    // (up to ~5·10⁻³ in opacity). A pixel the polygon missed would lose its whole opacity.
    CHECK(rms < 1e-4);
    CHECK(worstAlpha < 1e-2);
    CHECK(worstColour < 5e-2);
    if (blend == BlendMode::Volume) {
      REQUIRE(boxStats.fragments > 10000);
      CHECK(std::llabs(static_cast<long long>(polygonStats.fragments) - static_cast<long long>(boxStats.fragments)) <=
            2 + static_cast<long long>(boxStats.fragments / 10000));
    }
  }
}
