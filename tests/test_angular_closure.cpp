// The angular closure of a particle's own multiple-scattering term (bake/AngularClosureBaker.h,
// core/AngularClosure.h): the forward Monte Carlo of the reference particle against the own-term
// model, per exit direction.
//   - On the homogeneous sphere the tables are the sphere's own (within 3–4% of Monte Carlo, the
//     scattering tests), so the closure must be 1 in every direction: a check of the Monte Carlo's
//     normalisation, of the exit-direction convention (μ = ω_out · l against −v · l) and of the
//     model's integral over view directions and chords, which all enter K.
//   - The same K whatever the thread count.
//   - The record's rules (values, sizes) and the interpolation the shader repeats.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

#include <tbb/global_control.h>

#include "bake/AngularClosureBaker.h"
#include "bake/OpticalDepthBaker.h"
#include "core/AngularClosure.h"
#include "core/Defaults.h"
#include "support/BakedFixtures.h"

using namespace cloudlut;

namespace {

bake::AngularClosureSettings smallSettings() {
  bake::AngularClosureSettings s;
  s.log2RhoFirst = -1.0f;  // ρ = 1/2, 2, 8
  s.log2RhoStep = 2.0f;
  s.densityNodes = 3;
  s.sunDirections = 2;
  s.photonsPerDirection = 6000;
  s.viewDirections = 200;
  s.discSide = 24;
  return s;
}

Table4D depthTable(DensityModel model) {
  bake::OpticalDepthSettings ods;
  ods.dims = {32, 16, 32, 16};
  return bake::bakeOpticalDepth(ReferenceParticle(model, 1), ods);
}

}  // namespace

TEST_CASE("angular closure: the homogeneous sphere's own tables need none", "[closure]") {
  const bake::ScatteringResult& sc = test::defaultScattering(0);
  REQUIRE(sc.multiple);
  const Table4D od = depthTable(DensityModel::Sphere);
  // ρ = 1/2 and 2. (At ρ = 8 the forward bin holds a few per cent of the power, and a stream of
  // photons once put it 3–5 standard errors from the others, docs/LIGHTING.md.)
  bake::AngularClosureSettings s = smallSettings();
  s.densityNodes = 2;
  s.photonsPerDirection = 12000;
  const AngularClosure k = *bake::computeAngularClosure(od, *sc.multiple, ReferenceParticle(DensityModel::Sphere, 1),
                                                        defaults::kFirstPhase, defaults::kLaterPhase, s);
  REQUIRE(k.values.size() == 2u * 8u);
  double worst = 0.0;
  for (std::size_t i = 0; i < k.values.size(); ++i) {
    INFO("node " << i / 8 << " bin " << i % 8 << ": K " << k.values[i] << " ± " << k.relativeErrors[i]);
    // the tables' own error against Monte Carlo (≤ 4%) and three standard errors of this one
    CHECK(std::abs(k.values[i] - 1.0) <= 0.05 + 3.0 * k.relativeErrors[i]);
    worst = std::max(worst, std::abs(k.values[i] - 1.0));
  }
  std::printf("angular closure of the homogeneous sphere: largest |K - 1| %.3f\n", worst);
  for (std::size_t i = 0; i < k.values.size(); ++i)
    std::printf("%.3f±%.3f%c", k.values[i], k.relativeErrors[i], i % 8 == 7 ? '\n' : ' ');
}

TEST_CASE("angular closure: the noise particle's dense core sends too much light back toward the sun", "[closure]") {
  const bake::ScatteringResult& sc = test::defaultScattering(0);
  const Table4D od = depthTable(DensityModel::Noise);
  const AngularClosure k = *bake::computeAngularClosure(od, *sc.multiple, ReferenceParticle(DensityModel::Noise, 1),
                                                        defaults::kFirstPhase, defaults::kLaterPhase, smallSettings());
  // ρ = 8 (node 2): the model's sphere at the chords' mean density reflects like a dense sphere
  // (docs/LIGHTING.md measured K 0.76 toward the sun, 1.15–1.33 forward and sideways)
  const float towardSun = k.values[2 * 8 + 7], sideways = k.values[2 * 8 + 2];
  INFO("K toward the sun " << towardSun << ", sideways " << sideways);
  CHECK(towardSun < 0.9f);
  CHECK(sideways > 1.1f);
}

TEST_CASE("angular closure: the same whatever the thread count", "[closure]") {
  const bake::ScatteringResult& sc = test::defaultScattering(0);
  const Table4D od = depthTable(DensityModel::Noise);
  bake::AngularClosureSettings s = smallSettings();
  s.photonsPerDirection = 500;
  const auto run = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
    return *bake::computeAngularClosure(od, *sc.multiple, ReferenceParticle(DensityModel::Noise, 1),
                                        defaults::kFirstPhase, defaults::kLaterPhase, s);
  };
  const AngularClosure one = run(1), two = run(2);
  CHECK(one.values == two.values);
  CHECK(one.relativeErrors == two.relativeErrors);
}

