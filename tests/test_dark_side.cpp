// The converged table's dark side against forward photon tracing (bench/DarkSideCheck.h,
// reference/PhotonExitTally.h): the tally's normalisation against the closed-form unscattered
// share, then the default converged tables at ρ = 1 bin by bin.
#include <catch2/catch.hpp>

#include <cmath>

#include "bench/DarkSideCheck.h"
#include "core/Defaults.h"
#include "reference/PhotonExitTally.h"
#include "reference/SphereMonteCarlo.h"
#include "support/BakedFixtures.h"

using namespace cloudlut;

namespace {
constexpr double kPi = 3.14159265358979323846;
}

TEST_CASE("Exit-radiance bins that cover the sphere hold all the scattered power", "[reference][dark-side]") {
  // 3 × 3 × 2 bins partition every exit point and direction: Σ L̄·A·Ω⊥/π over them must be the
  // scattered share 1 − unscattered (closed form), whatever the photons did inside.
  std::vector<reference::ExitBin> bins;
  const double thS[4] = {0, 1.0, 2.0, kPi}, thV[4] = {0, 0.5, 1.1, kPi / 2}, phV[3] = {0, 1.3, kPi};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 2; ++k)
        bins.push_back({{thS[i], thS[i + 1]}, {thV[j], thV[j + 1]}, {phV[k], phV[k + 1]}});
  for (double sigma : {0.5, 4.0}) {
    const auto t = reference::tallyExitRadiance(sigma, defaults::kFirstPhase, defaults::kLaterPhase, bins, 20000, 5);
    double power = 0.0;
    for (std::size_t k = 0; k < bins.size(); ++k) {
      const auto& b = bins[k];
      const double area = 2 * kPi * (std::cos(b.thetaS[0]) - std::cos(b.thetaS[1]));
      const double proj = (b.phiV[1] - b.phiV[0]) * (std::pow(std::sin(b.thetaV[1]), 2) - std::pow(std::sin(b.thetaV[0]), 2));
      power += t[k].radiance * area * proj / kPi;
    }
    INFO("sigma " << sigma);
    // Only the forced first collision's weight varies between photons (by the chord): ±1%.
    CHECK(power == Approx(1.0 - reference::unscatteredShare(sigma)).epsilon(0.01));
  }
}

TEST_CASE("Converged tables at rho 1 match forward photon tracing on the dark side", "[scattering][dark-side]") {
  const auto& r = test::defaultScattering(0);
  REQUIRE(r.single);
  REQUIRE(r.multiple);
  // Six wide dark-side bins (θS ≥ 100°; θv in thirds, φv in halves), thousands of photons each.
  const auto bins = reference::darkSideBins(1, 3, 2);
  const auto c = bench::compareDarkSide(*r.single, *r.multiple, 1.0, bins, 200000, 11);
  for (const auto& b : c.bins) {
    INFO("table " << b.table << " photons " << b.photons << " +- " << b.se);
    CHECK(std::abs(b.table - b.photons) <= 4.0 * b.se + 0.04 * b.photons);
  }
  INFO("median |error| " << c.medianAbsError << " worst " << c.worstError);
  CHECK(c.medianAbsError <= 0.02);
}
