// Renderer II (cloudscapes): GPU generation against its CPU reference, the clipmap rings, the
// stability of particles under camera motion, light-space occlusion against an independent CPU
// computation, volume-aware blending (exact transmittance, draw-order independence), presets and
// bad input. Small images throughout.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <random>
#include <tuple>

#include <glm/geometric.hpp>

#include "support/CliRunner.h"
#include "core/Errors.h"
#include "core/TableLookup.h"
#include "scene/Cloudscape.h"
#include "scene/CloudscapeGrid.h"
#include "render/GlContext.h"
#include "render/GpuParticleRecord.h"
#include "render/Renderer.h"
#include "support/ImageDifference.h"
#include "support/RenderFixture.h"
#include "support/RenderLuts.h"

using namespace cloudlut;
using namespace cloudlut::render;
using namespace cloudlut::scene;
using namespace cloudlut::test;

namespace {

using Key = std::tuple<int, int, int, int>;
Key keyOf(const GridParticle& p) { return {p.ring, p.cellX, p.cellZ, p.layer}; }

std::map<Key, GridParticle> byKey(const std::vector<GridParticle>& ps) {
  std::map<Key, GridParticle> m;
  for (const auto& p : ps) m.emplace(keyOf(p), p);
  return m;
}

RenderSettings cloudSettings(const CloudscapeScene& scene, int w, int h) {
  RenderSettings s;
  s.width = w;
  s.height = h;
  Scene empty;
  empty.view = scene.view;
  s.view = resolveView(empty, {});
  return s;
}

// Sum of the optical depths of the particles along a ray, from the optical-depth table on the CPU.
double opticalDepthAlong(const Table4D& od, const std::vector<Particle>& ps, const glm::vec3& eye,
                         const glm::vec3& dir, float minChord, bool& thin) {
  double tau = 0.0;
  thin = false;
  for (const Particle& p : ps) {
    const Hit h = intersect(p, eye, dir);
    if (!h.hit) {
      if (h.closest < 1.02f) thin = true;
      continue;
    }
    const OpticalDepthSample s = lookupOpticalDepth(od, h.S, h.v, p.density);
    if (s.chordLength < minChord) thin = true;
    tau += s.opticalDepth;
  }
  return tau;
}

}  // namespace

TEST_CASE("cloudscape: presets load, report their density range, and bad ones name the field", "[cloudscape]") {
  for (const std::string& name : cloudscapePresetNames()) {
    INFO(name);
    const CloudscapeScene s = loadCloudscape(name);
    CHECK(s.cloud.cloudTop > s.cloud.cloudBase);
    for (const std::string& q : qualityPresetNames()) {
      const glm::vec2 range = cloudscapeDensityRange(s.cloud, qualityPreset(q));
      CHECK(range.x > 0.0f);
      CHECK(range.y > range.x);
    }
  }
  CHECK(qualityPreset("low").maxParticles() == 104LL * 104 * 4 * 2);
  CHECK(qualityPreset("medium").maxParticles() == 136LL * 136 * 4 * 4);
  CHECK(qualityPreset("high").maxParticles() == 184LL * 184 * 4 * 6);
  CHECK_THROWS_AS(qualityPreset("ultra"), UsageError);
  CHECK_THROWS_AS(loadCloudscape("cirrus_no_such_preset"), UsageError);

  const nlohmann::json ok = nlohmann::json::parse(R"({"coverage": 0.5, "density": 1, "cloud_base_m": 1000, "cloud_top_m": 2000})");
  CHECK_NOTHROW(parseCloudscape(ok, "t.json"));
  const std::vector<std::pair<std::string, std::string>> bad = {
      {R"({"density": 1, "cloud_base_m": 1000, "cloud_top_m": 2000})", "coverage"},
      {R"({"coverage": 1.5, "density": 1, "cloud_base_m": 1000, "cloud_top_m": 2000})", "coverage"},
      {R"({"coverage": 0.5, "density": -1, "cloud_base_m": 1000, "cloud_top_m": 2000})", "density"},
      {R"({"coverage": 0.5, "density": 1, "cloud_top_m": 2000})", "cloud_base_m"},
      {R"({"coverage": 0.5, "density": 1, "cloud_base_m": 3000, "cloud_top_m": 2000})", "cloud_top_m"},
      {R"({"coverage": 0.5, "density": 1, "cloud_base_m": 1000, "cloud_top_m": 2000, "particle_size": [2, 1]})", "particle_size"},
      {R"({"coverage": 0.5, "density": 1, "cloud_base_m": 1000, "cloud_top_m": 2000, "visibility_m": "far"})", "visibility_m"},
      {R"({"coverage": 0.5, "density": 1, "cloud_base_m": 1000, "cloud_top_m": 2000, "colour": 1})", "colour"},
      {R"({"coverage": 0.5, "density": 1, "cloud_base_m": 1000, "cloud_top_m": 2000, "camera": {"fov_deg": 0}})", "camera.fov_deg"},
  };
  for (const auto& [text, field] : bad) {
    INFO(text);
    try {
      parseCloudscape(nlohmann::json::parse(text), "t.json");
      FAIL("accepted");
    } catch (const FileError& e) {
      CHECK(std::string(e.what()).find("t.json: " + field) != std::string::npos);
    }
  }
}

