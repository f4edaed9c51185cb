#pragma once
// The resolutions `cloudlut bake --for-scene` chooses: what a scene needs from the tables (the
// range of density scales its particles use), the density slices that cover it, and the
// smallest optical-depth and scattering tables whose interpolation errors stay within a
// tolerance, each measured against the quantity integrated directly.
#include <array>
#include <string>

#include "bake/ScatteringBaker.h"
#include "core/ReferenceParticle.h"

namespace cloudlut::bake {

struct SceneNeeds {
  std::string source;      // the scene file or cloudscape preset
  std::string kind;        // "particles" or "cloudscape"
  float rhoMin = 1, rhoMax = 1;  // density scales ρ the particles use
  std::size_t particles = 0;     // particle count (0 for a cloudscape: generated on the GPU)
};

// Reads a particle scene (a JSON file with "particles") or a cloudscape (preset name or file;
// `quality` = low, medium or high; a cloudscape's densities depend on the radius R, m, of the
// reference particle the tables are baked for). FileError / UsageError as the renderer reports them.
SceneNeeds readSceneNeeds(const std::string& fileOrPreset, const std::string& quality, double radiusMetres);

// Density slices s = log2 ρ (integers, evenly spaced by 1) that cover the scene: from one
// below the smallest ρ (single scattering is looked up at ρ times the ray's mean density) to
// the largest.
std::array<int, 2> densitySlicesFor(const SceneNeeds& needs);

struct OpticalDepthChoice {
  std::array<int, 4> dims;
  double errorP95;  // 95th percentile of |opacity error| at the scene's densities
};

// The smallest optical-depth table (from a ladder of resolutions up to the default 64×32×64×32,
// the largest whose folded depth every OpenGL implementation can load) whose
// interpolation error in opacity, 1 − e^{−τ}, at the scene's smallest and largest ρ, has its
// 95th percentile over 2000 random rays at or below `tolerance` (against the chord integrated
// directly). Falls back to the largest candidate, with its error, when none is enough.
OpticalDepthChoice chooseOpticalDepthResolution(const ReferenceParticle& particle, const SceneNeeds& needs,
                                                double tolerance, double unitOpticalRadius, int steps);

struct ScatteringChoice {
  std::array<int, 4> dims;       // θS, φv, θv nodes and density slices
  int slicesPerOctave;           // density slices per doubling of ρ
  double angularErrorP95;        // single-scattering relative error at the slices' own densities
  double errorP95;               // ... at densities between the slices too (what a scene sees)
};

// Scattering tables for the density range [settings.sMin, settings.sMax] (integers): the
// resolution whose single-scattering table has the 95th percentile of its relative
// interpolation error, over 1500 random rays as a camera sees them (rows carrying at least 1%
// of the mean), at or below `tolerance`, against L1 integrated directly along each ray. L1 is
// the sharpest of the two tables (the terminator); the multiple table takes the same
// resolution. Two steps: the smallest θS × φv × θv of the ladder 16×17×8 … 64×65×32 (φv folded
// onto [0, π]; the default 32×33×16 in the middle) within the tolerance at the slices'
// densities, then the fewest density slices per octave (1, 2, 4, 8; the default is 2) within
// it at densities log-uniform over the range, where the density interpolation (linear in ρ,
// densityAxisLinearInRho) adds to the angular error. Falls back to the largest candidate that a GL
// 3D texture holds (θv × slices ≤ 2048), with its error.
ScatteringChoice chooseScatteringResolution(const ScatteringSettings& settings, double tolerance);

}  // namespace cloudlut::bake
