// The optical-depth table (seed §4.1) against independent computations: the constant and the
// closed-form radial chord integrals, and a 4096-sample integration of the noise particle.
#include <catch2/catch.hpp>

#include <tbb/global_control.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cmath>
#include <random>
#include <vector>

#include "bake/OpticalDepthBaker.h"
#include "core/Defaults.h"
#include "core/Float4.h"
#include "core/Glsl.h"
#include "core/LastMatter.h"
#include "core/TableLookup.h"

using namespace cloudlut;
using namespace cloudlut::glsl;

namespace {
constexpr float kPi = 3.14159265358979f;

struct Ray { vec3 S, v; };

Ray randomRay(std::mt19937& rng) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const float phi = 2 * kPi * u(rng), theta = kPi * u(rng);
  const vec3 S = sphericalPoint(phi, theta);
  return {S, frameDirection(tangentX(phi, theta), tangentY(phi), S, 2 * kPi * u(rng), 0.5f * kPi * u(rng))};
}

// Closed form for ρ̂ = (1 - r²)²: along P = S + t v, 1 - r² = t (L - t), so the chord integral
// is ∫_0^L t²(L - t)² dt = L⁵/30 and the mean density is L⁴/30.
double radialMean(double L) { return L * L * L * L / 30.0; }

// First t with t (L - t) >= √0.1 (density 0.1), as a fraction of L; 1 when never.
double radialFirstMatter(double L) {
  const double c = std::sqrt(0.1);
  const double disc = L * L - 4.0 * c;
  if (disc < 0.0) return 1.0;
  return 0.5 * (L - std::sqrt(disc)) / L;
}
}  // namespace

TEST_CASE("homogeneous sphere: mean density is exactly 1 on every non-degenerate chord", "[optical-depth]") {
  const ReferenceParticle sphere(DensityModel::Sphere, 1);
  bake::OpticalDepthSettings s;
  s.dims = {16, 9, 16, 9};
  const Table4D t = bake::bakeOpticalDepth(sphere, s);
  for (std::size_t n = 0; n < t.nodeCount(); ++n) {
    REQUIRE(t.at(n, 0) == Approx(1.0f).margin(1e-6));
    REQUIRE(t.at(n, 1) == 0.0f);
  }
}

TEST_CASE("radial fall-off: matches the closed-form chord integral within 1e-4", "[optical-depth]") {
  const ReferenceParticle radial(DensityModel::Radial, 1);
  std::mt19937 rng(11);
  const int steps = bake::defaultSteps(DensityModel::Radial);
  double worst = 0.0, worstFirst = 0.0;
  for (int i = 0; i < 20000; ++i) {
    const Ray r = randomRay(rng);
    const double L = chordLength(r.S, r.v);
    const bake::ChordIntegral c = bake::integrateChord(radial, r.S, r.v, steps);
    worst = std::max(worst, std::fabs(c.meanDensity - radialMean(L)));
    // The channel jumps where the chord's peak density L⁴/16 crosses the threshold; keep
    // away from that discontinuity.
    if (std::fabs(L * L * L * L / 16.0 - 0.1) > 0.005)
      worstFirst = std::max(worstFirst, std::fabs(c.firstMatter - radialFirstMatter(L)));
  }
  CHECK(worst < 1e-4);
  CHECK(worstFirst < 5e-3);
}

TEST_CASE("noise particle: default steps within 1e-3 mean and 5e-3 max of a 4096-step integration", "[optical-depth]") {
  const ReferenceParticle noise(DensityModel::Noise, 1);
  std::mt19937 rng(5);
  const int steps = bake::defaultSteps(DensityModel::Noise);
  double sum = 0.0, worst = 0.0;
  const int n = 3000;
  for (int i = 0; i < n; ++i) {
    const Ray r = randomRay(rng);
    const float a = bake::integrateChord(noise, r.S, r.v, steps).meanDensity;
    const float b = bake::integrateChord(noise, r.S, r.v, 4096).meanDensity;
    sum += std::fabs(a - b);
    worst = std::max(worst, static_cast<double>(std::fabs(a - b)));
  }
  CHECK(sum / n < 1e-3);
  CHECK(worst < 5e-3);
}