TEST_CASE("cloudscape: rings double their cells, nothing beyond the far plane, stable under small moves",
          "[cloudscape]") {
  const CloudscapeScene scene = loadCloudscape(kDefaultCloudscape);
  const QualityPreset q = qualityPreset("low");
  const GridParameters g = gridParameters(scene.cloud, q);
  for (int r = 1; r < q.rings; ++r) CHECK(grid::cgCellSize(r, g.g0) == 2.0f * grid::cgCellSize(r - 1, g.g0));

  RenderSettings s = cloudSettings(scene, 160, 90);
  const CpuGeneration a = generateCloudscapeCpu(scene.cloud, q, s.view.camera, s.width, s.height);
  REQUIRE(a.particles.size() > 100);
  const float far = modelledFarDistance(scene.cloud, q);
  int perRing[8] = {0};
  for (const GridParticle& p : a.particles) {
    ++perRing[p.ring];
    CHECK(glm::length(p.particle.center - s.view.camera.eye) <= far);
    const float cell = grid::cgCellSize(p.ring, g.g0);
    // Inside its own cell (plus the jitter), and sized by its ring's cell.
    const glm::vec2 c = grid::cgCellCentre(p.ring, p.cellX, p.cellZ, g.g0);
    CHECK(std::abs(p.particle.center.x - c.x) <= 0.5f * scene.cloud.jitter * cell + 1e-3f * cell);
    CHECK(std::abs(p.particle.center.z - c.y) <= 0.5f * scene.cloud.jitter * cell + 1e-3f * cell);
    CHECK(p.particle.radii.x <= cell * scene.cloud.particleSize.y * 1.0001f);
    CHECK(p.particle.center.y >= scene.cloud.cloudBase);
    CHECK(p.particle.center.y <= scene.cloud.cloudTop);
    CHECK(p.weight > 0.0f);
    CHECK(p.weight <= 1.0f);
  }
  int ringsUsed = 0;
  for (int r = 0; r < q.rings; ++r) ringsUsed += perRing[r] > 0;
  CHECK(ringsUsed >= 3);

  // Move the camera by 0.4 of a ring-0 cell: every inner-ring particle at full weight in both
  // frames is bit-identical.
  Camera moved = s.view.camera;
  const glm::vec3 shift(0.4f * scene.cloud.cellSize, 0.0f, 0.1f * scene.cloud.cellSize);
  moved.eye += shift;
  moved.target += shift;
  const CpuGeneration b = generateCloudscapeCpu(scene.cloud, q, moved, s.width, s.height);
  const auto mb = byKey(b.particles);
  int compared = 0;
  for (const GridParticle& p : a.particles) {
    if (p.ring != 0 || p.weight < 1.0f) continue;
    const auto it = mb.find(keyOf(p));
    if (it == mb.end() || it->second.weight < 1.0f) continue;
    ++compared;
    CHECK(it->second.particle.center == p.particle.center);
    CHECK(it->second.particle.radii == p.particle.radii);
    CHECK(it->second.particle.density == p.particle.density);
  }
  CHECK(compared > 50);
}

