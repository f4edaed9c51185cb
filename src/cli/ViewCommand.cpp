// `cloudlut view`: flies through a cloudscape (--scene PRESET|FILE, the default one without it)
// or a particle scene (--particles FILE) in a window, rendered by the same renderer as
// `cloudlut render`. The options are validated and the tables found before the window opens;
// the work is view/Viewer.h's.
#include <cmath>
#include <cstdio>
#include <string>

#include "cli/Command.h"
#include "cli/Options.h"
#include "cli/SceneOptions.h"
#include "core/Errors.h"
#include "render/RenderTypes.h"
#include "view/Viewer.h"
#include "view/ViewerControls.h"

namespace cloudlut::cli {
namespace {

namespace fs = std::filesystem;

fs::path requireDirectory(const std::string& text, const char* option) {
  const fs::path dir = text.empty() ? fs::path(".") : fs::path(text);
  if (!fs::is_directory(dir)) throw UsageError(std::string("--") + option + ": '" + text + "' is not a directory");
  return dir;
}

int runView(int argc, char** argv) {
  std::string epilog = "Controls:\n";
  for (const std::string& line : view::controlsHelp()) epilog += "  " + line + "\n";
  cxxopts::Options options("cloudlut view",
                           "Fly through a cloudscape in a window (OpenGL 4.5 core, the renderer of cloudlut render).\n"
                           "Negative coordinates: write --eye=-1,2,3.");
  options.custom_help("[OPTION...]\n\n" + epilog);
  options.add_options()
    ("luts", "LUT directory, or a directory of LUT sets (e.g. orders18/ and converged/; N switches)", cxxopts::value<std::string>())
    ("particles", "scene file (JSON, docs/SCENE_FORMAT.md)", cxxopts::value<std::string>())
    ("scene", "cloudscape preset (fair_weather_cumulus, stratocumulus, overcast, cumulus_congestus, towering_cumulus_sunset) or file; default fair_weather_cumulus", cxxopts::value<std::string>())
    ("quality", "first cloudscape grid preset: low, medium, high (keys 1 2 3)", cxxopts::value<std::string>()->default_value("low"))
    ("blend", "first blending: alpha or volume (key B; default: volume for cloudscapes, alpha for --particles)", cxxopts::value<std::string>())
    ("downscale", "first particle resolution 1/N: 1, 2, 4 (key G)", cxxopts::value<int>()->default_value("1"))
    ("width", "window width in pixels", cxxopts::value<int>()->default_value("480"))
    ("height", "window height in pixels", cxxopts::value<int>()->default_value("270"))
    ("exposure", "tone mapping: 1 - exp(-exposure * radiance)", cxxopts::value<double>()->default_value("5"))
    ("terms", "first lighting terms: single, multiple, ambient, all (keys Z X C)", cxxopts::value<std::string>()->default_value("all"))
    ("no-occlusion", "start with constant sunlight (key O)")
    ("screenshot-dir", "where F12 writes cloudlut_NNNN.png", cxxopts::value<std::string>()->default_value("."))
    ("record", "write the flight as a camera path on exit (render it with cloudlut render --path FILE)", cxxopts::value<std::string>());
  addViewOptions(options);  // camera and light: cli/SceneOptions.h
  addSkyModelOption(options);
  addDetailNoiseOption(options);
  cxxopts::ParseResult args;
  if (!parseOptions(options, argc, argv, args)) return kExitOk;
  if (!args.count("luts")) throw UsageError("missing --luts");

  view::ViewerOptions o;
  const int width = args["width"].as<int>(), height = args["height"].as<int>();
  if (width < 16 || height < 16 || width > 8192 || height > 8192)
    throw UsageError("--width/--height: expected 16 to 8192 pixels");
  o.settings.width = width;
  o.settings.height = height;
  o.exposure = static_cast<float>(requirePositive(args["exposure"].as<double>(), "exposure"));
  o.settings.terms = parseTermList(args["terms"].as<std::string>());
  o.settings.occlusion = args.count("no-occlusion") == 0;
  o.settings.downscale = args["downscale"].as<int>();
  if (o.settings.downscale != 1 && o.settings.downscale != 2 && o.settings.downscale != 4)
    throw UsageError("--downscale: expected 1, 2 or 4");
  o.quality = args["quality"].as<std::string>();
  (void)scene::qualityPreset(o.quality);  // UsageError for an unknown preset
  o.screenshotDir = requireDirectory(args["screenshot-dir"].as<std::string>(), "screenshot-dir");
  if (args.count("record")) {
    o.record = fs::path(args["record"].as<std::string>());
    requireDirectory(o.record->parent_path().string(), "record");
  }

  DrawnScene drawn = loadDrawnScene(args);
  o.particles = drawn.particles;
  o.scene = std::move(drawn.scene);
  o.cloudscape = std::move(drawn.cloudscape);
  o.settings.view = drawn.view;
  o.settings.detail = drawn.detail;
  o.settings.blend = args.count("blend") ? render::parseBlendMode(args["blend"].as<std::string>())
                                         : o.particles ? render::BlendMode::Alpha : render::BlendMode::Volume;
  o.lutSets = view::findLutSets(args["luts"].as<std::string>());
  return view::runViewer(o);
}

const CommandRegistration registration{"view", "fly through the cloudscape in a window (OpenGL 4.5, GLFW)", runView};

}  // namespace
}  // namespace cloudlut::cli
