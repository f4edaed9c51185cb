// The renderer, in process, headless (OSMesa/llvmpipe): the small scene's silhouette, and one
// particle's pixels against core/TableLookup (what `cloudlut query` computes) for the same rays.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

#include "support/CliRunner.h"
#include "core/Glsl.h"
#include "core/TableLookup.h"
#include "render/GlContext.h"
#include "render/Renderer.h"
#include "render/ShaderSources.h"
#include "scene/Scene.h"
#include "support/RenderFixture.h"
#include "support/RenderLuts.h"
#include "support/SourceScenes.h"

using namespace cloudlut;
using namespace cloudlut::render;
using namespace cloudlut::scene;
using namespace cloudlut::test;

namespace {

float firstPhase(const Table4D& single, float mu) {
  const auto phase = single.parameters().value("first_phase", nlohmann::json::object());
  return glsl::phaseFunction(phase.value("kind", 2), mu, phase.value("param", 0.9f));
}

double relativeDifference(double value, double reference) {
  return std::abs(value - reference) / std::max(std::abs(reference), 1e-12);
}

}  // namespace

TEST_CASE("render: the small scene has the particles' silhouette, no NaN, and is not empty", "[render]") {
  RenderFixture rig = RenderFixture::synthetic(DensityModel::Noise);
  Renderer& renderer = rig.renderer;
  const Scene scene = sourceScene("data/scenes/small.json");
  REQUIRE(scene.particles.size() >= 5);

  RenderSettings settings = sceneSettings(scene, 128, 96);
  const Image image = renderer.render(scene.particles, settings);
  REQUIRE(image.width == 128);
  REQUIRE(image.height == 96);
  CHECK(image.nonFiniteCount() == 0);

  const CameraFrame camera(settings.view.camera, image.width, image.height);
  std::size_t covered = 0, cores = 0, outside = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const glm::vec3 dir = camera.rayDirection(float(x) + 0.5f, float(y) + 0.5f);
      bool nearAny = false, inCore = false;
      for (const Particle& p : scene.particles) {
        nearAny = nearAny || intersect(p, camera.eye(), dir, 1.05f).hit;
        inCore = inCore || intersect(p, camera.eye(), dir, 0.5f).hit;
      }
      const float* px = image.pixel(x, y);
      if (px[3] > 0.0f) ++covered;
      if (inCore) {
        ++cores;
        INFO("core pixel " << x << "," << y);
        CHECK(px[3] > 0.05f);
        CHECK(px[0] > 0.0f);
        CHECK(std::isfinite(image.distanceAt(x, y)));
      }
      if (!nearAny) {
        ++outside;
        INFO("outside pixel " << x << "," << y);
        CHECK(px[0] == 0.0f);
        CHECK(px[1] == 0.0f);
        CHECK(px[2] == 0.0f);
        CHECK(px[3] == 0.0f);
        CHECK(std::isinf(image.distanceAt(x, y)));
      }
    }
  CHECK(cores > 500);
  CHECK(outside > 2000);
  CHECK(covered > static_cast<std::size_t>(image.width * image.height / 10));
}

// The scattering table's stored multiple-scattering source at density ρ as the cloud model reads
// it: below the table's least density it is taken proportional to ρ (particle.frag.glsl).
float multipleSourceBelowRange(const Table4D& lm, const glm::vec3& S, const glm::vec3& v, const glm::vec3& l,
                               float rho) {
  const float rhoMin = std::exp2(static_cast<float>(lm.axes()[3].min));
  return sampleScattering(lm, S, v, l, std::max(rho, rhoMin)) * std::min(rho / rhoMin, 1.0f);
}

