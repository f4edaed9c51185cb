// Cloudscape level of detail and structure (issue 14): the tables' reference radius reaches the
// generator, the column optical depth is the same in every ring (camera above a square of sky vs
// 60 km away from it, and each ring alone over the same square), particles stay in the layer with densities in the tables' range, ring
// borders do not show over a slow camera move, the dump of a cloudscape renders like the
// cloudscape, and neighbouring particles turn the reference particle differently.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <tuple>

#include <glm/geometric.hpp>

#include "core/Errors.h"
#include "core/TableLookup.h"
#include "render/GlContext.h"
#include "render/Renderer.h"
#include "scene/Cloudscape.h"
#include "scene/CloudscapeGrid.h"
#include "scene/SceneWriter.h"
#include "support/CliRunner.h"
#include "support/RenderFixture.h"
#include "support/RenderLuts.h"

using namespace cloudlut;
using namespace cloudlut::render;
using namespace cloudlut::scene;
using namespace cloudlut::test;

namespace {

constexpr double kPiD = 3.14159265358979323846;

RenderSettings settingsFor(const View& view, int w, int h) {
  RenderSettings s;
  s.width = w;
  s.height = h;
  s.view = view;
  return s;
}

View viewOf(const CloudscapeScene& scene) {
  Scene empty;
  empty.view = scene.view;
  return resolveView(empty, {});
}

// Area integral of a particle's vertical column optical depth per unit σ, m²: ∫ ρ ℓ dA =
// ρ · (4π/3) · a · c for semi-axes a, c across the vertical (the unit sphere's volume times the
// horizontal scale; the noise rotation does not change the sphere).
double columnMass(const Particle& p) { return p.density * (4.0 / 3.0) * kPiD * p.radii.x * p.radii.z; }

// Mean vertical column optical depth per σ over the square [lo, hi]² (x, z) from the particles
// whose centres lie in it, and the same on a coarse grid of `n`² blocks (the cloud pattern).
struct SquareColumns {
  double mean = 0;
  std::vector<double> blocks;
};
SquareColumns columnsOver(const std::vector<GridParticle>& ps, glm::vec2 lo, float side, int n) {
  SquareColumns out;
  out.blocks.assign(static_cast<std::size_t>(n * n), 0.0);
  const float block = side / static_cast<float>(n);
  double total = 0;
  for (const GridParticle& g : ps) {
    const glm::vec2 rel = glm::vec2(g.particle.center.x, g.particle.center.z) - lo;
    if (rel.x < 0 || rel.y < 0 || rel.x >= side || rel.y >= side) continue;
    const double m = columnMass(g.particle);
    total += m;
    out.blocks[static_cast<std::size_t>(int(rel.y / block) * n + int(rel.x / block))] += m / (block * block);
  }
  out.mean = total / (double(side) * side);
  return out;
}

double correlation(const std::vector<double>& a, const std::vector<double>& b) {
  double ma = 0, mb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ma += a[i];
    mb += b[i];
  }
  ma /= double(a.size());
  mb /= double(b.size());
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  return sab / std::sqrt(saa * sbb);
}

// Ring `ring` alone over the square [lo, lo + side]² (x, z): every cell of that ring whose centre
// lies in the square, at level-of-detail weight 1 (the ring as it is drawn where it is not
// fading), its particles' column masses summed as in columnsOver.
SquareColumns ringColumnsOver(const CloudType& cloud, const QualityPreset& q, int ring, glm::vec2 lo, float side, int n) {
  const GridParameters g = gridParameters(cloud, q);
  const float s = grid::cgCellSize(ring, g.g0);
  std::vector<GridParticle> ps;
  const int cells = static_cast<int>(std::lround(side / s));
  const glm::ivec2 first(static_cast<int>(std::lround(lo.x / s)), static_cast<int>(std::lround(lo.y / s)));
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i) {
      const int ix = first.x + i, iz = first.y + j;
      const glm::vec2 cellCloud = grid::cgCellCloud(ring, ix, iz, g.g0, g.g1, g.g2, g.g3, g.g4);
      const int layers = grid::cgLayerCount(cellCloud.x, g.g0, g.g4);
      for (int k = 0; k < layers; ++k) {
        const grid::CgParticle p =
            grid::cgParticle(ring, ix, iz, k, cellCloud.x, cellCloud.y, 1.0f, g.g0, g.g1, g.g2, g.g3, g.g4);
        GridParticle gp;
        gp.particle.center = grid::vec3(grid::cgCellCentre(ring, ix, iz, g.g0).x, p.centre.y,
                                        grid::cgCellCentre(ring, ix, iz, g.g0).y);  // binned by its cell
        gp.particle.radii = p.radii;
        gp.particle.density = p.density;
        gp.ring = ring;
        ps.push_back(gp);
      }
    }
  return columnsOver(ps, lo, side, n);
}

}  // namespace

