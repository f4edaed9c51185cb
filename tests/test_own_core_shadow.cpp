// The own term's core shadow (docs/LIGHTING.md, "The particle's own core shadow"): the shared
// functions of cloudlut_shading.glsl against their definitions computed here, and the particle's
// own optical depth toward the sun from the optical-depth table (core/OwnSunDepth.h) against a
// direct integration of the particle's density along the sun ray.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <utility>

#include <glm/geometric.hpp>

#include "bake/ChordMatterProfile.h"
#include "bake/OpticalDepthBaker.h"
#include "core/Defaults.h"
#include "core/Glsl.h"
#include "core/Medium.h"
#include "core/OwnSunDepth.h"
#include "core/ReferenceParticle.h"
#include "core/TableLookup.h"

using namespace cloudlut;

namespace {

// Distance from x inside the unit sphere to its surface along unit d, by bisection on |x + t·d|.
double exitByBisection(const glm::dvec3& x, const glm::dvec3& d) {
  double lo = 0.0, hi = 2.0;
  for (int i = 0; i < 80; ++i) {
    const double mid = 0.5 * (lo + hi);
    (glm::dot(x + mid * d, x + mid * d) < 1.0 ? lo : hi) = mid;
  }
  return lo;
}

// max(e^{−τ}, 1/(1 + ¾(1 − g)τ)): the direct or the two-stream diffuse transmittance.
double sunlight(double tau, double g) { return std::max(std::exp(-tau), 1.0 / (1.0 + 0.75 * (1.0 - g) * tau)); }

Table4D depthTable(DensityModel model) {
  bake::OpticalDepthSettings ods;
  ods.dims = {64, 32, 64, 32};
  return bake::bakeOpticalDepth(ReferenceParticle(model, 1), ods);
}

// ∫ σ·ρ·ρ̂(x + t·l) dt from x to the sphere's surface toward the sun (midpoint rule).
double integratedToSun(const ReferenceParticle& particle, double sigma, float rho, const glm::vec3& x,
                       const glm::vec3& l) {
  const double length = exitByBisection(glm::dvec3(x), glm::dvec3(l));
  constexpr int kSteps = 4000;
  double sum = 0.0;
  for (int i = 0; i < kSteps; ++i)
    sum += particle.density(x + static_cast<float>((i + 0.5) * length / kSteps) * l);
  return sigma * rho * sum * length / kSteps;
}

}  // namespace

