// `cloudlut bake --for-scene`: only the densities a scene uses, the smallest optical-depth table
// within the tolerance (checked here on fresh rays against a direct integration), and a LUT set
// the renderer accepts.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include <nlohmann/json.hpp>

#include "support/CliRunner.h"
#include "bake/OpticalDepthBaker.h"
#include "bake/SingleScattering.h"
#include "core/Glsl.h"
#include "core/TableLookup.h"
#include "io/LutIo.h"

using namespace cloudlut;
using namespace cloudlut::test;

namespace {
const std::string kScene = std::string(CLOUDLUT_SOURCE_DIR) + "/data/scenes/small.json";  // ρ from 0.25 to 4
}

TEST_CASE("bake --for-scene covers the scene's densities, meets its tolerance and renders", "[cli][for-scene]") {
  TempDir tmp;
  const std::string out = (tmp / "luts").string();
  const CliResult bake = runCli("bake --for-scene '" + kScene + "' --tolerance 0.05 --orders 4 --precision float "
                                "--format bin --out '" + out + "'");
  REQUIRE(bake.exitCode == 0);
  CHECK(bake.out.find("saved:") != std::string::npos);

  const io::LutSet set = io::readLutSet(out);
  REQUIRE(set.manifest.contains("for_scene"));
  // density axis: log2 0.25 − 1 = −3 … log2 4 = 2, a whole number of slices per octave
  const Axis& density = set.tables.at("multiple_scattering").table.axes()[3];
  CHECK(density.min == Approx(-3.0));
  CHECK(density.max == Approx(2.0));
  CHECK((density.size - 1) % 5 == 0);

  // The chosen single-scattering table is within the tolerance (95th percentile of the relative
  // error) on fresh rays at random densities across the scene's range, against the integral.
  {
    const Table4D& l1 = set.tables.at("single_scattering").table;
    std::mt19937_64 g(7);
    std::uniform_real_distribution<double> w(0.0, 1.0);
    const auto unit = [&] {
      const double z = 2.0 * w(g) - 1.0, p = 6.283185307179586 * w(g), r = std::sqrt(1.0 - z * z);
      return glm::dvec3(r * std::cos(p), r * std::sin(p), z);
    };
    std::vector<double> exact, table;
    for (int i = 0; i < 1200; ++i) {
      const glm::dvec3 S = unit(), l = unit();
      glm::dvec3 v = unit();
      if (glm::dot(v, S) > 0.0) v = -v;
      const double rho = std::exp2(-3.0 + 5.0 * w(g));
      exact.push_back(bake::singleScatteringL1(S, v, l, unitOpticalRadius(l1) * rho));
      table.push_back(lookupScattering(l1, glm::vec3(S), glm::vec3(v), glm::vec3(l), static_cast<float>(rho)));
    }
    double mean = 0.0;
    for (double e : exact) mean += e / static_cast<double>(exact.size());
    std::vector<double> rel;
    for (std::size_t i = 0; i < exact.size(); ++i)
      if (exact[i] >= 0.01 * mean) rel.push_back(std::abs(table[i] - exact[i]) / exact[i]);
    std::sort(rel.begin(), rel.end());
    INFO("single scattering: " << rel.size() << " rows, p95 " << rel[rel.size() * 95 / 100]);
    CHECK(rel[rel.size() * 95 / 100] <= 0.05 * 1.2);
  }

  // The chosen optical-depth table is smaller than the default and within the tolerance on
  // rays it was not chosen with, against a 4096-sample integration.
  const Table4D& od = set.tables.at("optical_depth").table;
  const auto dims = od.dims();
  CHECK(static_cast<long>(dims[0]) * dims[1] * dims[2] * dims[3] < 64L * 32 * 64 * 32);
  const ReferenceParticle particle(DensityModel::Noise, 1);
  std::mt19937 rng(99);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<double> errors;
  for (int i = 0; i < 1500; ++i) {
    const float phi = 6.2831853f * u(rng), theta = std::acos(2.0f * u(rng) - 1.0f);
    const glm::vec3 S = glsl::sphericalPoint(phi, theta);
    const glm::vec3 v = glsl::frameDirection(glsl::tangentX(phi, theta), glsl::tangentY(phi), S,
                                             6.2831853f * u(rng), std::acos(std::sqrt(u(rng))));
    const float exact = bake::integrateChord(particle, S, v, 4096).meanDensity;
    for (float rho : {0.25f, 4.0f}) {
      const OpticalDepthSample s = lookupOpticalDepth(od, S, v, rho);
      errors.push_back(std::fabs(s.transmittance - std::exp(-unitOpticalRadius(od) * rho * s.chordLength * exact)));
    }
  }
  std::sort(errors.begin(), errors.end());
  CHECK(errors[errors.size() * 95 / 100] <= 0.05 * 1.2);  // the tolerance, with room for sampling

  const CliResult render = runCli("render --luts '" + out + "' --particles '" + kScene + "' --width 96 --height 64 --quiet --out '" +
                                  (tmp / "a.png").string() + "'");
  CHECK(render.exitCode == 0);
}

TEST_CASE("bake --for-scene rejects missing scenes, unknown presets and bad tolerances", "[cli][for-scene]") {
  TempDir tmp;
  const std::string out = " --tables optical-depth --quiet --out '" + (tmp / "luts").string() + "'";
  CHECK(runCli("bake --for-scene '" + (tmp / "missing.json").string() + "'" + out).exitCode != 0);
  CHECK(runCli("bake --for-scene no_such_preset" + out).exitCode == 2);
  CHECK(runCli("bake --for-scene '" + kScene + "' --tolerance 0" + out).exitCode == 2);
  CHECK_FALSE(std::filesystem::exists(tmp / "luts"));
}