TEST_CASE("render: one particle's pixels match core/TableLookup within 1%", "[render]") {
  TempDir tmp;
  const Table4D od = smallOpticalDepth(DensityModel::Noise);
  const Table4D l1 = syntheticSingle(), lm = syntheticMultiple();
  writeLutSet(tmp / "luts", {&od, &l1, &lm});
  const io::LutSet luts = io::readLutSet(tmp / "luts");
  auto context = createHeadlessContext();
  Renderer renderer(*context, luts);

  // Sun colour red and sky colour green separate the terms: R = single + multiple,
  // G = ambient, A = 1 - transmittance.
  RenderSettings settings;
  settings.width = 128;
  settings.height = 96;
  settings.view.camera = Camera{{0.7f, 1.1f, 6.5f}, {0.2f, -0.1f, 0.0f}, {0.0f, 1.0f, 0.0f}, 40.0f};
  settings.view.lighting.sunDirection = glm::normalize(glm::vec3(0.3f, 0.8f, 0.5f));
  settings.view.lighting.sunColor = {1.0f, 0.0f, 0.0f};
  settings.view.lighting.skyColor = {0.0f, 1.0f, 0.0f};
  settings.diffusionShare = 0.0f;  // the CPU check follows the tables' terms (the diffusion volume has its own tests)

  struct Case {
    const char* name;
    Particle particle;
  };
  Particle sphere;
  sphere.center = {0.3f, -0.2f, 0.1f};
  sphere.radii = glm::vec3(1.6f);
  sphere.rotation = quatFromEulerDegrees({20.0f, -35.0f, 50.0f});
  sphere.density = 0.25f;
  Particle ellipsoid = sphere;
  ellipsoid.radii = {2.0f, 1.1f, 1.4f};
  ellipsoid.density = 0.6f;
  // The reference particle turned inside the ellipsoid (x = c + R·diag(r)·Q·p, the cloudscape's
  // per-particle rotation): the CPU lookup maps through Particle::toParticle as the path tracer does.
  Particle turned = ellipsoid;
  turned.noiseRotation = glm::normalize(glm::quat(0.62f, -0.31f, 0.55f, 0.47f));
  const Case cases[] = {{"rotated sphere, rho 0.25", sphere},
                        {"rotated ellipsoid, rho 0.6", ellipsoid},
                        {"ellipsoid with the reference particle turned, rho 0.6", turned}};

  // Seed lighting (§4.4): multiple at ρ, crease ambient. Cloud lighting, for a particle alone:
  // no shadow from the sun volume (its own chord is taken out exactly), multiple at the ray's
  // density ρ·T̄ with no cloud around it, ambient sky·(1 − e^{−τ}); its single scattering takes
  // the larger of the table's mean sun transmittance and e^{−τ} of the particle's own sun-volume
  // ramp at the mean point (singleSunTransmittance), so it is rendered apart (terms = single)
  // and held between the table's value and P1·(1 − e^{−τ}), the value of an unshadowed chord.
  for (const LightingModel lighting : {LightingModel::Seed, LightingModel::Cloud})
  for (const Case& c : cases) {
    INFO(c.name << ", lighting " << toString(lighting));
    settings.lighting = lighting;
    settings.sunlight = defaultSunlight(lighting);
    const Particle& p = c.particle;
    const bool seed = lighting == LightingModel::Seed;
    RenderSettings apart = settings;
    apart.terms = seed ? kAllTerms : kTermMultiple | kTermAmbient;
    const Image image = renderer.render({p}, apart);
    REQUIRE(image.nonFiniteCount() == 0);
    apart.terms = kTermSingle;
    const Image singleImage = renderer.render({p}, apart);
    const CameraFrame camera(settings.view.camera, image.width, image.height);
    const glm::vec3 sun = settings.view.lighting.sunDirection;
    const glm::vec3 l = glm::normalize(p.toParticle() * sun);
    double maxRadiance = 0, maxAmbient = 0, maxTransmittance = 0, maxDistance = 0;
    int compared = 0, misses = 0, singleOutside = 0, singleAboveTable = 0;
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x) {
        const glm::vec3 dir = camera.rayDirection(float(x) + 0.5f, float(y) + 0.5f);
        const Hit h = intersect(p, camera.eye(), dir);
        const float* px = image.pixel(x, y);
        if (!h.hit) {
          if (h.closest > 1.01f) {
            CHECK(px[3] == 0.0f);
            ++misses;
          }
          continue;
        }
        // "Not too thin to matter": chords longer than 0.2 radii and optical depth above 0.05.
        const OpticalDepthSample s = lookupOpticalDepth(od, h.S, h.v, p.density);
        if (s.chordLength < 0.2f || s.opticalDepth < 0.05f) continue;
        const float phase = firstPhase(l1, glm::dot(dir, sun));
        const float single = phase * lookupScattering(l1, h.S, h.v, l, p.density * s.meanDensity);
        if (!seed) {
          const float rendered = singleImage.pixel(x, y)[0];
          const float unshadowed = phase * glsl::chordOpacity(s.opticalDepth);
          singleOutside += rendered < 0.99f * single - 1e-7f || rendered > 1.01f * unshadowed + 1e-7f;
          singleAboveTable += rendered > 1.01f * single + 1e-7f;
        }
        // the mean source of the sphere of density ρ over the ray's own opacity (shading.glsl)
        const float source = seed ? sampleScattering(lm, h.S, h.v, l, p.density)
                                  : multipleSourceBelowRange(lm, h.S, h.v, l, p.density * s.meanDensity);
        const float multiple = glsl::multipleScatteringFromTable(source, s.opticalDepth);
        const float ambient = seed ? glsl::ambientScale(s.transmittance, s.firstMatter)
                                   : glsl::uniformSkyAmbient(s.opticalDepth);
        const float distance = h.tEnter + s.firstMatter * (h.tExit - h.tEnter);
        INFO("pixel " << x << "," << y << " tau " << s.opticalDepth);
        maxRadiance = std::max(maxRadiance, relativeDifference(px[0], seed ? single + multiple : multiple));
        maxAmbient = std::max(maxAmbient, relativeDifference(px[1], ambient));
        maxTransmittance = std::max(maxTransmittance, relativeDifference(1.0 - px[3], s.transmittance));
        maxDistance = std::max(maxDistance, relativeDifference(image.distanceAt(x, y), distance));
        CHECK(px[2] == 0.0f);
        ++compared;
      }
    std::printf("[render] %s, %s lighting: %d pixels compared; max relative difference: radiance %.2e, ambient %.2e, "
                "transmittance %.2e, distance %.2e; cloud single above the table at %d pixels, outside its bounds at %d\n",
                c.name, toString(lighting), compared, maxRadiance, maxAmbient, maxTransmittance, maxDistance,
                singleAboveTable, singleOutside);
    CHECK(singleOutside == 0);
    CHECK(compared > 1000);
    CHECK(misses > 1000);
    CHECK(maxRadiance <= 0.01);
    CHECK(maxAmbient <= 0.01);
    CHECK(maxTransmittance <= 0.01);
    CHECK(maxDistance <= 0.01);
  }
}

