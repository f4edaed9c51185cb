// The scene path tracer (reference/ScenePathTracer.h) against the independent homogeneous-sphere
// tracer (reference/SphereMonteCarlo.h), closed forms, and its command line.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include <glm/geometric.hpp>
#include <tbb/global_control.h>

#include "support/CliRunner.h"
#include "core/Defaults.h"
#include "core/Glsl.h"
#include "io/ExrImage.h"
#include "reference/ScenePathTracer.h"
#include "reference/SphereMonteCarlo.h"

using namespace cloudlut;
using namespace cloudlut::reference;

namespace {

constexpr double kUnitSigma = defaults::kUnitOpticalRadius;

// One homogeneous sphere of world radius `radius` at `center`.
SceneMedium sphereMedium(const ReferenceParticle& model, double radius, double rho,
                         const glm::dvec3& center = glm::dvec3(0.0)) {
  SceneMedium m;
  m.model = &model;
  m.unitOpticalRadius = kUnitSigma;
  m.particles.push_back({center, glm::dmat3(1.0 / radius), rho});
  return m;
}

bool within(double a, double seA, double b, double seB, double k = 4.0) {
  return std::abs(a - b) <= k * std::sqrt(seA * seA + seB * seB) + 1e-12;
}

}  // namespace

TEST_CASE("reference scene: one homogeneous sphere agrees with the sphere tracer, single and all orders",
          "[reference-scene]") {
  const ReferenceParticle model(DensityModel::Sphere, 1);
  struct Geometry { glm::dvec3 S, v, l; };
  const std::vector<Geometry> geometries = {
      {{0.3, 0.5, 0.81}, {-0.2, -0.4, -0.89}, {0.5, 0.8, 0.3}},     // facing the sun's side
      {{0.0, 0.0, 1.0}, {0.1, 0.0, -1.0}, {0.0, 1.0, 0.2}},         // sun from the side
      {{-0.6, 0.2, 0.77}, {0.5, 0.1, -0.86}, {-0.3, -0.2, -0.93}},  // looking toward the sun (back-lit)
  };
  for (const double rho : {0.25, 1.0}) {
    const double radius = 2.5;  // world size must not matter
    const SceneMedium medium = sphereMedium(model, radius, rho, glm::dvec3(1.0, -2.0, 0.5));
    SphereMcSettings sphereSettings;
    sphereSettings.paths = rho < 0.5 ? 20000 : 6000;
    sphereSettings.seed = 7;
    std::vector<SphereMcQuery> queries;
    for (const auto& g : geometries) queries.push_back({g.S, g.v, g.l, kUnitSigma * rho});
    const auto expected = estimateSphereRadiance(queries, sphereSettings);
    for (std::size_t k = 0; k < geometries.size(); ++k) {
      const Geometry& g = geometries[k];
      const glm::dvec3 S = glm::normalize(g.S), v = glm::normalize(g.v);
      REQUIRE(glm::dot(S, v) < 0.0);
      const glm::dvec3 origin = medium.particles[0].center + radius * S - 3.0 * v;
      SceneLight light;
      light.sunDirection = glm::normalize(g.l);
      ScenePtSettings st;
      st.seed = 11;
      const RayEstimate e = estimateRay(medium, light, st, origin, v, sphereSettings.paths, k);
      INFO("rho " << rho << " geometry " << k << ": single " << e.single << " ± " << e.singleSe << " vs "
                  << expected[k].single << " ± " << expected[k].singleSe << "; multiple " << e.multiple << " ± "
                  << e.multipleSe << " vs " << expected[k].multipleAll << " ± " << expected[k].multipleAllSe);
      CHECK(e.transmittance == Approx(std::exp(-2.0 * kUnitSigma * rho * -glm::dot(S, v))).margin(1e-9));
      CHECK(within(e.single, e.singleSe, expected[k].single, expected[k].singleSe));
      CHECK(within(e.multiple, e.multipleSe, expected[k].multipleAll, expected[k].multipleAllSe));
      CHECK(e.singleSe < 0.05 * e.single + 1e-4);
    }
  }
}