TEST_CASE("cloudscape: GPU generation equals the CPU reference", "[cloudscape]") {
  RenderFixture rig = RenderFixture::synthetic();
  Renderer& renderer = rig.renderer;
  const CloudscapeScene scene = loadCloudscape(kDefaultCloudscape);
  // The presets, and a grid of more layers than any preset (the records' identity must hold them).
  const QualityPreset tall{"tall", 32, 2, 24};
  for (const QualityPreset& q : {qualityPreset("low"), qualityPreset("medium"), tall}) {
    const char* quality = q.name.c_str();
    INFO(quality);
    const RenderSettings s = cloudSettings(scene, 160, 90);
    const CpuGeneration cpu = generateCloudscapeCpu(scene.cloud, q, s.view.camera, s.width, s.height);
    const CpuGeneration gpu = renderer.generateOnGpu(scene.cloud, q, s);
    CHECK(gpu.validCells == cpu.validCells);
    CHECK(gpu.particles.size() == cpu.particles.size());
    // the light-space passes take every particle within the far distance, in view or not
    CHECK(gpu.lit == cpu.lit);
    CHECK(gpu.lit == generateCloudscapeAround(scene.cloud, q, s.view.camera.eye).particles.size());
    CHECK(gpu.lit > gpu.particles.size());
    const auto mc = byKey(cpu.particles);
    std::size_t matched = 0;
    double worst = 0.0;
    int topLayer = 0;
    for (const GridParticle& p : gpu.particles) {
      const auto it = mc.find(keyOf(p));
      if (it == mc.end()) continue;
      ++matched;
      const float scale = it->second.particle.radii.x;
      worst = std::max<double>(worst, glm::length(p.particle.center - it->second.particle.center) / scale);
      worst = std::max<double>(worst, glm::length(p.particle.radii - it->second.particle.radii) / scale);
      worst = std::max<double>(worst, std::abs(p.particle.density - it->second.particle.density) /
                                          std::max(it->second.particle.density, 1e-6f));
      worst = std::max<double>(worst, std::abs(p.weight - it->second.weight));
      topLayer = std::max(topLayer, p.layer);
    }
    std::printf("[cloudscape] %s: %zu particles drawn (CPU %zu) of %zu lit, %zu cells, %zu matched, worst relative "
                "difference %.2e\n",
                quality, gpu.particles.size(), cpu.particles.size(), gpu.lit, gpu.validCells, matched, worst);
    CHECK(matched == cpu.particles.size());
    CHECK(worst < 1e-4);
    if (q.name == "tall") CHECK(topLayer >= 16);
  }
  // Beyond what the records can identify: a usage error, not a wrong identity.
  const QualityPreset tooTall{"too tall", 8, 2, kGridLayerLimit + 1};
  CHECK_THROWS_AS(renderer.generateOnGpu(scene.cloud, tooTall, cloudSettings(scene, 160, 90)), UsageError);
}

