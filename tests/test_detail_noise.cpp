// The detail noise of the density (seed §5.4; lut_formats/glsl/cloudlut_detail_noise.glsl): its
// statistics (zero mean, bounded, the stated spread), the path tracer's use of it (transmittance
// by ratio tracking against an independent quadrature of the modulated extinction), and the
// renderer's (each chord's optical depth times the shared chord factor).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <vector>

#include <glm/geometric.hpp>

#include "core/DetailNoise.h"
#include "core/ReferenceParticle.h"
#include "reference/ScenePathTracer.h"
#include "reference/SphereMonteCarlo.h"
#include "render/Renderer.h"
#include "scene/Scene.h"
#include "support/RenderFixture.h"

using namespace cloudlut;

TEST_CASE("detail noise: zero mean, within [-1, 1], standard deviation about 0.4", "[detail-noise]") {
  reference::McRng rng(11, 0, 0);
  const int n = 100000;
  double sum = 0, sum2 = 0, worst = 0;
  int clipped = 0;
  for (int i = 0; i < n; ++i) {
    const glm::vec3 p(400.0 * rng.next() - 200.0, 400.0 * rng.next() - 200.0, 400.0 * rng.next() - 200.0);
    const double v = glsl::detailNoise(p, 7u);
    sum += v;
    sum2 += v * v;
    worst = std::max(worst, std::abs(v));
    clipped += std::abs(v) >= 1.0;
  }
  const double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
  std::printf("detail noise over %d points: mean %+.4f, sd %.3f, clipped %.2f%%\n", n, mean, sd, 100.0 * clipped / n);
  CHECK(std::abs(mean) < 0.01);  // the points are ~1 feature apart: about independent, se ≈ 0.0013
  CHECK(sd > 0.33);
  CHECK(sd < 0.47);
  CHECK(worst <= 1.0);
  CHECK(clipped < n / 30);

  // The ensemble mean at one point over seeds: zero too (symmetric gradients).
  double seedSum = 0;
  for (std::uint32_t s = 0; s < 20000; ++s) seedSum += glsl::detailNoise(glm::vec3(3.3f, -1.7f, 0.45f), s);
  CHECK(std::abs(seedSum / 20000.0) < 0.01);
}

TEST_CASE("detail noise: the chord factor is 1 when off and the density factor's mean along the chord",
          "[detail-noise]") {
  DetailNoise d;
  CHECK(glsl::detailChordFactor(glm::vec3(0.0f), glm::vec3(5.0f, 1.0f, 0.0f), d.packed()) == 1.0f);
  d.amplitude = 0.8f;
  d.scale = 2.0f;
  const glm::vec4 k = d.packed();
  // A chord shorter than the finest wavelength (s/4): the factor at its midpoint.
  const glm::vec3 a(1.0f, 2.0f, 3.0f), b(1.2f, 2.1f, 3.1f);
  CHECK(glsl::detailChordFactor(a, b, k) == glsl::detailDensityFactor(0.5f * (a + b), k));
  // A chord of 4 feature sizes: 4 points, the coarsest octave alone (the finer ones at their mean 0).
  const glm::vec3 c = a + glm::vec3(8.0f, 0.0f, 0.0f);
  double coarse = 0;
  for (int i = 0; i < 4; ++i)
    coarse += glsl::detailNoiseOctaves(glm::mix(a, c, (float(i) + 0.5f) / 4.0f) * k.y, 1u, 1);
  CHECK(glsl::detailChordFactor(a, c, k) == Approx(1.0 + 0.8 * coarse / 4.0).epsilon(1e-6));
  // Over many random chords the factor averages to 1 (the mean optical depth is kept).
  reference::McRng rng(3, 0, 0);
  double sum = 0, lo = 2, hi = 0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const glm::vec3 p(200.0 * rng.next(), 200.0 * rng.next(), 200.0 * rng.next());
    const glm::vec3 q = p + glm::vec3(8.0 * rng.next() - 4.0, 8.0 * rng.next() - 4.0, 8.0 * rng.next() - 4.0);
    const double f = glsl::detailChordFactor(p, q, k);
    sum += f;
    lo = std::min(lo, f);
    hi = std::max(hi, f);
  }
  CHECK(std::abs(sum / n - 1.0) < 0.01);
  CHECK(lo >= 1.0 - 0.8 - 1e-6);
  CHECK(hi <= 1.0 + 0.8 + 1e-6);
}