TEST_CASE("own core shadow: the shared functions against their definitions", "[closure][core-shadow]") {
  const glm::vec3 points[] = {{0, 0, 0}, {0.3f, -0.2f, 0.5f}, {-0.7f, 0.1f, 0.2f}, {0.05f, 0.9f, -0.3f}};
  const glm::vec3 dirs[] = {glm::normalize(glm::vec3(1, 2, 3)), glm::normalize(glm::vec3(-0.4f, 0.1f, 0.9f)),
                            glm::vec3(0, -1, 0)};
  for (const glm::vec3& x : points)
    for (const glm::vec3& d : dirs) {
      const double exact = exitByBisection(glm::dvec3(x), glm::dvec3(d));
      CHECK(glsl::unitSphereExitDistance(x, d) == Approx(exact).margin(1e-5));
      CHECK(glsl::homogeneousOwnSunDepth(x, d, 1.5f, 12.0f) == Approx(1.5 * 12.0 * exact).epsilon(1e-5));
    }
  CHECK(glsl::unitSphereExitDistance(glm::vec3(0, 0, 2), glm::vec3(0, 0, 1)) == 0.0f);  // outside, past it

  // the ramp: 0 before the first matter, the whole chord after the last, half at the middle,
  // the outer third's share a third of the way, linear within each third; even (linear
  // throughout) for a = 1/3
  for (const float a : {0.265f, 1.0f / 3.0f, 0.5f}) {
    INFO("outer third " << a);
    CHECK(glsl::ownSunRamp(6.0f, 0.2f, 0.8f, 0.1f, a) == 0.0f);
    CHECK(glsl::ownSunRamp(6.0f, 0.2f, 0.8f, 0.3f, a) == Approx(6.0f * a * 0.5f));
    CHECK(glsl::ownSunRamp(6.0f, 0.2f, 0.8f, 0.4f, a) == Approx(6.0f * a));
    CHECK(glsl::ownSunRamp(6.0f, 0.2f, 0.8f, 0.5f, a) == Approx(3.0f));
    CHECK(glsl::ownSunRamp(6.0f, 0.2f, 0.8f, 0.7f, a) == Approx(6.0f * (1.0f - a * 0.5f)));
    CHECK(glsl::ownSunRamp(6.0f, 0.2f, 0.8f, 0.95f, a) == Approx(6.0f));
  }
  for (const float s : {0.0f, 0.13f, 0.37f, 0.5f, 0.71f, 1.0f})
    CHECK(glsl::chordMatterShare(s, 1.0f / 3.0f) == Approx(s).margin(1e-6));
  // the splat's slope steps: the changes of the share's slope (central differences inside each
  // third, 0 outside the span) across u = 0, 1/3, 2/3, 1
  for (const float a : {0.0f, 0.265f, 1.0f / 3.0f, 0.5f}) {
    INFO("outer third " << a);
    const auto slope = [a](double u) {
      constexpr double h = 1e-3;
      return (glsl::chordMatterShare(static_cast<float>(u + h), a) - glsl::chordMatterShare(static_cast<float>(u - h), a)) /
             (2.0 * h);
    };
    const double slopes[] = {slope(-0.1), slope(1.0 / 6.0), slope(0.5), slope(5.0 / 6.0), slope(1.1)};
    const glm::vec4 steps = glsl::chordMatterSlopeSteps(a);
    for (int q = 0; q < 4; ++q) CHECK(steps[q] == Approx(slopes[q + 1] - slopes[q]).margin(2e-3));
  }

  // the mean scattering point: the e^{−τ(t − first)/(last − first)}-weighted mean of t over the
  // matter [first, last] (midpoint rule), for transparent to opaque chords
  for (const float tau : {1e-4f, 0.3f, 2.0f, 15.0f})
    for (const auto& [first, last] : {std::pair{0.0f, 1.0f}, std::pair{0.1f, 0.7f}, std::pair{0.45f, 0.55f}}) {
      constexpr int kSteps = 20000;
      double weighted = 0.0, total = 0.0;
      for (int i = 0; i < kSteps; ++i) {
        const double t = first + (i + 0.5) * (last - first) / kSteps;
        const double w = std::exp(-tau * (t - first) / (last - first));
        weighted += w * t;
        total += w;
      }
      INFO("tau " << tau << ", matter [" << first << ", " << last << "]");
      CHECK(glsl::meanScatteringShare(first, last, tau) == Approx(weighted / total).margin(1e-5));
    }

  // the factor: the ratio of the two sunlights, at most the bound (1: only ever darkens)
  const float g = 0.757f;
  for (const float most : {1.0f, 1.2f, 4.0f})
    for (const float own : {0.0f, 0.5f, 2.0f, 9.0f, 40.0f})
      for (const float hom : {0.0f, 0.3f, 3.0f, 20.0f}) {
        const double expected = std::min(sunlight(own, g) / sunlight(hom, g), static_cast<double>(most));
        INFO("tau own " << own << ", tau homogeneous " << hom << ", bound " << most);
        CHECK(glsl::ownCoreShadow(own, hom, g, most) == Approx(expected).epsilon(1e-5));
        if (own >= hom) CHECK(glsl::ownCoreShadow(own, hom, g, most) <= 1.0f);
      }
}

