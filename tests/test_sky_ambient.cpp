// skyAboveShare and layeredSkyAmbient (lut_formats/glsl/cloudlut_shading.glsl), the ambient under
// a sky that is brighter above the horizon than below, against an independent Monte Carlo: a
// camera ray enters a conservative horizontal slab of optical thickness τ, is scattered by
// Henyey–Greenstein of mean cosine g until it leaves, and collects 1 when it leaves through the
// top after at least one scattering (radiance per unit sky radiance above the horizon, nothing
// below: by linearity the rest is skyBelow·(opacity − that)).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <random>

#include "core/Glsl.h"

namespace {

// Radiance toward a camera whose view direction has the vertical cosine viewUp (> 0: looking up
// at the slab from below), per unit radiance of the sky above the horizon, the sky below dark.
double slabSkyAboveMonteCarlo(double tau, double viewUp, double g, int paths, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int up = 0;
  for (int n = 0; n < paths; ++n) {
    double z = viewUp > 0.0 ? 0.0 : tau, mu = viewUp;  // optical height, direction's vertical cosine
    for (bool scattered = false;; scattered = true) {
      z += mu * -std::log(1.0 - u(rng));
      if (z >= tau || z <= 0.0) {
        up += scattered && z >= tau;
        break;
      }
      const double s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u(rng));
      const double cosT = (1.0 + g * g - s * s) / (2.0 * g);
      const double sinT = std::sqrt(std::max(0.0, 1.0 - cosT * cosT));
      const double phi = 2.0 * 3.14159265358979323846 * u(rng);
      mu = mu * cosT + std::sqrt(std::max(0.0, 1.0 - mu * mu)) * sinT * std::cos(phi);
    }
  }
  return double(up) / paths;
}

// The model for the same slab: the view chord's optical depth τ/|viewUp|, its mean scattering
// point (meanScatteringFraction) and the vertical optical depths above and below that point.
double slabSkyAboveModel(float tau, float viewUp, float g) {
  using namespace cloudlut::glsl;
  const float chord = tau / std::abs(viewUp);
  const float fromEntry = meanScatteringFraction(chord) * tau;  // vertical optical depth from the entry face
  const float below = viewUp > 0.0f ? fromEntry : tau - fromEntry;
  const float share = skyAboveShare(tau - below, below, g, viewUp);
  return layeredSkyAmbient(chord, share, vec3(1.0f), vec3(0.0f)).y;
}

}  // namespace

TEST_CASE("layeredSkyAmbient: a cloud layer under a sky from above against a slab Monte Carlo", "[lighting][shading]") {
  const float g = 0.757f;  // the mean cosine of the default later phase (Cornette–Shanks 0.7)
  const int paths = 20000;
  // Measured (2026-12-02, 20 000 paths): within −15% … +13% for τ ≥ 3 at every angle below, within
  // ±5% for τ ≥ 10 but at grazing views; the share without the view term (the diffusion profile
  // alone) is 44% low at the base of a τ = 10 layer seen from straight below and 35% high on its
  // top seen from straight above.
  struct Case {
    float tau, viewUp;
    double tolerance;
  };
  const Case cases[] = {{3, 1, 0.08},     {3, 0.5f, 0.06},    {3, -0.5f, 0.08},   {3, -1, 0.18},
                        {10, 1, 0.06},    {10, 0.5f, 0.06},   {10, 0.2f, 0.16},   {10, -0.5f, 0.05},
                        {10, -1, 0.04},   {30, 1, 0.05},     {30, 0.2f, 0.14},   {30, -1, 0.04},
                        {100, 1, 0.08},   {100, -1, 0.04},   {0.1f, 1, 0.09},   {1, 0.5f, 0.06}};
  for (const Case& c : cases) {
    const double mc = slabSkyAboveMonteCarlo(c.tau, c.viewUp, g, paths, 23u);
    const double model = slabSkyAboveModel(c.tau, c.viewUp, g);
    const double se = std::sqrt(mc * (1.0 - mc) / paths);
    std::printf("[sky ambient] tau %6.2f view up %+.1f: model %.4f, Monte Carlo %.4f +- %.4f (%+.1f%%)\n", c.tau,
                c.viewUp, model, mc, se, 100.0 * (model / mc - 1.0));
    CHECK(std::abs(model - mc) <= c.tolerance * mc + 3.0 * se);
  }
}

TEST_CASE("layeredSkyAmbient: a uniform sky gives the uniform formula whatever the cloud around", "[lighting][shading]") {
  using namespace cloudlut::glsl;
  const vec3 sky(0.05f, 0.08f, 0.15f);
  for (const float tau : {0.0f, 1e-4f, 0.3f, 4.0f, 60.0f})
    for (const float above : {0.0f, 2.0f, 200.0f})
      for (const float viewUp : {-1.0f, 0.0f, 0.7f}) {
        const float share = skyAboveShare(above, 5.0f, 0.757f, viewUp);
        CHECK(share >= 0.0f);
        CHECK(share <= 1.0f);
        const vec3 a = layeredSkyAmbient(tau, share, sky, sky);
        for (int c = 0; c < 3; ++c) CHECK(a[c] == sky[c] * uniformSkyAmbient(tau));
      }
  // No cloud around: the share of the phase lobe from above, ½ + ¾·g·viewUp.
  CHECK(skyAboveShare(0.0f, 0.0f, 0.6f, 0.5f) == Approx(0.5 + 0.75 * 0.6 * 0.5).epsilon(1e-6));
  // Deep in a thick layer: the diffusion profile, the more sky the nearer the top.
  CHECK(skyAboveShare(10.0f, 90.0f, 0.757f, 0.0f) > skyAboveShare(90.0f, 10.0f, 0.757f, 0.0f));
}
