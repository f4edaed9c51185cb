#pragma once
// The scene options of `cloudlut reference scene` and `cloudlut render` (both methods): the
// camera and sun (the same names and formats for every verb), the medium a particle list
// describes (density model, β, R, phase functions; from a LUT set's manifest or from options),
// the lighting terms and the ray marcher's options.
#include <cxxopts.hpp>

#include "core/Medium.h"
#include "scene/Cloudscape.h"
#include "scene/Scene.h"

namespace cloudlut::cli {

// --eye, --target, --up, --fov, --sun, --sun-color, --sky-color, --sky-below.
void addViewOptions(cxxopts::Options& options);
scene::ViewSettings parseViewOverrides(const cxxopts::ParseResult& args);

// What `render` and `view` draw: the particles of --particles FILE, or the cloudscape of
// --scene PRESET|FILE (the default cloudscape without either), and the view resolved from the
// defaults, the file and the command line (a cloudscape's default camera: eye at 600 m looking
// toward a point 1.5 km up, 6 km ahead). UsageError for both options at once.
struct DrawnScene {
  bool particles = false;
  scene::Scene scene;
  scene::CloudscapeScene cloudscape;
  scene::View view;
  DetailNoise detail;  // the detail noise drawn (parseDetailNoise); amplitude 0 = off
};
DrawnScene loadDrawnScene(const cxxopts::ParseResult& args);

// --sky-model atmosphere|uniform: the sky that lights the drawn scene, over the scene's
// "sky"."model" (cloudscape presets: the atmosphere). loadDrawnScene takes it, and refuses
// --sky-color and --sky-below under the atmosphere, which sets both (UsageError naming them).
void addSkyModelOption(cxxopts::Options& options);
// The --sky-model value as "the sky is the atmosphere" (nullopt without the option); UsageError
// naming --sky-model for any value but atmosphere or uniform.
std::optional<bool> parseSkyModel(const cxxopts::ParseResult& args);
// For the methods that have only the uniform sky (the ray marcher, the path tracer): UsageError
// when `view` is lit by the atmosphere, naming where that came from (--sky-model, or the
// "sky"."model" of `sceneFile`) and --sky-model uniform, which lights it by a uniform sky.
void requireUniformSky(const scene::View& view, const cxxopts::ParseResult& args, const std::string& sceneFile,
                       const char* method);

// --detail-noise off|on: the density's detail noise (seed §5.4, core/DetailNoise.h).
void addDetailNoiseOption(cxxopts::Options& options);
// The detail noise of `scene` as the command line asks: without the option, the scene's
// "detail_noise" (none when absent); off: none; on: the scene's, else `fallback`.
DetailNoise parseDetailNoise(const cxxopts::ParseResult& args, const std::optional<DetailNoise>& fromScene,
                             const DetailNoise& fallback);

// --density-model, --model-seed, --extinction, --radius and the phase options (cli/Options.h),
// each overriding the LUT set's value (io/LutSetMedium.h) when --luts is given, else the
// defaults; `withLuts` also adds --luts.
void addMediumOptions(cxxopts::Options& options, bool withLuts);
Medium parseMedium(const cxxopts::ParseResult& args);

// "single,multiple,ambient|all" → render::Term bits; UsageError naming --terms.
unsigned parseTermList(const std::string& text);

// Adds --method (particles | raymarch) and the ray marcher's options to `cloudlut render`.
void addRayMarchOptions(cxxopts::Options& options);
// True when the parsed render arguments ask for --method raymarch (UsageError for an unknown
// method).
bool wantsRayMarch(const cxxopts::ParseResult& args);
// `cloudlut render --method raymarch ...`: the verb for that method (RenderRayMarch.cpp).
int runRayMarchRender(const cxxopts::ParseResult& args);

}  // namespace cloudlut::cli