TEST_CASE("every model gives finite values in [0, 1] at the poles and on grazing rays", "[optical-depth]") {
  for (DensityModel m : {DensityModel::Noise, DensityModel::Threshold, DensityModel::Pyroclastic,
                         DensityModel::Radial, DensityModel::Sphere}) {
    const ReferenceParticle p(m, 3, 48);
    bake::OpticalDepthSettings s;
    s.dims = {12, 7, 12, 7};  // includes θS = 0, π and θv = π/2 nodes
    const Table4D t = bake::bakeOpticalDepth(p, s);
    for (std::size_t n = 0; n < t.nodeCount(); ++n)
      for (int c = 0; c < 2; ++c) {
        const float v = t.at(n, c);
        REQUIRE(std::isfinite(v));
        REQUIRE(v >= 0.0f);
        REQUIRE(v <= 1.0f);
      }
  }
}

TEST_CASE("the pole row is consistent: every φS there describes the same rays", "[optical-depth]") {
  // At θS = 0 the node (φS, φv) and the node (0, φS + φv) are the same chord, so a lookup at the
  // pole must not depend on which φS the renderer's atan2 happens to return, and a lookup just
  // off the pole must be close to the one on it.
  const ReferenceParticle p(DensityModel::Noise, 1, 48);
  bake::OpticalDepthSettings s;
  s.dims = {32, 17, 33, 9};
  const Table4D t = bake::bakeOpticalDepth(p, s);
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int i = 0; i < 200; ++i) {
    const float phiV = 2 * kPi * u(rng), thetaV = 0.45f * kPi * u(rng);
    const vec3 S(0.0f, 0.0f, 1.0f);
    const vec3 v = frameDirection(tangentX(0.0f, 0.0f), tangentY(0.0f), S, phiV, thetaV);
    const float onPole = lookupOpticalDepth(t, S, v, 1.0f).meanDensity;
    // the same chord expressed from a frame at φS = 1.3 on the pole
    const float phiS = 1.3f;
    const float viaOther = [&] {
      float out[2];
      float pv = std::fmod(phiV - phiS + 4 * kPi, 2 * kPi);
      t.sample({phiS / (2 * kPi), 0.0f, pv / (2 * kPi), thetaV / (0.5f * kPi)}, out);
      return out[0];
    }();
    CHECK(viaOther == Approx(onPole).margin(0.03));
    // just off the pole, moved along a random azimuth
    const float a = 2 * kPi * u(rng);
    const vec3 S2 = sphericalPoint(a, 1e-3f);
    const float offPole = lookupOpticalDepth(t, S2, v, 1.0f).meanDensity;
    CHECK(offPole == Approx(onPole).margin(0.03));
  }
}

TEST_CASE("optical-depth bake is identical for 1 and 2 threads", "[optical-depth]") {
  const ReferenceParticle p(DensityModel::Noise, 7, 48);
  bake::OpticalDepthSettings s;
  s.dims = {16, 8, 16, 8};
  Table4D one, two;
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
    one = bake::bakeOpticalDepth(p, s);
  }
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
    two = bake::bakeOpticalDepth(p, s);
  }
  REQUIRE(one.data() == two.data());
}

TEST_CASE("optical depth lookup: sphere chord gives tau = sigma rho L exactly", "[optical-depth]") {
  const ReferenceParticle sphere(DensityModel::Sphere, 1);
  bake::OpticalDepthSettings s;
  s.dims = {8, 5, 8, 5};
  const Table4D t = bake::bakeOpticalDepth(sphere, s);
  std::mt19937 rng(2);
  for (int i = 0; i < 100; ++i) {
    const Ray r = randomRay(rng);
    const OpticalDepthSample o = lookupOpticalDepth(t, r.S, r.v, 0.5f);
    const double expected = defaults::kUnitOpticalRadius * 0.5 * chordLength(r.S, r.v);
    REQUIRE(o.opticalDepth == Approx(expected).epsilon(1e-5));
    REQUIRE(o.transmittance == Approx(std::exp(-expected)).epsilon(1e-4).margin(1e-12));
  }
}