TEST_CASE("reference scene: an empty pixel has transmittance 1 and no radiance", "[reference-scene]") {
  const ReferenceParticle model(DensityModel::Noise, 1);
  const SceneMedium medium = sphereMedium(model, 1.0, 1.0);
  const RayEstimate e = estimateRay(medium, {}, {}, glm::dvec3(0, 0, 5), glm::dvec3(0, 1, 0), 100, 0);
  CHECK(e.transmittance == 1.0);
  CHECK(e.transmittanceSe == 0.0);
  CHECK(e.single == 0.0);
  CHECK(e.multiple == 0.0);
  CHECK(e.sky == 0.0);
}

TEST_CASE("reference scene: a thin homogeneous sphere matches the single-scattering integral", "[reference-scene]") {
  const ReferenceParticle model(DensityModel::Sphere, 1);
  const double rho = 0.004, sigma = kUnitSigma * rho;  // optical radius ≈ 0.05
  const SceneMedium medium = sphereMedium(model, 1.0, rho);
  const glm::dvec3 v = glm::normalize(glm::dvec3(0.1, -0.3, -1.0)), l = glm::normalize(glm::dvec3(0.4, 0.8, 0.3));
  const glm::dvec3 origin = glm::dvec3(0.05, 0.2, 0.0) - 4.0 * v;
  // Closed form along the chord: ∫ σ e^{−σ t} P1(v·l) e^{−σ d_sun} dt, by fine quadrature.
  const double b = glm::dot(origin, v), c = glm::dot(origin, origin) - 1.0, disc = std::sqrt(b * b - c);
  const double t0 = -b - disc, t1 = -b + disc;
  double integral = 0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const double t = t0 + (i + 0.5) * (t1 - t0) / n;
    const glm::dvec3 x = origin + t * v;
    const double bs = glm::dot(x, l), cs = glm::dot(x, x) - 1.0, dSun = -bs + std::sqrt(bs * bs - cs);
    integral += sigma * std::exp(-sigma * (t - t0)) * std::exp(-sigma * dSun) * (t1 - t0) / n;
  }
  const double expected = integral * glsl::phaseCornetteShanks(static_cast<float>(glm::dot(v, l)), 0.9f);
  SceneLight light;
  light.sunDirection = l;
  ScenePtSettings st;
  st.seed = 3;
  const RayEstimate e = estimateRay(medium, light, st, origin, v, 400000, 0);
  INFO("single " << e.single << " ± " << e.singleSe << " vs closed form " << expected);
  CHECK(within(e.single, e.singleSe, expected, 0.0));
  CHECK(e.singleSe < 0.03 * expected);
  CHECK(e.transmittance == Approx(std::exp(-sigma * (t1 - t0))).epsilon(1e-9));
}

TEST_CASE("reference scene: a uniform sky on a non-absorbing medium gives sky·(1 − T)", "[reference-scene]") {
  // Energy: a medium without absorption under a uniform sky is invisible, so the light it sends
  // toward the camera is exactly the sky it hides.
  const ReferenceParticle model(DensityModel::Radial, 1);
  SceneMedium medium = sphereMedium(model, 1.0, 0.5);
  medium.particles.push_back({glm::dvec3(0.8, 0.3, 0.0), glm::dmat3(1.0 / 0.7), 0.8});
  const glm::dvec3 v = glm::normalize(glm::dvec3(0.05, -0.1, -1.0));
  ScenePtSettings st;
  st.seed = 5;
  const RayEstimate e = estimateRay(medium, {}, st, glm::dvec3(0.3, 0.2, 5.0), v, 4000, 0);
  INFO("sky " << e.sky << " ± " << e.skySe << ", 1 - T " << 1.0 - e.transmittance << " ± " << e.transmittanceSe);
  CHECK(e.transmittance < 0.9);
  CHECK(within(e.sky, e.skySe, 1.0 - e.transmittance, e.transmittanceSe));
}

