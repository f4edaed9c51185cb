#pragma once
// Command-line pieces shared by `cloudlut reference scene`, `cloudlut render --method raymarch`
// and the ground-truth bench: the camera/sun options (the same names and formats as
// `cloudlut render`), the medium a particle list describes (density model, β, R, phase
// functions; from a LUT set's manifest or from options), and the ray-march render.
#include <cstdint>
#include <string>

#include <cxxopts.hpp>

#include "core/Progress.h"
#include "core/ReferenceParticle.h"
#include "io/ExrImage.h"
#include "reference/ScenePathTracer.h"
#include "reference/SphereMonteCarlo.h"
#include "scene/Scene.h"

namespace cloudlut::cli {

// --eye, --target, --up, --fov, --sun, --sun-color, --sky-color.
void addViewOptions(cxxopts::Options& options);
scene::ViewSettings parseViewOverrides(const cxxopts::ParseResult& args);

// The medium: density model and seed of the reference particle, β and R, the phase functions.
struct MediumSpec {
  DensityModel model = DensityModel::Noise;
  std::uint64_t seed = 1;
  double extinction = 0.07;  // β, 1/m
  double radius = 183.8;     // R, m
  reference::McPhase first{2, 0.9f}, later{2, 0.7f};
  std::string source = "defaults";  // where it came from, for messages
  double unitOpticalRadius() const { return extinction * radius; }
};

// Reads DIR/manifest.json: tables.optical_depth.parameters (density_model, seed,
// extinction_per_m, radius_m) and the scattering tables' first_phase / later_phase. FileError
// naming the file when it is missing or malformed.
MediumSpec mediumFromLutSet(const std::string& dir);

// --density-model, --model-seed, --extinction, --radius, --phase, --g1, --gm, --droplet-um
// (each overrides the LUT set's value); `withLuts` also adds --luts.
void addMediumOptions(cxxopts::Options& options, bool withLuts);
MediumSpec parseMedium(const cxxopts::ParseResult& args);

// "x,y,z" → three finite numbers (non-negative when `colour`); UsageError naming the option.
glm::vec3 parseVec3Option(const std::string& text, const std::string& option, bool colour);

// "single,multiple,ambient|all" → render::Term bits; UsageError naming --terms.
unsigned parseTermList(const std::string& text);

// Adds --method (particles | raymarch) and the ray marcher's options to `cloudlut render`.
void addRayMarchOptions(cxxopts::Options& options);
// True when the parsed render arguments ask for --method raymarch (UsageError for an unknown
// method).
bool wantsRayMarch(const cxxopts::ParseResult& args);
// `cloudlut render --method raymarch ...`: the whole verb for that method.
int runRayMarchRender(const cxxopts::ParseResult& args);

// The path-traced ground truth of a scene as an EXR image: R, G, B (linear radiance, sun and
// sky colours applied), A = 1 − transmittance, and per-pixel standard errors "stderr.R",
// "stderr.G", "stderr.B", "stderr.A"; also the uncoloured components "single", "multiple"
// (per unit sun irradiance) and "ambient" (per unit sky radiance). `stats` (optional) receives
// the wall time and the mean path length.
struct ReferenceSceneStats {
  double seconds = 0;
  double meanVertices = 0;
};
io::ExrImage renderReferenceScene(const std::vector<scene::Particle>& particles, const scene::View& view,
                                  const MediumSpec& medium, const reference::ScenePtSettings& settings, int width,
                                  int height, const ProgressFn& progress = {}, ReferenceSceneStats* stats = nullptr);

}  // namespace cloudlut::cli