TEST_CASE("path tracer: the transmittance through detail noise matches a quadrature of the modulated extinction",
          "[detail-noise][reference-scene]") {
  // One homogeneous sphere (the Sphere model: ρ̂ = 1 inside), optical radius 2.5; the detail's
  // feature size 0.6 of the radius, amplitude 0.8.
  const ReferenceParticle model(DensityModel::Sphere, 1);
  reference::SceneMedium m;
  m.model = &model;
  m.unitOpticalRadius = 2.5;
  m.particles.push_back({glm::dvec3(0.0), glm::dmat3(1.0), 1.0});
  DetailNoise d;
  d.amplitude = 0.8f;
  d.scale = 0.6f;
  m.detail = d.packed();
  reference::ScenePtSettings st;
  reference::SceneLight light;
  int differing = 0;
  for (const double y : {0.0, 0.3, 0.55, 0.8}) {
    const glm::dvec3 o(-3.0, y, 0.17), dir(1.0, 0.0, 0.0);
    // Independent: τ = ∫ σ·m(x) dx over the chord, midpoint rule with 20 000 steps.
    const double half = std::sqrt(1.0 - y * y - 0.17 * 0.17), t0 = 3.0 - half, t1 = 3.0 + half;
    const int steps = 20000;
    double tau = 0;
    for (int i = 0; i < steps; ++i) {
      const double t = t0 + (i + 0.5) * (t1 - t0) / steps;
      tau += 2.5 * glsl::detailDensityFactor(glm::vec3(o + t * dir), m.detail);
    }
    tau *= (t1 - t0) / steps;
    const reference::RayEstimate e = reference::estimateRay(m, light, st, o, dir, 40000, 5);
    const double plain = std::exp(-2.5 * (t1 - t0));
    INFO("y " << y << ": quadrature " << std::exp(-tau) << ", ratio tracking " << e.transmittance << " ± "
              << e.transmittanceSe << ", without detail " << plain);
    CHECK(std::abs(e.transmittance - std::exp(-tau)) < 4.0 * e.transmittanceSe + 1e-4);
    differing += std::abs(plain - std::exp(-tau)) > 6.0 * e.transmittanceSe;
  }
  CHECK(differing >= 3);  // the detail changes these chords' transmittance measurably
}

TEST_CASE("renderer: detail noise multiplies each chord's optical depth by the shared chord factor",
          "[render][detail-noise]") {
  test::RenderFixture rig = test::RenderFixture::synthetic();
  scene::Particle p;
  p.center = {0.3f, -0.2f, 0.1f};
  p.radii = glm::vec3(1.2f);
  p.density = 0.35f;
  render::RenderSettings rs;
  rs.width = 96;
  rs.height = 72;
  rs.view.camera.eye = {0.0f, 0.5f, 5.0f};
  rs.view.camera.target = {0.0f, 0.0f, 0.0f};
  rs.view.camera.fovDeg = 40.0f;
  const render::Image off = rig.renderer.render({p}, rs);
  rs.detail.amplitude = 0.7f;
  rs.detail.scale = 0.25f;
  const render::Image on = rig.renderer.render({p}, rs);
  const scene::CameraFrame camera(rs.view.camera, rs.width, rs.height);
  const glm::vec4 k = rs.detail.packed();
  double worst = 0, ratioSum = 0;
  int n = 0, visible = 0;
  for (int y = 0; y < rs.height; ++y)
    for (int x = 0; x < rs.width; ++x) {
      const float aOff = off.pixel(x, y)[3], aOn = on.pixel(x, y)[3];
      if (!(aOff > 0.02f && aOff < 0.98f && aOn < 0.98f)) continue;
      // The chord of the pixel's ray (eye outside): |e + t·dir − c| = r.
      const glm::vec3 e = camera.eye(), dir = camera.rayDirection(float(x) + 0.5f, float(y) + 0.5f), oc = e - p.center;
      const float b = glm::dot(oc, dir), c = glm::dot(oc, oc) - p.radii.x * p.radii.x, disc = b * b - c;
      if (!(disc > 0.0f)) continue;
      const float tNear = -b - std::sqrt(disc), tExit = -b + std::sqrt(disc);
      const double factor = glsl::detailChordFactor(e + dir * tNear, e + dir * tExit, k);
      const double tauOff = -std::log(1.0 - aOff), tauOn = -std::log(1.0 - aOn);
      worst = std::max(worst, std::abs(tauOn / (tauOff * factor) - 1.0));
      ratioSum += tauOn / tauOff;
      visible += std::abs(tauOn / tauOff - 1.0) > 0.1;
      ++n;
    }
  std::printf("detail noise in the renderer: %d pixels, worst relative error of tau %.2e, mean tau ratio %.4f, "
              "%d pixels changed by more than 10%%\n", n, worst, ratioSum / n, visible);
  REQUIRE(n > 1000);
  CHECK(worst < 2e-3);
  CHECK(std::abs(ratioSum / n - 1.0) < 0.05);
  CHECK(visible > n / 5);
}
