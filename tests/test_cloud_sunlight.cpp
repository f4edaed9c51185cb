// slabTransmittance (lut_formats/glsl/cloudlut_shading.glsl), the share of the sun's irradiance
// through τ of cloud, against an independent Monte Carlo: photons entering a conservative slab of
// optical thickness τ at normal incidence, scattered by Henyey–Greenstein of mean cosine g, are
// counted when they leave through the far face (direct and diffuse together).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <random>

#include "core/Glsl.h"

namespace {

// Total transmittance of the slab [0, τ] (optical depth along its normal) for a unit beam at
// normal incidence; HG phase of mean cosine g; no absorption.
double slabTransmittanceMonteCarlo(double tau, double g, int photons, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int through = 0;
  for (int n = 0; n < photons; ++n) {
    double z = 0.0, mu = 1.0;  // depth (optical) and the direction's cosine to the normal
    for (;;) {
      z += mu * -std::log(1.0 - u(rng));
      if (z >= tau) {
        ++through;
        break;
      }
      if (z < 0.0) break;
      // HG deflection cosine (inverse CDF), then a uniform azimuth about the old direction
      const double s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u(rng));
      const double cosT = std::abs(g) < 1e-6 ? 2.0 * u(rng) - 1.0 : (1.0 + g * g - s * s) / (2.0 * g);
      const double sinT = std::sqrt(std::max(0.0, 1.0 - cosT * cosT));
      const double phi = 2.0 * 3.14159265358979323846 * u(rng);
      mu = mu * cosT + std::sqrt(std::max(0.0, 1.0 - mu * mu)) * sinT * std::cos(phi);
    }
  }
  return double(through) / photons;
}

}  // namespace

TEST_CASE("slabTransmittance: the sunlight under a cloud layer against a slab Monte Carlo", "[lighting][shading]") {
  const float g = 0.7f;  // near the default later phase's mean cosine
  const int photons = 20000;
  // The bound is the Eddington approximation's own error (measured −0.3% to +5%) plus the noise;
  // the two-stream diffuseTransmittance alone is 14–24% low on the same slabs.
  struct Case {
    float tau;
    double tolerance;
  };
  for (const Case c : {Case{0.05f, 0.01}, Case{2.0f, 0.07}, Case{10.0f, 0.05}, Case{40.0f, 0.05}, Case{120.0f, 0.06}}) {
    const double mc = slabTransmittanceMonteCarlo(c.tau, g, photons, 17u);
    const double model = cloudlut::glsl::slabTransmittance(c.tau, g);
    const double se = std::sqrt(mc * (1.0 - mc) / photons);
    std::printf("[slab transmittance] tau %6.2f: model %.4f, Monte Carlo %.4f +- %.4f, e^-tau %.2e\n", c.tau, model, mc, se,
                std::exp(-double(c.tau)));
    CHECK(std::abs(model - mc) <= c.tolerance * mc + 3.0 * se);
    // far below the cloud the direct beam is gone, the diffuse light is not
    if (c.tau >= 10.0f) CHECK(model > 100.0 * std::exp(-double(c.tau)));
  }
}
