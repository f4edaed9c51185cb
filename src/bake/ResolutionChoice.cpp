#include "bake/ResolutionChoice.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <vector>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "bake/OpticalDepthBaker.h"
#include "bake/SingleScattering.h"
#include "core/Defaults.h"
#include "core/Errors.h"
#include "core/Glsl.h"
#include "core/SphereRays.h"
#include "core/TableLookup.h"
#include "scene/Cloudscape.h"
#include "scene/Scene.h"

namespace cloudlut::bake {

SceneNeeds readSceneNeeds(const std::string& fileOrPreset, const std::string& quality, double radiusMetres) {
  SceneNeeds needs;
  needs.source = fileOrPreset;
  bool particleScene = false;
  if (std::filesystem::is_regular_file(fileOrPreset)) {
    std::ifstream in(fileOrPreset);
    const nlohmann::json doc = nlohmann::json::parse(in, nullptr, false);
    if (doc.is_discarded()) throw FileError(fileOrPreset, "not valid JSON");
    particleScene = !scene::isCloudscapeDocument(doc);
  }
  if (particleScene) {
    const scene::Scene scene = scene::readScene(fileOrPreset);
    if (scene.particles.empty()) throw FileError(fileOrPreset, "the scene has no particles: nothing to bake for");
    needs.kind = "particles";
    needs.particles = scene.particles.size();
    needs.rhoMin = needs.rhoMax = scene.particles.front().density;
    for (const auto& p : scene.particles) {
      needs.rhoMin = std::min(needs.rhoMin, p.density);
      needs.rhoMax = std::max(needs.rhoMax, p.density);
    }
  } else {
    const scene::CloudscapeScene scene = scene::loadCloudscape(fileOrPreset, "--for-scene");
    const glm::vec2 range = scene::cloudscapeDensityRange(scene.cloud, scene::qualityPreset(quality),
                                                               static_cast<float>(radiusMetres));
    needs.kind = "cloudscape";
    needs.rhoMin = range.x;
    needs.rhoMax = range.y;
  }
  if (!(needs.rhoMin > 0.0f) || !std::isfinite(needs.rhoMax))
    throw FileError(fileOrPreset, "the scene's density scales must be positive and finite");
  return needs;
}

std::array<int, 2> densitySlicesFor(const SceneNeeds& needs) {
  const int lo = static_cast<int>(std::floor(std::log2(needs.rhoMin))) - 1;
  int hi = static_cast<int>(std::ceil(std::log2(needs.rhoMax)));
  if (hi <= lo) hi = lo + 1;
  return {std::clamp(lo, -20, 19), std::clamp(hi, -19, 20)};
}

OpticalDepthChoice chooseOpticalDepthResolution(const ReferenceParticle& particle, const SceneNeeds& needs,
                                                double tolerance, double unitOpticalRadius, int steps) {
  // Random rays and their directly integrated mean density: the reference of every candidate.
  std::mt19937_64 rng(4242);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  struct Ray { glm::vec3 S, v; float exact; };
  std::vector<Ray> rays(2000);
  for (Ray& r : rays) {
    const float phi = 6.2831853f * u(rng), theta = std::acos(2.0f * u(rng) - 1.0f);
    r.S = glsl::sphericalPoint(phi, theta);
    const float thetaV = std::acos(std::sqrt(u(rng)));  // cosine-weighted: rays as a camera sees them
    r.v = glsl::frameDirection(glsl::tangentX(phi, theta), glsl::tangentY(phi), r.S, 6.2831853f * u(rng), thetaV);
    r.exact = integrateChord(particle, r.S, r.v, steps).meanDensity;
  }
  // Up to the default 64×32×64×32: its folded depth, 64·32 = 2048, is the largest 3D texture
  // side OpenGL implementations must support.
  const std::array<std::array<int, 4>, 5> ladder{
      {{16, 8, 16, 8}, {24, 12, 24, 12}, {32, 16, 32, 16}, {48, 24, 48, 24}, defaults::kOpticalDepthDims}};
  OpticalDepthChoice choice{ladder.back(), 0.0};
  for (const auto& dims : ladder) {
    OpticalDepthSettings s;
    s.dims = dims;
    s.steps = steps;
    const Table4D table = bakeOpticalDepth(particle, s);
    std::vector<double> errors;
    for (const float rho : {needs.rhoMin, needs.rhoMax})
      for (const Ray& r : rays) {
        const float L = glsl::chordLength(r.S, r.v);
        const float sampled = lookupOpticalDepth(table, r.S, r.v, 1.0f).meanDensity;
        const double k = rho * unitOpticalRadius * L;
        errors.push_back(std::fabs(std::exp(-k * sampled) - std::exp(-k * r.exact)));
      }
    std::sort(errors.begin(), errors.end());
    const double p95 = errors[static_cast<std::size_t>(0.95 * static_cast<double>(errors.size() - 1))];
    choice.dims = dims;
    choice.errorP95 = p95;
    if (p95 <= tolerance) break;
  }
  return choice;
}

ScatteringChoice chooseScatteringResolution(const ScatteringSettings& settings, double tolerance) {
  std::mt19937_64 rng(4343);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const auto unit = [&] {
    const double z = 2.0 * u(rng) - 1.0, p = 6.283185307179586 * u(rng), r = std::sqrt(1.0 - z * z);
    return glm::dvec3(r * std::cos(p), r * std::sin(p), z);
  };
  const int octaves = static_cast<int>(std::lround(settings.sMax - settings.sMin));
  struct Ray { glm::dvec3 S, v, l; double rhoBetween, rhoSlice, exactBetween, exactSlice; };
  std::vector<Ray> rays(1500);
  double meanBetween = 0.0, meanSlice = 0.0;
  const double sigma1 = settings.extinction * settings.radius;
  for (Ray& r : rays) {
    r.S = unit();
    r.l = unit();
    // v cosine-weighted about the inward normal: rays as a distant camera sees them
    const double u1 = u(rng), u2 = u(rng);
    r.v = cosineWeightedInward(r.S, u1, u2);
    const double s = settings.sMin + (settings.sMax - settings.sMin) * u(rng);
    r.rhoBetween = std::exp2(s);
    r.rhoSlice = std::exp2(std::round(s));
    r.exactBetween = singleScatteringL1(r.S, r.v, r.l, sigma1 * r.rhoBetween);
    r.exactSlice = singleScatteringL1(r.S, r.v, r.l, sigma1 * r.rhoSlice);
    meanBetween += r.exactBetween / static_cast<double>(rays.size());
    meanSlice += r.exactSlice / static_cast<double>(rays.size());
  }
  // One bake of a candidate's single table; the 95th percentile of its relative error at the
  // slice densities (first) and between them (second).
  const auto errorsOf = [&](const std::array<int, 4>& dims) {
    ScatteringSettings s = settings;
    s.dims = dims;
    s.single = true;
    s.multiple = false;
    const ScatteringResult r = bakeScattering(s);
    const auto p95 = [&](bool between) {
      std::vector<double> errors;
      for (const Ray& ray : rays) {
        const double exact = between ? ray.exactBetween : ray.exactSlice;
        if (exact < 0.01 * (between ? meanBetween : meanSlice)) continue;
        const double table = lookupScattering(*r.single, glm::vec3(ray.S), glm::vec3(ray.v), glm::vec3(ray.l),
                                              static_cast<float>(between ? ray.rhoBetween : ray.rhoSlice));
        errors.push_back(std::abs(table - exact) / exact);
      }
      std::sort(errors.begin(), errors.end());
      return errors.empty() ? 0.0 : errors[static_cast<std::size_t>(0.95 * static_cast<double>(errors.size() - 1))];
    };
    return std::array<double, 2>{p95(false), p95(true)};
  };
  ScatteringChoice choice{};
  const std::array<std::array<int, 3>, 5> ladder{{{16, 17, 8}, {24, 25, 12}, {32, 33, 16}, {48, 49, 24}, {64, 65, 32}}};
  for (const auto& d : ladder) {
    choice.dims = {d[0], d[1], d[2], octaves + 1};
    choice.slicesPerOctave = 1;
    const auto e = errorsOf(choice.dims);
    choice.angularErrorP95 = e[0];
    choice.errorP95 = e[1];
    if (choice.angularErrorP95 <= tolerance) break;
  }
  for (const int perOctave : {2, 4, 8}) {
    if (choice.errorP95 <= tolerance) break;
    const std::array<int, 4> dims{choice.dims[0], choice.dims[1], choice.dims[2], octaves * perOctave + 1};
    if (dims[2] * dims[3] > 2048) break;  // the folded depth of a GL 3D texture
    choice.dims = dims;
    choice.slicesPerOctave = perOctave;
    choice.errorP95 = errorsOf(dims)[1];
  }
  return choice;
}

}  // namespace cloudlut::bake