TEST_CASE("reference scene: a sky darker below the horizon weights the paths that leave downward", "[reference-scene]") {
  // The sky below the horizon (SceneLight::skyBelow) changes only what an escaping path collects,
  // not the random draws: the ambient is linear in it, path by path, and at 1 it is the uniform
  // sky. Seen from above, a cloud sends back more ground than seen from below.
  const ReferenceParticle model(DensityModel::Noise, 1);
  SceneMedium medium = sphereMedium(model, 1.0, 1.0);
  const auto ambient = [&](double below, const glm::dvec3& eye) {
    SceneLight light;
    light.skyBelow = below;
    ScenePtSettings st;
    st.seed = 9;
    return estimateRay(medium, light, st, eye, -eye, 3000, 0);
  };
  for (const glm::dvec3 eye : {glm::dvec3(0.1, 4.0, 0.2), glm::dvec3(0.1, -4.0, 0.2)}) {
    const RayEstimate dark = ambient(0.0, eye), uniform = ambient(1.0, eye), tenth = ambient(0.1, eye);
    CHECK(tenth.sky == Approx(dark.sky + 0.1 * (uniform.sky - dark.sky)).epsilon(1e-12));
    CHECK(uniform.single == dark.single);
    CHECK(uniform.transmittance == dark.transmittance);
    CHECK(within(uniform.sky, uniform.skySe, 1.0 - uniform.transmittance, uniform.transmittanceSe));
    CHECK(dark.sky < uniform.sky);
  }
  const double fromAbove = ambient(0.0, glm::dvec3(0.1, 4.0, 0.2)).sky, fromBelow = ambient(0.0, glm::dvec3(0.1, -4.0, 0.2)).sky;
  INFO("sky-only ambient seen from above " << fromAbove << ", from below " << fromBelow);
  CHECK(fromAbove > fromBelow);
}

TEST_CASE("reference scene: the image is the same for any number of threads", "[reference-scene]") {
  const ReferenceParticle model(DensityModel::Noise, 1);
  SceneMedium medium = sphereMedium(model, 1.0, 0.6);
  medium.particles.push_back({glm::dvec3(0.7, 0.2, -0.3), glm::dmat3(1.0 / 0.8), 1.0});
  const auto ray = [](double px, double py, glm::dvec3& o, glm::dvec3& d) {
    o = glm::dvec3(0, 0, 4);
    d = glm::normalize(glm::dvec3((px - 10) / 10.0, (10 - py) / 10.0, -2.0));
  };
  ScenePtSettings st;
  st.samplesPerPixel = 4;
  SceneLight light;
  light.sunDirection = glm::normalize(glm::dvec3(0.3, 1, 0.2));
  ScenePtImage one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = renderScene(medium, light, st, 20, 20, ray);
  }
  two = renderScene(medium, light, st, 20, 20, ray);
  for (std::size_t i = 0; i < one.pixels.size(); ++i) {
    REQUIRE(one.pixels[i].single == two.pixels[i].single);
    REQUIRE(one.pixels[i].multiple == two.pixels[i].multiple);
    REQUIRE(one.pixels[i].transmittance == two.pixels[i].transmittance);
  }
}

TEST_CASE("reference scene: command line writes the documented channels; bad input fails clearly",
          "[reference-scene]") {
  using namespace cloudlut::test;
  TempDir dir;
  const std::string scene = std::string(CLOUDLUT_SOURCE_DIR) + "/data/bench_scenes/two.json";
  const auto ok = runCli("reference scene --particles '" + scene + "' --out '" + (dir / "r.exr").string() +
                         "' --width 12 --height 8 --spp 4 --density-model radial --quiet");
  REQUIRE(ok.exitCode == 0);
  const io::ExrImage img = io::readExrImage(dir / "r.exr");
  CHECK(img.width == 12);
  CHECK(img.height == 8);
  for (const char* c : {"R", "G", "B", "A", "stderr.R", "stderr.G", "stderr.B", "stderr.A", "single", "multiple", "ambient"})
    CHECK(img.has(c));

  const auto missing = runCli("reference scene --particles '" + (dir / "nope.json").string() + "' --out '" +
                              (dir / "x.exr").string() + "' --quiet");
  CHECK(missing.exitCode == 1);
  CHECK(missing.err.find("nope.json") != std::string::npos);
  const auto badSpp = runCli("reference scene --particles '" + scene + "' --spp 1 --quiet");
  CHECK(badSpp.exitCode == 2);
  CHECK(badSpp.err.find("--spp") != std::string::npos);
  const auto badOut = runCli("reference scene --particles '" + scene + "' --out x.png --quiet");
  CHECK(badOut.exitCode == 2);
  const auto badModel = runCli("reference scene --particles '" + scene + "' --density-model fluffy --quiet");
  CHECK(badModel.exitCode == 2);
  const auto noLuts = runCli("reference scene --particles '" + scene + "' --luts '" + (dir / "none").string() + "' --quiet");
  CHECK(noLuts.exitCode == 1);
  CHECK(noLuts.err.find("manifest.json") != std::string::npos);
  const auto noParticles = runCli("reference scene --quiet");
  CHECK(noParticles.exitCode == 2);
}