TEST_CASE("cloudscape: occlusion matches exp(-xi * sum tau) computed on the CPU", "[cloudscape]") {
  RenderFixture rig = RenderFixture::synthetic();
  const io::LutSet& luts = rig.luts;
  Renderer& renderer = rig.renderer;
  const float sigma = unitOpticalRadius(luts.tables.at("optical_depth").table);
  RenderSettings s;
  s.width = 64;
  s.height = 64;
  s.view.camera = Camera{{0, 1, 20}, {0, 1, 0}, {0, 1, 0}, 40};
  s.view.lighting.sunDirection = glm::normalize(glm::vec3(0.2f, 1.0f, 0.1f));
  s.smoothOcclusion = false;
  Particle receiver, occluder, occluder2, free;
  receiver.center = {0, 0, 0};
  occluder.center = receiver.center + 3.0f * s.view.lighting.sunDirection + glm::vec3(0.3f, 0, 0);
  occluder.radii = {1.5f, 1.0f, 1.2f};
  occluder.rotation = quatFromEulerDegrees({10, 40, 0});
  occluder.density = 2.0f;
  occluder2.center = receiver.center + 6.0f * s.view.lighting.sunDirection;
  occluder2.density = 0.5f;
  free.center = {6, 0, 0};
  const std::vector<Particle> ps = {receiver, occluder, occluder2, free};
  const std::vector<float> sun = renderer.sunlight(ps, s);
  REQUIRE(sun.size() == ps.size());

  // Independent CPU: chord of the ray from each centre toward the sun through every other particle.
  for (std::size_t i = 0; i < ps.size(); ++i) {
    double tau = 0.0;
    for (std::size_t j = 0; j < ps.size(); ++j) {
      if (j == i) continue;
      const glm::mat3 inv = ps[j].toParticle();
      const glm::dvec3 o = inv * (ps[i].center - ps[j].center), d = inv * s.view.lighting.sunDirection;
      const double a = glm::dot(d, d), b = glm::dot(o, d), c = glm::dot(o, o) - 1.0;
      const double disc = b * b - a * c;
      if (disc <= 0) continue;
      const double t0 = std::max(0.0, (-b - std::sqrt(disc)) / a), t1 = (-b + std::sqrt(disc)) / a;
      if (t1 > t0) tau += ps[j].density * sigma * (t1 - t0) * std::sqrt(a);
    }
    const double expected = std::exp(-kOcclusionXi * tau);
    INFO("particle " << i << " tau " << tau);
    CHECK(sun[i] == Approx(expected).epsilon(1e-3));
  }
  CHECK(sun[0] < 0.5f * sun[3]);  // behind the dense particle, toward the sun
  CHECK(sun[3] == Approx(1.0f));

  // With smoothing the shadowed particle still receives less light than the free one.
  s.smoothOcclusion = true;
  const std::vector<float> smooth = renderer.sunlight(ps, s);
  CHECK(smooth[0] < smooth[3]);
  for (float v : smooth) CHECK(std::isfinite(v));
}

TEST_CASE("cloudscape: volume blending gives exp(-total optical depth) and ignores draw order", "[cloudscape]") {
  TempDir tmp;
  const Table4D od = smallOpticalDepth(DensityModel::Sphere);
  const Table4D l1 = syntheticSingle(), lm = syntheticMultiple();
  writeLutSet(tmp / "luts", {&od, &l1, &lm});
  const io::LutSet luts = io::readLutSet(tmp / "luts");
  auto context = createHeadlessContext();
  Renderer renderer(*context, luts);
  RenderSettings s;
  s.width = 96;
  s.height = 72;
  s.view.camera = Camera{{0.3f, 0.4f, 8.0f}, {0, 0, 0}, {0, 1, 0}, 40};
  s.view.lighting.sunDirection = glm::normalize(glm::vec3(0.4f, 0.8f, 0.3f));
  s.occlusion = false;  // the colour test compares draw orders; occlusion is order-free anyway

  Particle p0, p1, p2;
  p0.center = {-0.6f, 0.0f, 0.0f};
  p0.radii = glm::vec3(1.2f);
  p0.density = 0.05f;
  p1.center = {0.5f, 0.2f, 0.4f};
  p1.radii = glm::vec3(1.0f);
  p1.density = 0.08f;
  p2.center = {0.0f, -0.3f, -0.8f};
  p2.radii = {1.4f, 0.9f, 1.1f};
  p2.density = 0.03f;
  const std::vector<std::vector<Particle>> sets = {{p0, p1}, {p0, p1, p2}};
  const CameraFrame camera(s.view.camera, s.width, s.height);
  for (const auto& ps : sets) {
    INFO(ps.size() << " spheres");
    s.blend = BlendMode::Volume;
    RenderStats stats;
    const Image image = renderer.render(ps, s, &stats);
    REQUIRE(image.nonFiniteCount() == 0);
    CHECK(stats.fragmentOverflow == 0);
    double worst = 0.0;
    int compared = 0, overlapping = 0;
    for (int y = 0; y < s.height; ++y)
      for (int x = 0; x < s.width; ++x) {
        const glm::vec3 dir = camera.rayDirection(float(x) + 0.5f, float(y) + 0.5f);
        bool thin = false;
        const double tau = opticalDepthAlong(od, ps, camera.eye(), dir, 0.2f, thin);
        if (thin || tau == 0.0) continue;
        int hits = 0;
        for (const Particle& p : ps) hits += intersect(p, camera.eye(), dir).hit;
        overlapping += hits >= 2;
        worst = std::max(worst, std::abs((1.0 - image.pixel(x, y)[3]) - std::exp(-tau)) / std::exp(-tau));
        ++compared;
      }
    std::printf("[cloudscape] volume, %zu spheres: %d pixels (%d overlapping), max relative transmittance error %.2e\n",
                ps.size(), compared, overlapping, worst);
    CHECK(overlapping > 150);
    CHECK(worst < 2e-3);

    // Draw order: shuffled lists give the same volume image.
    std::vector<Particle> shuffled(ps.rbegin(), ps.rend());
    std::rotate(shuffled.begin(), shuffled.begin() + 1, shuffled.end());
    const Image again = renderer.render(shuffled, s);
    double diff = 0.0;
    for (std::size_t i = 0; i < image.rgba.size(); ++i) diff = std::max<double>(diff, std::abs(image.rgba[i] - again.rgba[i]));
    CHECK(diff < 1e-5);
  }

  // Alpha blending pops when the back-to-front order flips (p1's centre crosses p0's distance);
  // volume blending changes only by the tiny motion itself.
  const float d0 = glm::length(p0.center - s.view.camera.eye);
  Particle a = p1, b = p1;
  const glm::vec3 away = glm::normalize(p1.center - s.view.camera.eye);
  a.center = s.view.camera.eye + away * (d0 - 0.01f);
  b.center = s.view.camera.eye + away * (d0 + 0.01f);
  p0.density = p1.density = a.density = b.density = 0.4f;
  double popAlpha = 0, popVolume = 0;
  for (BlendMode mode : {BlendMode::Alpha, BlendMode::Volume}) {
    s.blend = mode;
    const Image ia = renderer.render({p0, a}, s), ib = renderer.render({p0, b}, s);
    double sum = 0;
    for (std::size_t i = 0; i < ia.rgba.size(); i += 4) sum += std::abs(ia.rgba[i] - ib.rgba[i]);
    (mode == BlendMode::Alpha ? popAlpha : popVolume) = sum / double(ia.rgba.size() / 4);
  }
  std::printf("[cloudscape] order flip: mean |change| alpha %.3e, volume %.3e\n", popAlpha, popVolume);
  CHECK(popAlpha > 5.0 * popVolume);
}