TEST_CASE("own core shadow: the own optical depth toward the sun from the table", "[closure][core-shadow]") {
  const Medium medium;
  const double sigma = medium.unitOpticalRadius();
  const glm::vec3 l = glm::normalize(glm::vec3(0.3f, 0.8f, -0.5f));

  SECTION("a homogeneous sphere: the table's ramp is the exact optical depth") {
    const Table4D od = depthTable(DensityModel::Sphere);
    const ReferenceParticle sphere(DensityModel::Sphere, 1);
    for (const glm::vec3& x : {glm::vec3(0, 0, 0), glm::vec3(0.4f, -0.3f, 0.2f), glm::vec3(-0.5f, -0.5f, 0.5f)}) {
      const double exact = integratedToSun(sphere, sigma, 2.0f, x, l);
      INFO("x " << x.x << " " << x.y << " " << x.z);
      CHECK(ownSunOpticalDepth(od, chordOuterThird(od), x, l, 2.0f) == Approx(exact).epsilon(0.03));
    }
  }
  SECTION("the noise particle: behind its last matter the whole chord, before its first none") {
    const Table4D od = depthTable(medium.model);
    const ReferenceParticle particle(medium.model, medium.seed);
    int behind = 0;
    for (int i = 0; i < 12; ++i) {
      // points near the surface on the side away from the sun, and on the side toward it
      const float a = 0.52f * static_cast<float>(i);
      glm::vec3 t = glm::normalize(glm::cross(l, glm::vec3(0, 0, 1)));
      const glm::vec3 u = glm::cross(l, t);
      const glm::vec3 offset = 0.35f * (std::cos(a) * t + std::sin(a) * u);
      const float depth = std::sqrt(std::max(0.0f, 0.98f * 0.98f - glm::dot(offset, offset)));
      const glm::vec3 far = offset - depth * l, near = offset + depth * l;
      const double whole = integratedToSun(particle, sigma, 1.0f, far, l);
      INFO("offset angle " << a);
      CHECK(ownSunOpticalDepth(od, chordOuterThird(od), far, l, 1.0f) == Approx(whole).epsilon(0.05).margin(0.05));
      CHECK(ownSunOpticalDepth(od, chordOuterThird(od), near, l, 1.0f) <= 0.05 * whole + 1e-3);
      behind += whole > 1.0;
    }
    CHECK(behind >= 6);  // the chords hold matter: the check above is not of empty rays
  }
}

TEST_CASE("chord matter: the outer thirds' share measured from the particle", "[lighting][bake]") {
  // bake/ChordMatterProfile against the share computed here another way: the radial fall-off
  // (1 − r²)² along chords b from the centre, each span between the points where it crosses the
  // first-matter threshold found by bisection (not by samples), the thirds' matter by the
  // midpoint rule, the chords weighed by 2πb db · τ(b) (4000 chords, 2000 steps each).
  const double threshold = defaults::kFirstMatterThreshold;
  double weighted = 0.0, total = 0.0;
  constexpr int kChords = 4000, kSteps = 2000;
  for (int i = 0; i < kChords; ++i) {
    const double b = (i + 0.5) / kChords;
    if (ReferenceParticle::radialFalloff(static_cast<float>(b * b)) < threshold) continue;
    double lo = 0.0, hi = std::sqrt(1.0 - b * b);  // the span's half-length
    for (int k = 0; k < 60; ++k) {
      const double mid = 0.5 * (lo + hi);
      (ReferenceParticle::radialFalloff(static_cast<float>(b * b + mid * mid)) >= threshold ? lo : hi) = mid;
    }
    double all = 0.0, outer = 0.0;
    for (int k = 0; k < kSteps; ++k) {
      const double t = -lo + (k + 0.5) * 2.0 * lo / kSteps;
      const double d = ReferenceParticle::radialFalloff(static_cast<float>(b * b + t * t));
      all += d;
      if (std::abs(t) > lo / 3.0) outer += d;
    }
    weighted += b * 0.5 * outer * (2.0 * lo / kSteps);
    total += b * all * (2.0 * lo / kSteps);
  }
  const double radial = weighted / total;
  const double measured = bake::measureChordOuterThird(ReferenceParticle(DensityModel::Radial, 1));
  INFO("radial fall-off: here " << radial << ", measured " << measured);
  CHECK(measured == Approx(radial).margin(0.005));
  CHECK(radial < 0.28);  // mid-chord matter: well below the even 1/3
  // a homogeneous sphere: even matter
  CHECK(bake::measureChordOuterThird(ReferenceParticle(DensityModel::Sphere, 1)) == Approx(1.0 / 3.0).margin(0.002));
  // the noise particle: the fall-off modulated, its matter mid-chord too
  const Medium medium;
  const double noise = bake::measureChordOuterThird(ReferenceParticle(medium.model, medium.seed));
  INFO("noise particle " << noise);
  CHECK(noise > 0.2);
  CHECK(noise < 0.3);
}