TEST_CASE("cloudscape LOD: the tables' reference radius sets the particles' density", "[cloudscape][lod]") {
  TempDir tmp;
  writeSyntheticLutSet(tmp / "luts183");
  {
    Table4D od = smallOpticalDepth();
    od.parameters()["radius_m"] = 2.0 * defaults::kParticleRadiusMetres;
    const Table4D l1 = syntheticSingle(), lm = syntheticMultiple();
    writeLutSet(tmp / "luts367", {&od, &l1, &lm});
  }
  const CloudscapeScene scene = loadCloudscape(kDefaultCloudscape);
  const QualityPreset q = qualityPreset("low");
  const RenderSettings s = settingsFor(viewOf(scene), 96, 54);
  auto context = createHeadlessContext();
  std::map<std::tuple<int, int, int, int>, float> tau[2];  // optical radius σ·ρ per particle
  int k = 0;
  for (const char* dir : {"luts183", "luts367"}) {
    const io::LutSet luts = io::readLutSet(tmp / dir);
    const float sigma = unitOpticalRadius(luts.tables.at("optical_depth").table);
    Renderer renderer(*context, luts);
    for (const GridParticle& p : renderer.generateOnGpu(scene.cloud, q, s).particles)
      tau[k][{p.ring, p.cellX, p.cellZ, p.layer}] = sigma * p.particle.density;
    ++k;
  }
  REQUIRE(tau[0].size() > 100);
  REQUIRE(tau[0].size() == tau[1].size());
  double worst = 0;
  for (const auto& [key, t] : tau[0]) worst = std::max(worst, std::abs(double(tau[1].at(key)) / t - 1.0));
  std::printf("[cloudscape lod] R = 183.8 m vs 367.6 m tables: worst relative difference of sigma*rho %.2e\n", worst);
  CHECK(worst < 1e-5);
}

TEST_CASE("cloudscape LOD: the column optical depth is the same seen from above and from 60 km", "[cloudscape][lod]") {
  CloudscapeScene scene = loadCloudscape(kDefaultCloudscape);
  scene.cloud.visibility = 1e6f;  // keep the far ring
  const QualityPreset q = qualityPreset("low");
  const float side = 16000.0f;
  const glm::vec2 lo(-0.5f * side, -0.5f * side);
  // Above the square's centre: ring 0 (and 1) over it; 60 km away: the outer ring.
  const CpuGeneration above = generateCloudscapeAround(scene.cloud, q, glm::vec3(0.0f, 600.0f, 0.0f));
  const CpuGeneration far = generateCloudscapeAround(scene.cloud, q, glm::vec3(60000.0f, 600.0f, 0.0f));
  int ringsAbove[8] = {0}, ringsFar[8] = {0};
  for (const auto& p : above.particles)
    if (std::abs(p.particle.center.x) < 0.5f * side && std::abs(p.particle.center.z) < 0.5f * side) ++ringsAbove[p.ring];
  for (const auto& p : far.particles)
    if (std::abs(p.particle.center.x) < 0.5f * side && std::abs(p.particle.center.z) < 0.5f * side) ++ringsFar[p.ring];
  const int n = 4;
  const SquareColumns a = columnsOver(above.particles, lo, side, n), b = columnsOver(far.particles, lo, side, n);
  const double sigma = static_cast<double>(defaults::kUnitOpticalRadius) / defaults::kParticleRadiusMetres;
  const double r = correlation(a.blocks, b.blocks);
  std::printf("[cloudscape lod] column optical depth over a %.0f km square: above %.3f (rings 0-3: %d %d %d %d "
              "particles), 60 km away %.3f (%d %d %d %d), ratio %.3f, pattern correlation %.3f\n",
              side / 1000.0, sigma * a.mean, ringsAbove[0], ringsAbove[1], ringsAbove[2], ringsAbove[3],
              sigma * b.mean, ringsFar[0], ringsFar[1], ringsFar[2], ringsFar[3], b.mean / a.mean, r);
  CHECK(ringsAbove[0] > 0);
  CHECK(ringsFar[0] == 0);
  CHECK(ringsFar[q.rings - 1] > 0);
  CHECK(a.mean > 0);
  CHECK(std::abs(b.mean / a.mean - 1.0) < 0.10);
  CHECK(r > 0.6);  // 4 km blocks; the outer ring's cells are 1.5 km wide
}