TEST_CASE("four chords at once: each lane is its chord alone, and both match a direct scalar scan", "[optical-depth]") {
  // integrateChords4 runs four chords of different lengths side by side (a lane past its last
  // panel idles, first-matter brackets are refined together). Each lane must be the chord
  // integrated alone, bit for bit; and the chord must match an independent scan of the scalar
  // density: a 20000-point midpoint sum for the mean, the first midpoint at or above the
  // threshold for the first matter. The integrator looks for the first matter at its own
  // samples (two per panel, about 4 grid cells), so it can step over a thinner wisp that
  // the scan finds: that part is held by its percentiles, not its worst case.
  const ReferenceParticle noise(DensityModel::Noise, 3);
  std::mt19937 rng(11);
  const int steps = bake::defaultSteps(DensityModel::Noise);
  double worstMean = 0.0;
  std::vector<double> firstErrors;
  for (int trial = 0; trial < 400; ++trial) {
    vec3 S[4], v[4];
    for (int k = 0; k < 4; ++k) {
      const Ray r = randomRay(rng);
      S[k] = r.S;
      v[k] = r.v;
    }
    if (trial % 50 == 0) v[trial / 50 % 4] = frameDirection(tangentX(0.3f, 1.0f), tangentY(0.3f), S[trial / 50 % 4], 0.0f,
                                                           0.5f * kPi);  // one grazing lane
    bake::ChordIntegral lanes[4];
    bake::integrateChords4(noise, S, v, steps, lanes);
    for (int k = 0; k < 4; ++k) {
      const bake::ChordIntegral alone = bake::integrateChord(noise, S[k], v[k], steps);
      REQUIRE(lanes[k].meanDensity == alone.meanDensity);
      REQUIRE(lanes[k].firstMatter == alone.firstMatter);
      const float L = chordLength(S[k], v[k]);
      if (L < 0.05f) continue;
      const int n = 20000;
      double sum = 0.0, first = 1.0;
      for (int i = 0; i < n; ++i) {
        const float t = L * (static_cast<float>(i) + 0.5f) / n;
        const float d = noise.density(S[k] * (1.0f - 1e-6f) + t * v[k]);
        sum += d;
        if (first == 1.0 && d >= defaults::kFirstMatterThreshold) first = t / L;
      }
      worstMean = std::max(worstMean, std::abs(lanes[k].meanDensity - sum / n));
      firstErrors.push_back(std::abs(lanes[k].firstMatter - first));
    }
  }
  CHECK(worstMean < 5e-3);
  std::sort(firstErrors.begin(), firstErrors.end());
  const double median = firstErrors[firstErrors.size() / 2], p95 = firstErrors[firstErrors.size() * 95 / 100];
  CAPTURE(median, p95, firstErrors.size());
  CHECK(median < 1e-4);
  CHECK(p95 < 1e-3);
}

TEST_CASE("the density at four points is the density at each, bit for bit, for every model", "[optical-depth]") {
  std::mt19937 rng(2);
  std::uniform_real_distribution<float> u(-1.1f, 1.1f);
  for (DensityModel m : {DensityModel::Noise, DensityModel::Threshold, DensityModel::Pyroclastic, DensityModel::Radial,
                         DensityModel::Sphere}) {
    const ReferenceParticle particle(m, 7);
    for (int i = 0; i < 2000; ++i) {
      Float4 x, y, z;
      for (int k = 0; k < 4; ++k) x[k] = u(rng), y[k] = u(rng), z[k] = u(rng);
      const Float4 d = particle.density4(x, y, z);
      for (int k = 0; k < 4; ++k) REQUIRE(d[k] == particle.density(vec3(x[k], y[k], z[k])));
    }
  }
}