TEST_CASE("angular closure: density nodes too dense for the Monte Carlo are left out", "[closure]") {
  const bake::ScatteringResult& sc = test::defaultScattering(0);
  const Table4D od = depthTable(DensityModel::Noise);
  bake::AngularClosureSettings s = smallSettings();
  s.sunDirections = 1;
  s.photonsPerDirection = 20;
  s.viewDirections = 8;
  s.discSide = 4;
  s.log2RhoFirst = 3.0f;  // σ·ρ = 103, 206, 412 with the default σ = 12.87
  s.log2RhoStep = 1.0f;
  const auto partial = bake::computeAngularClosure(od, *sc.multiple, ReferenceParticle(DensityModel::Noise, 1),
                                                   defaults::kFirstPhase, defaults::kLaterPhase, s);
  REQUIRE(partial);
  CHECK(partial->densityNodes == 2);
  CHECK(partial->values.size() == 2u * 8u);
  s.log2RhoFirst = 5.0f;  // 412: none
  CHECK_FALSE(bake::computeAngularClosure(od, *sc.multiple, ReferenceParticle(DensityModel::Noise, 1),
                                          defaults::kFirstPhase, defaults::kLaterPhase, s));
}

TEST_CASE("angular closure: the record's rules and the interpolation", "[closure]") {
  AngularClosure c;
  c.log2RhoFirst = -1.0f;
  c.log2RhoStep = 1.0f;
  c.densityNodes = 2;
  c.muBins = 2;
  c.values = {0.5f, 1.5f, 1.0f, 2.0f};
  std::string problem;
  const auto back = angularClosureFromJson(angularClosureToJson(c), problem);
  REQUIRE(back);
  CHECK(back->values == c.values);
  CHECK_FALSE(back->ownCoreShadow);
  c.ownCoreShadow = true;
  CHECK(angularClosureFromJson(angularClosureToJson(c), problem)->ownCoreShadow);
  nlohmann::json older = angularClosureToJson(c);
  older.erase("own_core_shadow");  // a set baked before the field: K without the core shadow
  CHECK_FALSE(angularClosureFromJson(older, problem)->ownCoreShadow);
  // the bound on its brightening: kept, and 1 (never brighten) for a set baked before it
  c.ownCoreShadowMax = 1.2f;
  CHECK(angularClosureFromJson(angularClosureToJson(c), problem)->ownCoreShadowMax == Approx(1.2f));
  older = angularClosureToJson(c);
  older.erase("own_core_shadow_max");
  CHECK(angularClosureFromJson(older, problem)->ownCoreShadowMax == 1.0f);
  // nodes at ρ = 1/2 and 1, bin centres at μ = −½ and ½; held beyond them
  CHECK(angularClosureAt(c, 0.5f, -0.5f) == Approx(0.5f));
  CHECK(angularClosureAt(c, 1.0f, 0.5f) == Approx(2.0f));
  CHECK(angularClosureAt(c, 0.1f, -1.0f) == Approx(0.5f));
  CHECK(angularClosureAt(c, std::sqrt(0.5f), 0.0f) == Approx((0.5f + 1.5f + 1.0f + 2.0f) / 4.0f));
  const struct {
    const char* field;
    nlohmann::json value;
  } bad[] = {{"values", {1.0, 1.0, 1.0}},         {"values", {1.0, 1.0, 1.0, 9.0}}, {"values", {1.0, 1.0, 1.0, "x"}},
             {"density_nodes", 17},                {"mu_bins", 0.5},                 {"log2_rho_step", 0.0},
             {"log2_rho_first", nullptr},          {"relative_errors", {-1.0, 0, 0, 0}},
             {"own_core_shadow", 1},               {"own_core_shadow_max", 0.9},     {"own_core_shadow_max", 5.0},
             {"own_core_shadow_max", "1.2"}};
  for (const auto& b : bad) {
    INFO(b.field << " = " << b.value.dump());
    nlohmann::json record = angularClosureToJson(c);
    record[b.field] = b.value;
    CHECK_FALSE(angularClosureFromJson(record, problem));
    CHECK(problem.rfind(b.field, 0) == 0);
  }
}

TEST_CASE("angular closure: the shared interpolation reproduces a plane between and beyond the nodes", "[closure]") {
  // K = 1 + 0.1·i + 0.02·j on a grid of 5 density nodes (log2 ρ = −2 … 2 in steps of 1) and 8
  // μ bins: bilinear interpolation reproduces a plane exactly, so at any (ρ, μ) it must give
  // 1 + 0.1·s + 0.02·m, s = log2 ρ + 2 and m = (μ + 1)·4 − ½, each clamped to the grid (the
  // closure is held beyond its first and last node and bin centre).
  AngularClosure c;
  c.log2RhoFirst = -2.0f;
  c.log2RhoStep = 1.0f;
  c.densityNodes = 5;
  c.muBins = 8;
  c.values.clear();  // the default closure holds one value
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 8; ++j) c.values.push_back(1.0f + 0.1f * float(i) + 0.02f * float(j));
  double worst = 0;
  int count = 0;
  for (double log2Rho = -3.3; log2Rho <= 3.3; log2Rho += 0.37)
    for (double mu = -1.0; mu <= 1.0; mu += 0.093) {
      const double s = std::clamp(log2Rho + 2.0, 0.0, 4.0), m = std::clamp((mu + 1.0) * 4.0 - 0.5, 0.0, 7.0);
      const double expected = 1.0 + 0.1 * s + 0.02 * m;
      const double got = angularClosureAt(c, float(std::exp2(log2Rho)), float(mu));
      worst = std::max(worst, std::abs(got - expected));
      ++count;
    }
  INFO(count << " points, worst |K - plane| " << worst);
  CHECK(worst < 1e-5);
}