TEST_CASE("cloudscape LOD: every ring alone has ring 0's column optical depth over the same square",
          "[cloudscape][lod]") {
  // The same 23.5 km square (16 cells of the outer ring) drawn by each ring alone: 128², 64², 32²
  // and 16² cells. Goal (issue 14): every ring's mean within 10% of ring 0's, the same pattern.
  for (const std::string& preset : cloudscapePresetNames()) {
    const char* name = preset.c_str();
    const CloudscapeScene scene = loadCloudscape(preset);
    const QualityPreset q = qualityPreset("medium");
    const float s3 = scene.cloud.cellSize * 8.0f, side = 16.0f * s3;
    const int n = 4;
    double worst = 0, leastCorrelation = 1;
    std::vector<SquareColumns> rings;
    for (const glm::vec2 lo : {glm::vec2(-8.0f * s3, -8.0f * s3), glm::vec2(24.0f * s3, -40.0f * s3)}) {
      const SquareColumns ring0 = ringColumnsOver(scene.cloud, q, 0, lo, side, n);
      REQUIRE(ring0.mean > 0);
      std::printf("[cloudscape lod] %s, square at (%.0f, %.0f) km, each ring alone: column mass per m2", name,
                  lo.x / 1000.0, lo.y / 1000.0);
      for (int r = 0; r < q.rings; ++r) {
        const SquareColumns c = r == 0 ? ring0 : ringColumnsOver(scene.cloud, q, r, lo, side, n);
        const double corr = correlation(ring0.blocks, c.blocks);
        std::printf("  ring %d %.2f (ratio %.3f, pattern %.3f)", r, c.mean, c.mean / ring0.mean, corr);
        worst = std::max(worst, std::abs(c.mean / ring0.mean - 1.0));
        leastCorrelation = std::min(leastCorrelation, corr);
      }
      std::printf("\n");
    }
    INFO(name);
    // A coarse cell's column is the mean of the finer ones under it (cgCellCloud); sampling the
    // thresholded coverage at its centre instead gave towering cumulus (3.2 km ring-3 cells)
    // +14% in ring 3 on its sparse second square.
    CHECK(worst < 0.10);
    CHECK(leastCorrelation > 0.6);
  }
}