TEST_CASE("render: particles are drawn back to front", "[render]") {
  std::vector<Particle> ps(3);
  ps[0].center = {0, 0, 0};
  ps[1].center = {0, 0, -5};
  ps[2].center = {0, 0, 3};
  const auto order = backToFrontOrder(ps, {0, 0, 10});
  CHECK(order == std::vector<std::size_t>{1, 0, 2});
}

TEST_CASE("render: degenerate geometry gives finite pixels", "[render]") {
  RenderFixture rig = RenderFixture::synthetic();
  Renderer& renderer = rig.renderer;
  RenderSettings settings;
  settings.width = 65;  // odd: the centre pixel's ray goes exactly through the particle's pole
  settings.height = 65;

  // Entry at the pole of the optical-depth frame (S = +z) with the sun at S (θS = 0) and the
  // view ray through the centre (θv = 0): every atan(0, 0) of the parameterization at once.
  Particle unit;
  settings.view.camera = Camera{{0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 40};
  settings.view.lighting.sunDirection = {0, 0, 1};
  Image image = renderer.render({unit}, settings);
  CHECK(image.nonFiniteCount() == 0);
  CHECK(image.pixel(32, 32)[3] > 0.5f);
  settings.view.lighting.sunDirection = {0, 0, -1};  // θS = π
  image = renderer.render({unit}, settings);
  CHECK(image.nonFiniteCount() == 0);

  // The eye inside one particle (at its centre): the front half of its chords is drawn, its first
  // matter at the eye (tests/test_camera_inside.cpp measures it against the path tracer); the
  // one ahead is drawn; a particle behind the eye is clipped.
  Particle around, ahead, behind;
  around.radii = glm::vec3(2.0f);
  around.center = {0, 0, 5};
  ahead.center = {0, 0, 0};
  behind.center = {0, 0, 9};
  image = renderer.render({around, ahead, behind}, settings);
  CHECK(image.nonFiniteCount() == 0);
  CHECK(image.pixel(32, 32)[3] > 0.5f);
  CHECK(image.pixel(0, 0)[3] > 0.0f);
  CHECK(image.pixel(0, 0)[3] < image.pixel(32, 32)[3]);  // the corner ray misses the particle ahead
  CHECK(image.distanceAt(32, 32) == Approx(0.0).margin(1e-3));
  const Image aheadOnly = renderer.render({ahead, behind}, settings);
  CHECK(aheadOnly.pixel(0, 0)[3] == 0.0f);
  CHECK(aheadOnly.distanceAt(32, 32) == Approx(4.0).margin(0.3));

  // No particles at all: an empty, transparent image.
  image = renderer.render({}, settings);
  CHECK(image.nonFiniteCount() == 0);
  CHECK(std::all_of(image.rgba.begin(), image.rgba.end(), [](float v) { return v == 0.0f; }));
}

namespace {

// The bilateral upscale written out independently, in double: output pixel (x, y) (rows from the
// top) maps to f = ((x + ½)·w/W − ½, (y + ½)·h/H − ½); its four neighbours ⌊f⌋ + {0, 1}² (clamped)
// are weighted bilinearly times 1 / (1 + (|d − d_n| / (0.05 d_n))²), d_n the distance of the
// nearest sample round(f) (1 where both lack a distance, 1e-3 where one does), plus 1e-12.
Image bilateralUpscaleReference(const Image& low, int width, int height) {
  Image out;
  out.width = width;
  out.height = height;
  out.rgba.resize(std::size_t(width) * height * 4);
  out.distance.resize(std::size_t(width) * height);
  const auto clampTo = [](long v, int n) { return int(std::min<long>(std::max<long>(v, 0), n - 1)); };
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const double fx = (x + 0.5) * low.width / width - 0.5, fy = (y + 0.5) * low.height / height - 0.5;
      const double ref = low.distanceAt(clampTo(std::lround(fx), low.width), clampTo(std::lround(fy), low.height));
      const long x0 = long(std::floor(fx)), y0 = long(std::floor(fy));
      const double ax = fx - std::floor(fx), ay = fy - std::floor(fy);
      double acc[4] = {0, 0, 0, 0}, wsum = 0;
      for (long j = 0; j < 2; ++j)
        for (long i = 0; i < 2; ++i) {
          const int px = clampTo(x0 + i, low.width), py = clampTo(y0 + j, low.height);
          const double d = low.distanceAt(px, py);
          double similarity;
          if (std::isinf(d) || std::isinf(ref)) {
            similarity = std::isinf(d) && std::isinf(ref) ? 1.0 : 1e-3;
          } else {
            const double rel = std::abs(d - ref) / (0.05 * std::max(ref, 1e-6));
            similarity = 1.0 / (1.0 + rel * rel);
          }
          const double w = (i ? ax : 1.0 - ax) * (j ? ay : 1.0 - ay) * similarity + 1e-12;
          for (int k = 0; k < 4; ++k) acc[k] += w * low.pixel(px, py)[k];
          wsum += w;
        }
      for (int k = 0; k < 4; ++k) out.rgba[4 * (std::size_t(y) * width + x) + k] = float(acc[k] / wsum);
      out.distance[std::size_t(y) * width + x] = float(ref);
    }
  return out;
}

}  // namespace

