// The defaults are written once (core/Defaults.h); this is where they are pinned to the seed
// paper's values (§5.1 and its public code), and where the constants the GLSL keeps on its own
// are checked against them. The one phase description (core/Phase.h) against the GLSL's kinds.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include "core/Defaults.h"
#include "core/Errors.h"
#include "core/Glsl.h"
#include "core/Phase.h"

using namespace cloudlut;

TEST_CASE("defaults are the seed's", "[defaults]") {
  CHECK(defaults::kExtinctionPerMetre == 0.07);
  CHECK(defaults::kParticleRadiusMetres == 183.8);
  CHECK(defaults::kUnitOpticalRadius == 0.07 * 183.8);
  CHECK(defaults::kDensitySlopeMin == -4);
  CHECK(defaults::kDensitySlopeMax == 3);
  // φv folded onto [0, π] (33 nodes at the spacing of the seed's 64 over [0, 2π]), two slices
  // per octave; the table stays within the seed's 32·64·16·8 samples
  CHECK(defaults::kScatteringDims == std::array<int, 4>{32, 33, 16, 15});
  CHECK(32 * 33 * 16 * 15 <= 32 * 64 * 16 * 8);
  CHECK(defaults::kOpticalDepthDims == std::array<int, 4>{64, 32, 64, 32});
  CHECK(defaults::kScatteringOrders == 18);
  CHECK(defaults::kFirstPhase == Phase{PhaseKind::CornetteShanks, 0.9f});
  CHECK(defaults::kLaterPhase == Phase{PhaseKind::CornetteShanks, 0.7f});
}

TEST_CASE("Phase kinds select the GLSL's phase functions", "[defaults][phase]") {
  // Checked at compile time too (core/Phase.cpp); here each kind against the function by name
  // (to float rounding: compilers may contract the two call sites differently, and 1 + g² − 2gμ
  // cancels near the forward peak).
  for (const float mu : {-1.0f, -0.3f, 0.0f, 0.5f, 0.99f}) {
    CHECK(phaseValue({PhaseKind::Isotropic, 0.0f}, mu) == Approx(glsl::phaseIsotropic()).epsilon(1e-4));
    CHECK(phaseValue({PhaseKind::HenyeyGreenstein, 0.8f}, mu) == Approx(glsl::phaseHenyeyGreenstein(mu, 0.8f)).epsilon(1e-4));
    CHECK(phaseValue({PhaseKind::CornetteShanks, 0.8f}, mu) == Approx(glsl::phaseCornetteShanks(mu, 0.8f)).epsilon(1e-4));
    CHECK(phaseValue({PhaseKind::JendersieDeon, 12.0f}, mu) ==
          Approx(glsl::phaseJendersieDeon(mu, glsl::jendersieDeonParameters(12.0f))).epsilon(1e-4));
  }
  CHECK_FALSE(phaseKindFromInt(-1));
  CHECK_FALSE(phaseKindFromInt(4));
  CHECK(phaseKindFromInt(3) == PhaseKind::JendersieDeon);
}

TEST_CASE("Phase JSON keeps the tables' {kind, param} form", "[defaults][phase]") {
  const nlohmann::json j = phaseToJson({PhaseKind::HenyeyGreenstein, 0.7f});
  CHECK(j["kind"] == 1);
  CHECK(j["param"].get<float>() == 0.7f);
  CHECK(j["name"] == "henyey_greenstein");
  CHECK(phaseFromJson(j, "f", "first_phase") == Phase{PhaseKind::HenyeyGreenstein, 0.7f});
  CHECK(phaseFromJson({{"kind", 3}, {"param", 10}}, "f", "p") == Phase{PhaseKind::JendersieDeon, 10.0f});
  CHECK_THROWS_WITH(phaseFromJson({{"kind", 7}, {"param", 0.5}}, "m.json", "single_scattering.first_phase"),
                    "m.json: single_scattering.first_phase: unknown phase kind 7 (0 isotropic, 1 Henyey-Greenstein, 2 Cornette-Shanks, 3 Jendersie-d'Eon)");
  CHECK_THROWS_AS(phaseFromJson({{"kind", "hg"}, {"param", 0.5}}, "m.json", "p"), FileError);
  CHECK_THROWS_AS(phaseFromJson(nlohmann::json::array(), "m.json", "p"), FileError);
  CHECK(describePhase({PhaseKind::CornetteShanks, 0.7f}) == "cs g=0.7");
  CHECK(describePhase({PhaseKind::JendersieDeon, 10.0f}) == "jd d=10 um");
  CHECK(describePhase({PhaseKind::Isotropic, 0.0f}) == "iso");
}