TEST_CASE("cloudscape: the default scene renders non-empty, finite, in every blend mode", "[cloudscape]") {
  RenderFixture rig = RenderFixture::synthetic(DensityModel::Noise);
  Renderer& renderer = rig.renderer;
  const CloudscapeScene scene = loadCloudscape(kDefaultCloudscape);
  RenderSettings s = cloudSettings(scene, 128, 72);
  for (BlendMode mode : {BlendMode::Volume, BlendMode::Alpha}) {
    for (int down : {1, 2}) {
      INFO(toString(mode) << " downscale " << down);
      s.blend = mode;
      s.downscale = down;
      RenderStats stats;
      const Image image = renderer.renderCloudscape(scene.cloud, qualityPreset("low"), s, &stats);
      REQUIRE(image.width == 128);
      REQUIRE(image.height == 72);
      CHECK(image.nonFiniteCount() == 0);
      std::size_t covered = 0;
      for (std::size_t i = 3; i < image.rgba.size(); i += 4) covered += image.rgba[i] > 0.05f;
      CHECK(stats.particles > 100);
      CHECK(covered > image.rgba.size() / 4 / 20);
    }
  }
}

TEST_CASE("cloudscape CLI: default scene, presets, frames, and bad input", "[cloudscape][cli]") {
  TempDir tmp;
  writeSyntheticLutSet(tmp / "luts");
  const std::string base = "render --luts '" + (tmp / "luts").string() + "' --width 96 --height 54 --quality low ";
  CliResult r = runCli(base + "--out '" + (tmp / "default.png").string() + "'");
  INFO(r.err);
  CHECK(r.exitCode == 0);
  CHECK(std::filesystem::exists(tmp / "default.png"));
  r = runCli(base + "--scene stratocumulus --blend alpha --downscale 2 --frames 2 --out '" + (tmp / "seq.png").string() + "'");
  CHECK(r.exitCode == 0);
  CHECK(std::filesystem::exists(tmp / "seq_0000.png"));
  CHECK(std::filesystem::exists(tmp / "seq_0001.png"));

  const std::string out = " --out '" + (tmp / "bad.png").string() + "'";
  r = runCli(base + "--scene cirrus_nope" + out);
  CHECK(r.exitCode == 2);
  CHECK(r.err.find("cirrus_nope") != std::string::npos);
  r = runCli(base + "--quality ultra" + out);
  CHECK(r.exitCode == 2);
  r = runCli(base + "--blend additive" + out);
  CHECK(r.exitCode == 2);
  r = runCli(base + "--downscale 3" + out);
  CHECK(r.exitCode == 2);
  r = runCli(base + "--tile-plan exact" + out);
  CHECK(r.exitCode == 2);
  CHECK(r.err.find("--tile-plan") != std::string::npos);
  {
    std::ofstream f(tmp / "bad.json");
    f << R"({"coverage": 2, "density": 1, "cloud_base_m": 1000, "cloud_top_m": 2000})";
  }
  r = runCli(base + "--scene '" + (tmp / "bad.json").string() + "'" + out);
  CHECK(r.exitCode == 1);
  CHECK(r.err.find("coverage") != std::string::npos);
  // A tile pool budget that holds not even one pixel's fragments (larger images are tiled:
  // tests/test_volume_tiles.cpp).
  r = runCli("render --luts '" + (tmp / "luts").string() + "' --width 64 --height 64 --quality low "
             "--fragments-per-pixel 1024 --volume-pool-mib 0.01" + out);
  CHECK(r.exitCode == 2);
  CHECK(r.err.find("MiB") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(tmp / "bad.png"));
}

