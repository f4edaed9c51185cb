// The atmosphere (issue 13): the model's defaults, its tables' parameterisation, the tables and
// the sky computed from them against the brute-force reference (src/reference/
// AtmosphereReference.h), the reference against itself in the optically thin limit, the
// parameters' rules, and `cloudlut bake --tables atmosphere` end to end. Cheap: one bake per
// process, a few hundred reference samples, a few thousand paths.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>

#include "bake/AtmosphereBaker.h"
#include "bench/AtmosphereComparison.h"
#include "core/Errors.h"
#include "core/Glsl.h"
#include "io/LutIo.h"
#include "reference/AtmosphereReference.h"
#include "scene/AtmosphereJson.h"
#include "support/Checks.h"
#include "support/CliRunner.h"
#include "support/TempDir.h"

using namespace cloudlut;

namespace {

const bake::AtmosphereTables& defaultTables() {
  static const bake::AtmosphereTables tables = bake::bakeAtmosphere(glsl::defaultAtmosphere());
  return tables;
}

const bench::AtmosphereCheck& checkNamed(const std::string& name, double elevation) {
  static const std::vector<bench::AtmosphereCheck> checks = bench::atmosphereChecks();
  for (const auto& c : checks)
    if (c.name == name && c.sunElevationDeg == elevation) return c;
  throw std::logic_error("no check " + name);
}

}  // namespace

TEST_CASE("the atmosphere's defaults are the issue's", "[atmosphere]") {
  const glsl::AtmosphereParameters a = glsl::defaultAtmosphere();
  CHECK(a.bottomRadius == 6360e3f);
  CHECK(a.topRadius == 6460e3f);
  CHECK(a.rayleighScattering == glm::vec3(5.802e-6f, 13.558e-6f, 33.1e-6f));
  CHECK(a.rayleighScaleHeight == 8e3f);
  CHECK(a.mieScattering == 3.996e-6f);
  CHECK(a.mieAbsorption == 4.40e-6f);
  CHECK(a.mieScaleHeight == 1.2e3f);
  CHECK(a.mieG == 0.8f);
  CHECK(a.ozoneAbsorption == glm::vec3(0.650e-6f, 1.881e-6f, 0.085e-6f));
  CHECK(glsl::atmosphereDensities(a, 25e3f).z == Approx(1.0f));
  CHECK(glsl::atmosphereDensities(a, 10e3f).z == Approx(0.0f).margin(1e-6));
  CHECK(glsl::atmosphereDensities(a, 17.5e3f).z == Approx(0.5f));
  CHECK(glsl::atmosphereDensities(a, 40e3f).z == Approx(0.0f).margin(1e-6));
  CHECK(a.groundAlbedo == glm::vec3(0.1f));
  // the sun's disc integrates to unit irradiance (midpoint rule over its solid angle)
  double sum = 0.0;
  const int n = 400;
  const double alpha = glsl::CLOUDLUT_SUN_ANGULAR_RADIUS;
  for (int i = 0; i < n; ++i) {
    const double psi = (i + 0.5) / n * alpha;
    sum += glsl::sunDiscRadiance(static_cast<float>(std::cos(psi))) * 2.0 * 3.14159265358979 * std::sin(psi) * alpha / n;
  }
  CHECK(sum == Approx(1.0).epsilon(0.01));
}

TEST_CASE("the transmittance parameterisation round-trips and covers the rays that miss the ground", "[atmosphere]") {
  const glsl::AtmosphereParameters a = glsl::defaultAtmosphere();
  for (const float xr : {0.0f, 0.1f, 0.5f, 1.0f})
    for (const float xm : {0.0f, 0.25f, 0.5f, 0.9f, 1.0f}) {
      const glm::vec2 rm = glsl::transmittanceRadiusMu(a, glm::vec2(xm, xr));
      CHECK(rm.x >= a.bottomRadius);
      CHECK(rm.x <= a.topRadius * 1.000001f);
      CHECK_FALSE(glsl::rayHitsGround(a, rm.x, rm.y - 1e-4f * (xm == 1.0f ? -1.0f : 0.0f)));
      const glm::vec2 back = glsl::transmittanceUnitRange(a, rm.x, rm.y);
      CHECK(back.x == Approx(xm).margin(2e-3));
      CHECK(back.y == Approx(xr).margin(1e-4));
    }
  // the sun tables' axes round-trip, and crowd their nodes about the horizon
  for (const float xs : {0.0f, 0.2f, 0.49f, 0.5f, 0.51f, 0.8f, 1.0f}) {
    const glm::vec2 rm = glsl::sunTableRadiusMu(a, glm::vec2(xs, 0.25f));
    const glm::vec2 back = glsl::sunTableUnitRange(a, rm.x, rm.y);
    CHECK(back.x == Approx(xs).margin(1e-5));
    CHECK(back.y == Approx(0.25f).margin(1e-5));
  }
  CHECK(std::abs(glsl::sunTableRadiusMu(a, glm::vec2(16.0f / 31.0f, 0.0f)).y) < 0.002f);
  // x_mu = 1 is the horizon of the ground at every altitude below the top
  const glm::vec2 rm = glsl::transmittanceRadiusMu(a, glm::vec2(1.0f, 0.3f));
  CHECK(rm.y == Approx(-std::sqrt(1.0 - double(a.bottomRadius) * a.bottomRadius / (double(rm.x) * rm.x))).margin(1e-3));
}