// The last matter the renderer derives from the table (core/LastMatter.h), against independent
// computations: exact for the homogeneous sphere (matter from entry to exit), the closed form of
// the radial fall-off (a symmetric profile: the last matter mirrors the first), and a direct
// scan of the noise particle's density along random chords.
TEST_CASE("last matter: the derived channel against the sphere, the closed form and a direct scan", "[optical-depth]") {
  bake::OpticalDepthSettings s;
  s.dims = {32, 16, 32, 16};
  {
    const Table4D t = withLastMatterChannel(bake::bakeOpticalDepth(ReferenceParticle(DensityModel::Sphere, 1), s));
    REQUIRE(t.channelCount() == 3);
    REQUIRE(t.channels()[2].name == "last_matter");
    for (std::size_t n = 0; n < t.nodeCount(); ++n) {
      REQUIRE(t.at(n, 1) == 0.0f);
      REQUIRE(t.at(n, 2) == 1.0f);
    }
  }
  const auto errors = [&](DensityModel model, auto&& expected) {
    const ReferenceParticle particle(model, 3);
    const Table4D od = bake::bakeOpticalDepth(particle, s);
    const Table4D t = withLastMatterChannel(od);
    // the nodes hold lookupLastMatter, channels 0 and 1 are the table's
    for (std::size_t n = 0; n < t.nodeCount(); n += 97) {
      REQUIRE(t.at(n, 0) == od.at(n, 0));
      REQUIRE(t.at(n, 1) == od.at(n, 1));
    }
    std::mt19937 rng(17);
    // at the chord (lookupLastMatter), and as the renderer reads it: the derived channel
    // interpolated between the nodes, at least the interpolated first matter (the shaders' clamp)
    std::vector<double> e, eNodes;
    while (e.size() < 3000) {
      const Ray r = randomRay(rng);
      const float L = chordLength(r.S, r.v);
      const double want = expected(particle, r, L);
      if (L < 0.1f || want < 0.0) continue;  // grazing chord, or one the reference skips
      e.push_back(std::abs(lookupLastMatter(od, r.S, r.v) - want));
      const glm::vec4 x = opticalDepthAxes(r.S, r.v);
      float values[4] = {0, 0, 0, 0};
      t.sample({x.x, x.y, x.z, x.w}, values);
      eNodes.push_back(std::abs(std::max(values[2], values[1]) - want));
    }
    std::sort(e.begin(), e.end());
    std::sort(eNodes.begin(), eNodes.end());
    return std::array<double, 4>{e[e.size() / 2], e[e.size() * 95 / 100], eNodes[e.size() / 2],
                                 eNodes[e.size() * 95 / 100]};
  };
  // radial: 1 − first matter (the profile t(L − t) is symmetric); away from the chords whose
  // peak density L⁴/16 crosses the threshold, where the matter appears at once.
  const auto radial = errors(DensityModel::Radial, [](const ReferenceParticle&, const Ray&, float L) {
    if (std::fabs(L * L * L * L / 16.0 - 0.1) < 0.02) return -1.0;
    const double first = radialFirstMatter(L);
    return first >= 1.0 ? 1.0 : 1.0 - first;
  });
  // noise: the last of 20000 midpoints at or above the threshold (1 when none)
  const auto noise = errors(DensityModel::Noise, [](const ReferenceParticle& p, const Ray& r, float L) {
    const int n = 20000;
    double last = 1.0;
    bool any = false;
    for (int i = 0; i < n; ++i) {
      const float t = L * (static_cast<float>(i) + 0.5f) / n;
      if (p.density(r.S * (1.0f - 1e-6f) + t * r.v) >= defaults::kFirstMatterThreshold) last = t / L, any = true;
    }
    return any ? last : 1.0;
  });
  std::printf("last matter against independent references (32x16x32x16 table), median / p95 of |error|: radial %.4f / "
              "%.4f (the channel between nodes %.4f / %.4f), noise %.4f / %.4f (%.4f / %.4f)\n", radial[0], radial[1],
              radial[2], radial[3], noise[0], noise[1], noise[2], noise[3]);
  CHECK(radial[0] < 0.01);
  CHECK(radial[1] < 0.05);
  CHECK(radial[2] < 0.01);
  CHECK(radial[3] < 0.05);
  CHECK(noise[0] < 0.02);
  CHECK(noise[1] < 0.2);
  CHECK(noise[2] < 0.02);
  CHECK(noise[3] < 0.2);
}