// Not run by default: writes the synthetic LUT set to $CLOUDLUT_SYNTHETIC_LUTS for manual renders.
TEST_CASE("cloudscape: write the synthetic LUT set", "[.write-synthetic-luts]") {
  const char* dir = std::getenv("CLOUDLUT_SYNTHETIC_LUTS");
  REQUIRE(dir != nullptr);
  writeSyntheticLutSet(dir, DensityModel::Noise);
}

// The light of what the camera sees does not depend on what else is in view: the light-space
// passes (sun, zenith and diffusion volumes) take every particle within the far distance, not only
// those in the frustum, so a particle that leaves the view still shadows and makes up the clouds
// in it. Two renders from the same camera, 160×90 and 90×90 (the same vertical field of view and
// pixel size, so the square image is the wide one's middle 90 columns), agree pixel for pixel.
// With the frustum's particles only they differed by 6.8·10⁻³ (relative RMSE over the cloud; now
// 7·10⁻⁵), and a 60-frame flight into the default cloudscape stepped by up to 9.6% between frames
// where it now steps by at most 1.2% (docs/LIGHTING.md).
TEST_CASE("cloudscape: the light in view does not depend on the frustum", "[cloudscape][lighting]") {
  RenderFixture rig = RenderFixture::synthetic(DensityModel::Noise);
  const CloudscapeScene scene = loadCloudscape(kDefaultCloudscape);
  RenderSettings wide = cloudSettings(scene, 160, 90), square = cloudSettings(scene, 90, 90);
  wide.blend = square.blend = BlendMode::Volume;
  RenderStats wideStats, squareStats;
  const Image a = rig.renderer.renderCloudscape(scene.cloud, qualityPreset("low"), wide, &wideStats);
  const Image b = rig.renderer.renderCloudscape(scene.cloud, qualityPreset("low"), square, &squareStats);
  REQUIRE(squareStats.particles < wideStats.particles);  // the square frustum draws fewer
  // The square's columns 0 … 89 are the wide image's 35 … 124.
  const ColourDifference e = colourDifference(b, 0, 0, a, 35, 0, 90, 90);
  const std::size_t cloud = e.pixels;
  REQUIRE(cloud > 500);
  const double difference = e.relativeRmse;
  std::printf("[cloudscape] %zu and %zu particles drawn (%zu lit): the square view against the wide one's middle, "
              "relative RMSE %.2e over %zu cloud pixels\n",
              squareStats.particles, wideStats.particles, wideStats.litParticles, difference, cloud);
  CHECK(squareStats.litParticles == wideStats.litParticles);
  CHECK(difference < 1e-3);
}