TEST_CASE("the atmosphere's tables and sky agree with the brute-force reference", "[atmosphere]") {
  const glsl::AtmosphereParameters a = glsl::defaultAtmosphere();
  const bake::AtmosphereTables& tables = defaultTables();
  const reference::AtmosphereReference ref(a);
  const glsl::AtmosphereTexture tt = bake::atmosphereTexture(tables.transmittance);
  // transmittance, between the table's nodes, at several altitudes and zenith cosines
  for (const double h : {0.0, 500.0, 3000.0, 20000.0})
    for (const double mu : {1.0, 0.5, 0.1, 0.02, 0.0}) {
      const double r = a.bottomRadius + h;
      const glm::dvec3 T(glsl::transmittanceToTop(a, tt, static_cast<float>(r), static_cast<float>(mu)));
      const glm::dvec3 expected = ref.transmittanceToTop(r, mu, 2000);
      INFO("h " << h << " mu " << mu);
      CHECK(bench::relativeError(T, expected) < 0.005);
    }
  // single scattering: zenith and toward the sun at 30°, 90° from the sun at 5°
  const glm::dvec3 position = bench::checkPosition(a);
  for (const auto* c : {&checkNamed("zenith", 30.0), &checkNamed("toward sun", 30.0), &checkNamed("90 deg from sun", 5.0)}) {
    const glm::dvec3 expected = ref.singleScattering(position, c->view, c->sun, 300);
    INFO(c->name << " at " << c->sunElevationDeg);
    CHECK(bench::relativeError(bench::tableSkyRadiance(tables, a, *c, 1), expected) < 0.02);
  }
  // all orders, 90° from the sun at 30° (level, half of it multiply scattered): the quadrature's
  // single scattering plus 2000 paths per channel of the orders >= 2, goal 5% plus the noise
  const bench::AtmosphereCheck& c = checkNamed("90 deg from sun", 30.0);
  const reference::AtmosphereRadiance mc = ref.multipleOrders(position, c.view, c.sun, 2000, 7);
  const glm::dvec3 expected = ref.singleScattering(position, c.view, c.sun, 300) + mc.value;
  const glm::dvec3 sky = bench::tableSkyRadiance(tables, a, c, 0);
  for (int k = 0; k < 3; ++k) CHECK(std::abs(sky[k] - expected[k]) < 0.05 * expected[k] + 3.0 * mc.standardError[k]);
  // the orders >= 2 are a real share of it (blue most), which single scattering misses
  const glm::dvec3 single = bench::tableSkyRadiance(tables, a, c, 1);
  CHECK(expected.z > 1.3 * single.z);
}

TEST_CASE("the atmosphere reference's Monte Carlo matches its quadrature in the optically thin limit", "[atmosphere]") {
  // a hundredth of the air: second orders fall to about 1% of the first
  glsl::AtmosphereParameters a = glsl::defaultAtmosphere();
  a.rayleighScattering *= 0.01f;
  a.mieScattering *= 0.01f;
  a.mieAbsorption *= 0.01f;
  a.ozoneAbsorption *= 0.01f;
  a.groundAlbedo = glm::vec3(0.0f);
  const reference::AtmosphereReference ref(a);
  const glm::dvec3 position(0.0, a.bottomRadius + 500.0, 0.0);
  const glm::dvec3 view = glm::normalize(glm::dvec3(0.3, 1.0, 0.2)), sun = glm::normalize(glm::dvec3(1.0, 0.6, 0.0));
  const glm::dvec3 single = ref.singleScattering(position, view, sun, 400);
  const reference::AtmosphereRadiance mc = ref.allOrders(position, view, sun, 20000, 3);
  for (int k = 0; k < 3; ++k) {
    CHECK(mc.value[k] > 0.99 * single[k] - 3.0 * mc.standardError[k]);
    CHECK(mc.value[k] < 1.03 * single[k] + 3.0 * mc.standardError[k]);
    CHECK(mc.standardError[k] < 0.4 * mc.value[k]);  // few paths collide at all in so thin an air
  }
}

