#pragma once
// What a scene needs from the tables, for `cloudlut bake --for-scene`: the range of density
// scales its particles use, and the optical-depth resolution whose interpolation error stays
// below a tolerance.
#include <array>
#include <string>

#include "core/ReferenceParticle.h"

namespace cloudlut::cli {

struct SceneNeeds {
  std::string source;      // the scene file or cloudscape preset
  std::string kind;        // "particles" or "cloudscape"
  float rhoMin = 1, rhoMax = 1;  // density scales ρ the particles use
  std::size_t particles = 0;     // particle count (0 for a cloudscape: generated on the GPU)
};

// Reads a particle scene (a JSON file with "particles") or a cloudscape (preset name or file;
// `quality` = low, medium or high). FileError / UsageError as the renderer reports them.
SceneNeeds readSceneNeeds(const std::string& fileOrPreset, const std::string& quality);

// Density slices s = log2 ρ (integers, evenly spaced by 1) that cover the scene: from one
// below the smallest ρ (single scattering is looked up at ρ times the ray's mean density) to
// the largest.
std::array<int, 2> densitySlicesFor(const SceneNeeds& needs);

struct OpticalDepthChoice {
  std::array<int, 4> dims;
  double errorP95;  // 95th percentile of |opacity error| at the scene's densities
  int candidatesTried;
};

// The smallest optical-depth table (from a ladder of resolutions up to the default 64×32×64×32,
// the largest whose folded depth every OpenGL implementation can load) whose
// interpolation error in opacity, 1 − e^{−τ}, at the scene's smallest and largest ρ, has its
// 95th percentile over 2000 random rays at or below `tolerance` (against the chord integrated
// directly). Falls back to the largest candidate, with its error, when none is enough.
OpticalDepthChoice chooseOpticalDepthResolution(const ReferenceParticle& particle, const SceneNeeds& needs,
                                                double tolerance, double unitOpticalRadius, int steps);

}  // namespace cloudlut::cli
