#include "cli/SceneNeeds.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <vector>

#include <nlohmann/json.hpp>

#include "bake/OpticalDepthBaker.h"
#include "core/Errors.h"
#include "core/Glsl.h"
#include "core/TableLookup.h"
#include "render/Cloudscape.h"
#include "render/Scene.h"

namespace cloudlut::cli {

SceneNeeds readSceneNeeds(const std::string& fileOrPreset, const std::string& quality) {
  SceneNeeds needs;
  needs.source = fileOrPreset;
  bool particleScene = false;
  if (std::filesystem::is_regular_file(fileOrPreset)) {
    std::ifstream in(fileOrPreset);
    const nlohmann::json doc = nlohmann::json::parse(in, nullptr, false);
    if (doc.is_discarded()) throw FileError(fileOrPreset, "not valid JSON");
    particleScene = !render::isCloudscapeDocument(doc);
  }
  if (particleScene) {
    const render::Scene scene = render::readScene(fileOrPreset);
    if (scene.particles.empty()) throw FileError(fileOrPreset, "the scene has no particles: nothing to bake for");
    needs.kind = "particles";
    needs.particles = scene.particles.size();
    needs.rhoMin = needs.rhoMax = scene.particles.front().density;
    for (const auto& p : scene.particles) {
      needs.rhoMin = std::min(needs.rhoMin, p.density);
      needs.rhoMax = std::max(needs.rhoMax, p.density);
    }
  } else {
    const render::CloudscapeScene scene = render::loadCloudscape(fileOrPreset);
    const glm::vec2 range = render::cloudscapeDensityRange(scene.cloud, render::qualityPreset(quality));
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
    r.exact = bake::integrateChord(particle, r.S, r.v, steps).meanDensity;
  }
  // Up to the default 64×32×64×32: its folded depth, 64·32 = 2048, is the largest 3D texture
  // side OpenGL implementations must support.
  const std::array<std::array<int, 4>, 5> ladder{{{16, 8, 16, 8},
                                                  {24, 12, 24, 12},
                                                  {32, 16, 32, 16},
                                                  {48, 24, 48, 24},
                                                  {64, 32, 64, 32}}};
  OpticalDepthChoice choice{ladder.back(), 0.0, 0};
  for (const auto& dims : ladder) {
    ++choice.candidatesTried;
    bake::OpticalDepthSettings s;
    s.dims = dims;
    s.steps = steps;
    const Table4D table = bake::bakeOpticalDepth(particle, s);
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

}  // namespace cloudlut::cli