TEST_CASE("the atmosphere reference's orders >= 2 plus its single scattering are its all orders", "[atmosphere]") {
  const glsl::AtmosphereParameters a = glsl::defaultAtmosphere();
  const reference::AtmosphereReference ref(a);
  const bench::AtmosphereCheck& c = checkNamed("90 deg from sun", 30.0);
  const glm::dvec3 position = bench::checkPosition(a);
  const reference::AtmosphereRadiance all = ref.allOrders(position, c.view, c.sun, 3000, 11);
  const reference::AtmosphereRadiance multiple = ref.multipleOrders(position, c.view, c.sun, 3000, 12);
  const glm::dvec3 single = ref.singleScattering(position, c.view, c.sun, 300);
  for (int k = 0; k < 3; ++k) {
    const double sigma = std::hypot(all.standardError[k], multiple.standardError[k]);
    CHECK(std::abs(single[k] + multiple.value[k] - all.value[k]) < 4.0 * sigma);
    CHECK(multiple.value[k] > 0.1 * single[k]);
  }
}

TEST_CASE("non-physical atmosphere parameters name the field", "[atmosphere]") {
  const auto problem = [](const nlohmann::json& j) {
    return test::fileErrorOf([&] { scene::atmosphereFromJson(j, "scene.json", "sky."); });
  };
  CHECK(problem({{"mie_scattering_per_m", -1e-6}}).find("sky.mie_scattering_per_m") != std::string::npos);
  CHECK(problem({{"rayleigh_scattering_per_m", {1e-6, -1e-6, 1e-6}}}).find("sky.rayleigh_scattering_per_m") != std::string::npos);
  CHECK(problem({{"top_radius_m", 6000e3}}).find("sky.top_radius_m") != std::string::npos);
  CHECK(problem({{"rayleigh_scale_height_m", 0}}).find("sky.rayleigh_scale_height_m") != std::string::npos);
  CHECK(problem({{"mie_g", 1.0}}).find("sky.mie_g") != std::string::npos);
  CHECK(problem({{"ground_albedo", "grey"}}).find("sky.ground_albedo") != std::string::npos);
  CHECK_NOTHROW(scene::atmosphereFromJson({{"mie_g", 0.7}}, "scene.json", "sky."));
  CHECK(scene::atmosphereFromJson({{"ground_albedo", 0.3}}, "x", "").groundAlbedo == glm::vec3(0.3f));
}

TEST_CASE("bake --tables atmosphere writes three tables a LUT set reader loads", "[atmosphere][cli]") {
  test::TempDir tmp;
  const test::CliResult r = test::runCli("bake --tables atmosphere --quiet --threads 2 --out '" + (tmp / "luts").string() + "'");
  REQUIRE(r.exitCode == 0);
  const io::LutSet set = io::readLutSet(tmp / "luts");
  REQUIRE(set.tables.size() == 3);
  const Table4D& t = set.tables.at("atmosphere_transmittance").table;
  CHECK(t.dims() == std::array<int, 4>{256, 128, 1, 1});
  const Table4D& ms = set.tables.at("atmosphere_multiple_scattering").table;
  CHECK(ms.dims() == std::array<int, 4>{32, 32, 6, 1});
  // block 1, (1/4π) ∫ L cos²θ dω, lies between 0 and block 0, (1/4π) ∫ L dω, at every node
  std::size_t outside = 0;
  for (int j = 0; j < 32; ++j)
    for (int i = 0; i < 32; ++i)
      for (int c = 0; c < 3; ++c) {
        const float J = ms.at(ms.index(i, j, 0, 0), c), K = ms.at(ms.index(i, j, 1, 0), c);
        if (!(K >= 0.0f && K <= J && J >= 0.0f)) ++outside;
      }
  CHECK(outside == 0);
  CHECK(set.tables.at("atmosphere_irradiance").table.dims() == std::array<int, 4>{64, 16, 1, 1});
  CHECK(set.manifest["atmosphere"]["mie_g"].get<double>() == Approx(0.8));
  // the zenith's transmittance from the ground (node x_mu = 0, x_r = 0): exp(−τ) of the column
  const glm::dvec3 T = reference::AtmosphereReference(glsl::defaultAtmosphere()).transmittanceToTop(6360e3, 1.0, 2000);
  CHECK(t.at(t.index(0, 0, 0, 0), 2) == Approx(T.z).epsilon(0.002));
  const test::CliResult info = test::runCli("info '" + (tmp / "luts").string() + "'");
  CHECK(info.exitCode == 0);
  CHECK(info.out.find("atmosphere_irradiance") != std::string::npos);
  const test::CliResult sheet = test::runCli("slices '" + (tmp / "luts").string() + "' --table atmosphere_transmittance --out '" +
                                             (tmp / "t.png").string() + "'");
  CHECK(sheet.exitCode == 0);
  // a bad parameters file is exit 1 naming the field
  {
    std::ofstream(tmp / "bad.json") << R"({"sky": {"model": "atmosphere", "mie_scale_height_m": 0}})";
  }
  const test::CliResult bad = test::runCli("bake --tables atmosphere --quiet --atmosphere '" + (tmp / "bad.json").string() +
                                           "' --out '" + (tmp / "luts2").string() + "'");
  CHECK(bad.exitCode == 1);
  CHECK(bad.err.find("sky.mie_scale_height_m") != std::string::npos);
}