TEST_CASE("render: the GPU bilateral upscale equals the filter computed on the CPU", "[render]") {
  RenderFixture rig = RenderFixture::synthetic(DensityModel::Noise);
  Renderer& renderer = rig.renderer;
  const Scene scene = sourceScene("data/scenes/small.json");
  RenderSettings low = sceneSettings(scene, 48, 36);
  // The particle buffer of a render at 1/downscale resolution is the render at the low size
  // (same camera and aspect): upscale that one on the CPU.
  const Image small = renderer.render(scene.particles, low);
  std::size_t edges = 0;
  for (int y = 0; y + 1 < small.height; ++y)
    for (int x = 0; x + 1 < small.width; ++x)
      edges += std::isinf(small.distanceAt(x, y)) != std::isinf(small.distanceAt(x + 1, y + 1));
  REQUIRE(edges > 20);  // cloud against sky: where the depth term matters
  // Sizes whose particle buffer is 48 × 36 (⌈W / downscale⌉): exact multiples and odd sizes.
  struct Size {
    int width, height, down;
  };
  for (const Size& size : {Size{96, 72, 2}, Size{192, 144, 4}, Size{95, 71, 2}, Size{189, 141, 4}}) {
    const int down = size.down;
    INFO(size.width << "x" << size.height << " downscale " << down);
    RenderSettings s = low;
    s.width = size.width;
    s.height = size.height;
    s.downscale = down;
    const Image gpu = renderer.render(scene.particles, s);
    const Image cpu = bilateralUpscaleReference(small, s.width, s.height);
    REQUIRE(gpu.width == s.width);
    REQUIRE(gpu.height == s.height);
    double worst = 0, fromBilinear = 0;
    std::size_t distanceMismatch = 0, onBoundary = 0, boundaryLines = 0;
    // Where f lies within float rounding of a rounding boundary (a fraction of 0 or ½), float
    // and double may pick different neighbours: such pixels are not compared.
    const auto nearBoundary = [](double f) {
      const double frac = f - std::floor(f);
      return std::min({frac, 1.0 - frac, std::abs(frac - 0.5)}) < 1e-5;
    };
    for (int x = 0; x < s.width; ++x) boundaryLines += nearBoundary((x + 0.5) * small.width / s.width - 0.5);
    for (int y = 0; y < s.height; ++y) boundaryLines += nearBoundary((y + 0.5) * small.height / s.height - 0.5);
    for (int y = 0; y < s.height; ++y)
      for (int x = 0; x < s.width; ++x) {
        if (nearBoundary((x + 0.5) * small.width / s.width - 0.5) ||
            nearBoundary((y + 0.5) * small.height / s.height - 0.5)) {
          ++onBoundary;
          continue;
        }
        for (int k = 0; k < 4; ++k) worst = std::max<double>(worst, std::abs(gpu.pixel(x, y)[k] - cpu.pixel(x, y)[k]));
        const float dg = gpu.distanceAt(x, y), dc = cpu.distanceAt(x, y);
        distanceMismatch += !(dg == dc || std::abs(dg - dc) <= 1e-6f * dc);
        // Against plain bilinear interpolation of alpha (no depth term), to show the filter is
        // not that.
        const double fx = (x + 0.5) * small.width / s.width - 0.5, fy = (y + 0.5) * small.height / s.height - 0.5;
        const int x0 = std::clamp(int(std::floor(fx)), 0, small.width - 1), y0 = std::clamp(int(std::floor(fy)), 0, small.height - 1);
        const int x1 = std::min(x0 + 1, small.width - 1), y1 = std::min(y0 + 1, small.height - 1);
        const double ax = std::clamp(fx - std::floor(fx), 0.0, 1.0), ay = std::clamp(fy - std::floor(fy), 0.0, 1.0);
        const double bilinear = (1 - ay) * ((1 - ax) * small.pixel(x0, y0)[3] + ax * small.pixel(x1, y0)[3]) +
                                ay * ((1 - ax) * small.pixel(x0, y1)[3] + ax * small.pixel(x1, y1)[3]);
        fromBilinear = std::max(fromBilinear, std::abs(cpu.pixel(x, y)[3] - bilinear));
      }
    std::printf("[render] upscale %dx%d from 48x36: max |GPU - CPU| %.2e, distance mismatches %zu (%zu pixels of %zu lines "
                "on a rounding boundary skipped), max |bilateral - bilinear| alpha %.3f\n",
                s.width, s.height, worst, distanceMismatch, onBoundary, boundaryLines, fromBilinear);
    CHECK(gpu.nonFiniteCount() == 0);
    CHECK(worst < 1e-5);
    CHECK(distanceMismatch == 0);
    CHECK(boundaryLines * 10 <= static_cast<std::size_t>(s.width + s.height));
    CHECK(fromBilinear > 0.05);
  }
}

TEST_CASE("shader sources: a float define is a GLSL float literal that reads back as the same float", "[render]") {
  for (const float v : {1e-7f, 0.1f, 3.0f, -2.5f, 1e30f, 0.0f, 16777217.0f}) {
    const std::string d = render::glslFloatDefine("X", v);
    INFO(d);
    REQUIRE(d.rfind("#define X ", 0) == 0);
    const std::string literal = d.substr(10, d.size() - 11);
    CHECK(literal.find_first_of(".eE") != std::string::npos);  // not an int literal
    CHECK(std::strtof(literal.c_str(), nullptr) == v);
  }
  for (const float v : {std::numeric_limits<float>::infinity(), std::numeric_limits<float>::quiet_NaN()})
    CHECK_THROWS_AS(render::glslFloatDefine("X", v), std::invalid_argument);
}