TEST_CASE("cloudscape LOD: particles stay in the layer, densities in the tables' range", "[cloudscape][lod]") {
  for (const std::string& name : cloudscapePresetNames()) {
    const CloudscapeScene scene = loadCloudscape(name);
    for (const char* quality : {"low", "medium"}) {
      INFO(name << " " << quality);
      const QualityPreset q = qualityPreset(quality);
      const glm::vec2 range = cloudscapeDensityRange(scene.cloud, q);
      const CpuGeneration g = generateCloudscapeAround(scene.cloud, q, viewOf(scene).camera.eye);
      REQUIRE(g.particles.size() > 100);
      float lowest = 1e9f, highest = -1e9f, rhoMax = 0, rhoMin = 1e9f;
      for (const GridParticle& p : g.particles) {
        // The rotation Q turns the unit sphere only: the vertical reach is the y semi-axis.
        lowest = std::min(lowest, p.particle.center.y - p.particle.radii.y);
        highest = std::max(highest, p.particle.center.y + p.particle.radii.y);
        rhoMax = std::max(rhoMax, p.particle.density);
        if (p.weight * p.fill >= 1.0f / 16.0f) rhoMin = std::min(rhoMin, p.particle.density);
      }
      std::printf("[cloudscape lod] %s %s: %zu particles, y %.0f..%.0f m (layer %.0f..%.0f), rho %.3f..%.3f "
                  "(range %.3f..%.3f)\n",
                  name.c_str(), quality, g.particles.size(), lowest, highest, scene.cloud.cloudBase,
                  scene.cloud.cloudTop, rhoMin, rhoMax, range.x, range.y);
      CHECK(lowest >= scene.cloud.cloudBase - 1e-2f);
      CHECK(highest <= scene.cloud.cloudTop + 1e-2f);
      CHECK(rhoMax <= range.y * 1.0001f);
      CHECK(rhoMin >= range.x * 0.9999f);
      CHECK(range.y <= 8.0f);  // the default tables' density axis ends at ρ = 8
    }
  }
}

TEST_CASE("cloudscape LOD: neighbouring particles turn the reference particle differently", "[cloudscape][lod]") {
  const CloudscapeScene scene = loadCloudscape(kDefaultCloudscape);
  const CpuGeneration g = generateCloudscapeAround(scene.cloud, qualityPreset("low"), viewOf(scene).camera.eye);
  std::map<std::tuple<int, int, int, int>, glm::quat> q;
  for (const GridParticle& p : g.particles) q[{p.ring, p.cellX, p.cellZ, p.layer}] = p.particle.noiseRotation;
  int pairs = 0, alike = 0;
  double meanAngle = 0;
  for (const auto& [key, a] : q) {
    const auto it = q.find({std::get<0>(key), std::get<1>(key) + 1, std::get<2>(key), std::get<3>(key)});
    if (it == q.end()) continue;
    const double angle = 2.0 * std::acos(std::min(1.0, std::abs(double(glm::dot(a, it->second)))));
    meanAngle += angle;
    alike += angle < 0.1;
    ++pairs;
  }
  meanAngle /= std::max(pairs, 1);
  std::printf("[cloudscape lod] %d neighbour pairs: mean relative rotation %.2f rad (independent uniform rotations: pi/2 + 2/pi = 2.14), "
              "%d within 0.1 rad\n", pairs, meanAngle, alike);
  REQUIRE(pairs > 1000);
  CHECK(meanAngle > 1.9);
  CHECK(meanAngle < 2.35);
  CHECK(alike < pairs / 1000 + 2);
}

TEST_CASE("cloudscape LOD: ring borders do not show over a slow camera move", "[cloudscape][lod]") {
  RenderFixture rig = RenderFixture::synthetic(DensityModel::Noise);
  Renderer& renderer = rig.renderer;
  const CloudscapeScene scene = loadCloudscape(kDefaultCloudscape);
  const QualityPreset q = qualityPreset("low");
  const GridParameters g = gridParameters(scene.cloud, q);
  RenderSettings s = settingsFor(viewOf(scene), 256, 144);
  const int frames = 3;
  std::vector<Image> images;
  std::vector<Camera> cameras;
  for (int f = 0; f < frames; ++f) {
    s.view.camera = cameraOnPath(viewOf(scene).camera, f, 60.0f, 0.0f);
    cameras.push_back(s.view.camera);
    images.push_back(renderer.renderCloudscape(scene.cloud, q, s));
  }
  // Pixels whose ray meets the middle of the layer inside a ring's fade span (border) or within
  // half a span of it on either side (elsewhere, at about the same distance).
  double sum[2] = {0, 0};
  long count[2] = {0, 0};
  const float mid = 0.5f * (scene.cloud.cloudBase + scene.cloud.cloudTop);
  for (int f = 0; f + 1 < frames; ++f) {
    const CameraFrame frame(cameras[static_cast<std::size_t>(f)], s.width, s.height);
    for (int y = 0; y < s.height; ++y)
      for (int x = 0; x < s.width; ++x) {
        const glm::vec3 dir = frame.rayDirection(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
        if (dir.y < 0.02f) continue;
        const glm::vec3 p = frame.eye() + dir * ((mid - frame.eye().y) / dir.y);
        const float d = std::max(std::abs(p.x - frame.eye().x), std::abs(p.z - frame.eye().z));
        int cls = -1;
        for (int r = 0; r + 1 < q.rings; ++r) {
          const glm::vec2 span = grid::cgFadeSpan(r, g.g0, g.g3);
          const float half = 0.5f * (span.y - span.x);
          if (d >= span.x && d <= span.y) cls = 0;
          else if (cls < 0 && ((d >= span.x - half && d < span.x) || (d > span.y && d <= span.y + half))) cls = 1;
        }
        if (cls < 0) continue;
        const std::size_t i = 4 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(s.width) + static_cast<std::size_t>(x));
        double diff = 0;
        for (int c = 0; c < 3; ++c)
          diff += std::abs(images[static_cast<std::size_t>(f + 1)].rgba[i + static_cast<std::size_t>(c)] -
                           images[static_cast<std::size_t>(f)].rgba[i + static_cast<std::size_t>(c)]);
        sum[cls] += diff;
        ++count[cls];
      }
  }
  REQUIRE(count[0] > 500);
  REQUIRE(count[1] > 500);
  const double border = sum[0] / double(count[0]), elsewhere = sum[1] / double(count[1]);
  std::printf("[cloudscape lod] frame difference: ring borders %.3e (%ld px), beside them %.3e (%ld px), ratio %.3f\n",
              border, count[0], elsewhere, count[1], border / elsewhere);
  CHECK(border <= 1.15 * elsewhere);
}

TEST_CASE("cloudscape dump: the dumped particles render like the cloudscape", "[cloudscape][lod][cli]") {
  TempDir tmp;
  writeSyntheticLutSet(tmp / "luts", DensityModel::Noise);
  const std::string dump = (tmp / "dump.json").string();
  const CliResult r = runCli("render --luts '" + (tmp / "luts").string() + "' --quality low --scene stratocumulus "
                             "--dump-particles '" + dump + "'");
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  const Scene dumped = readScene(dump);
  const CloudscapeScene scene = loadCloudscape("stratocumulus");
  const CpuGeneration around = generateCloudscapeAround(scene.cloud, qualityPreset("low"), viewOf(scene).camera.eye);
  REQUIRE(dumped.particles.size() == around.particles.size());
  // The dump holds more than the frustum: particles behind the camera too.
  const glm::vec3 fwd = viewOf(scene).camera.target - viewOf(scene).camera.eye;
  std::size_t behind = 0;
  for (const Particle& p : dumped.particles) behind += glm::dot(p.center - viewOf(scene).camera.eye, fwd) < 0.0f;
  CHECK(behind > 100);

  const io::LutSet luts = io::readLutSet(tmp / "luts");
  auto context = createHeadlessContext();
  Renderer renderer(*context, luts);
  RenderSettings s = settingsFor(resolveView(dumped, {}), 192, 108);
  s.blend = BlendMode::Volume;
  s.lighting = LightingModel::Seed;
  s.sunlight = SunlightModel::Particle;
  s.occlusion = true;  // the cloudscape's occlusion takes the particles out of view too, as the dump's does
  const Image a = renderer.renderCloudscape(scene.cloud, qualityPreset("low"), s);
  const Image b = renderer.render(dumped.particles, s);
  double diff = 0, mean = 0;
  for (std::size_t i = 0; i < a.rgba.size(); i += 4)
    for (std::size_t c = 0; c < 4; ++c) {
      diff += std::abs(a.rgba[i + c] - b.rgba[i + c]);
      mean += std::abs(a.rgba[i + c]);
    }
  std::printf("[cloudscape dump] %zu particles; render from the dump vs the preset: mean |difference| %.3e of mean %.3e\n",
              dumped.particles.size(), diff / double(a.rgba.size()), mean / double(a.rgba.size()));
  CHECK(mean > 0);
  CHECK(diff < 1e-3 * mean);
}
