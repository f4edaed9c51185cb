// `cloudlut render`: renders a particle scene (--particles FILE) or a procedural cloudscape
// (--scene PRESET|FILE; the default cloudscape without either) from a LUT directory with OpenGL
// 4.5 (headless, OSMesa) into a PNG (tone-mapped sRGB) or an EXR (linear radiance, alpha,
// distance); --frames N writes a numbered sequence along a slow camera path, --path FILE the frames
// of a recorded flight (scene/CameraPath.h); --dump-particles FILE writes a cloudscape's particles
// around the camera as a particle scene (scene/SceneWriter.h).
// Everything is validated before the tables are read or anything is rendered; the image is
// written through a temporary file and a rename.
#include <algorithm>
#include <cctype>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#include "cli/AtmosphereSetup.h"
#include "cli/Command.h"
#include "cli/Options.h"
#include "cli/RenderReport.h"
#include "cli/SceneOptions.h"
#include "core/Errors.h"
#include "io/LutIo.h"
#include "io/LutSetMedium.h"
#include "render/GlContext.h"
#include "render/ImageWriters.h"
#include "render/Renderer.h"
#include "scene/CameraPath.h"
#include "scene/Scene.h"
#include "scene/SceneWriter.h"

namespace cloudlut::cli {
namespace {

namespace fs = std::filesystem;

// OUT with "_NNNN" before the extension (frame sequences).
fs::path framePath(const fs::path& out, int frame) {
  char number[16];
  std::snprintf(number, sizeof number, "_%04d", frame);
  return out.parent_path() / (out.stem().string() + number + out.extension().string());
}

std::string lowerExtension(const fs::path& p) {
  std::string e = p.extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return e;
}

int runRender(int argc, char** argv) {
  cxxopts::Options options("cloudlut render",
                           "Render a particle scene (docs/SCENE_FORMAT.md) from a LUT directory with OpenGL 4.5.\n"
                           "Negative coordinates: write --eye=-1,2,3.");
  options.add_options()
    ("luts", "LUT directory (optical_depth, single_scattering, multiple_scattering)", cxxopts::value<std::string>())
    ("particles", "scene file (JSON, docs/SCENE_FORMAT.md)", cxxopts::value<std::string>())
    ("scene", "cloudscape preset (fair_weather_cumulus, stratocumulus, overcast, cumulus_congestus, towering_cumulus_sunset) or file; default fair_weather_cumulus", cxxopts::value<std::string>())
    ("quality", "cloudscape grid: low 104^2x4x2, medium 136^2x4x4, high 184^2x4x6", cxxopts::value<std::string>()->default_value("medium"))
    ("blend", "alpha or volume (default: volume for cloudscapes, alpha for --particles)", cxxopts::value<std::string>())
    ("downscale", "render the particles at 1/N resolution (1, 2, 4) and upscale (bilateral)", cxxopts::value<int>()->default_value("1"))
    ("frames", "write N frames OUT_0000.png ... along a slow forward move with a yaw", cxxopts::value<int>()->default_value("1"))
    ("path", "render the frames of a camera path (cloudlut view --record; docs/SCENE_FORMAT.md) as OUT_0000.png ...; --frames N: its first N", cxxopts::value<std::string>())
    ("speed", "--frames: metres per frame", cxxopts::value<double>()->default_value("40"))
    ("yaw", "--frames: degrees of yaw per frame", cxxopts::value<double>()->default_value("0.2"))
    ("fragments-per-pixel", "volume blending: node pool per particle-buffer pixel, the expected load that sizes the screen tiles", cxxopts::value<int>()->default_value("16"))
    ("tile-plan", "volume blending: plan the screen tiles from the expected load (expected) or from the fragments counted "
     "first (counted); auto counts first for cloudscapes, and for particle lists in the first frame and while frames "
     "overflow (unless their screen rectangles fit one tile), otherwise at a tile's overflow", cxxopts::value<std::string>()->default_value("auto"))
    ("volume-pool-mib", "volume blending: node pool budget of one screen tile in MiB (capped by the GL's storage block limit)", cxxopts::value<double>()->default_value("128"))
    ("no-occlusion", "constant sunlight (no light-space occlusion, no sun volume shadows)")
    ("shade-hidden", "volume blending: shade and store every fragment, also those behind segments that let through less than 1e-3 (the image within 1e-3 of their light; slower: for timing and checks)")
    ("box-proxies", "rasterise every particle as its bounding box, not the polygon around its outline seen from afar (the same image, more fragments: for timing)")
    ("diffusion", "cloud lighting: the share, 0 to 1, of the multiple light taken from a flux-limited diffusion solve over the particles, or over a box ahead of the camera in a wider scene or a cloudscape (docs/LIGHTING.md; 0: the tables' alone)", cxxopts::value<double>()->default_value("1"))
    ("diffusion-sweeps", "--diffusion: sweeps of the solve on each of its levels (but the finest, with cycles)", cxxopts::value<int>()->default_value("15"))
    ("diffusion-cycles", "--diffusion: correction cycles over the coarser levels in place of the finest level's sweeps (0: its sweeps)", cxxopts::value<int>()->default_value("3"))
    ("diffusion-warm-cycles", "--diffusion: when only the sun moved since the last frame, correction cycles from the last solve in place of a whole solve (0: a whole solve)", cxxopts::value<int>()->default_value("1"))
    ("diffusion-spacing", "--diffusion: node spacing, in units of the median particle radius (grown to hold the particles in 128 nodes per side; twice it in a box ahead of the camera)", cxxopts::value<double>()->default_value("0.5"))
    ("relight", "build the light-space volumes (sun, zenith, diffusion) every frame, also when the particles, sun and grids are the frame before's and its volumes would do (the same image, slower: for timing)")
    ("computed-chords", "the particle shader computes each particle's own chords in the sun volume again instead of reading the splat's (the same image, slower: for timing)")
    ("lighting", "lighting model: cloud (sunlight per shading point, multiple scattering of the cloud around each point, "
     "ambient from the sky above and the ground below through the cloud above and below each point) or seed (the "
     "seed paper's per-particle model)", cxxopts::value<std::string>()->default_value("cloud"))
    ("sunlight", "sunlight per particle (the seed's occlusion pass) or per shading point (the sun optical-depth volume); default: the lighting model's (seed: particle, cloud: volume)", cxxopts::value<std::string>())
    ("out", "output image: FILE.png (tone-mapped sRGB) or FILE.exr (linear RGB, A = 1 - transmittance, Z)", cxxopts::value<std::string>())
    ("width", "image width in pixels", cxxopts::value<long long>()->default_value("1280"))
    ("height", "image height in pixels", cxxopts::value<long long>()->default_value("720"))
    ("exposure", "PNG tone mapping: 1 - exp(-exposure * radiance) under a uniform sky; under the atmosphere the filmic curve's exposure (default: automatic, from the log-average luminance)", cxxopts::value<double>()->default_value("5"))
    ("sky-orders", "the atmosphere's scattering orders: 1 (single scattering only) or all", cxxopts::value<std::string>()->default_value("all"))
    ("no-light-shafts", "the atmosphere: no light shafts (the clouds' shadow left out of the air's in-scattered sunlight)")
    ("terms", "lighting terms: single, multiple, ambient, all (comma-separated)", cxxopts::value<std::string>()->default_value("all"))
    ("dump-particles", "cloudscapes: write every particle the grid generates around the camera (before frustum culling, level-of-detail fade in the density) as a particle scene FILE.json; --out optional", cxxopts::value<std::string>())
    ("quiet", "print nothing on success");
  addViewOptions(options);      // camera and light: cli/SceneOptions.h
  addSkyModelOption(options);
  addDetailNoiseOption(options);
  addRayMarchOptions(options);  // --method raymarch: cli/SceneOptions.h
  cxxopts::ParseResult args;
  if (!parseOptions(options, argc, argv, args)) return kExitOk;
  if (wantsRayMarch(args)) return runRayMarchRender(args);
  // The particle renderer takes the medium from the LUT set: the ray marcher's options do not apply.
  for (const char* option : {"density-model", "model-seed", "extinction", "radius", "phase", "g1", "gm", "droplet-um",
                             "steps", "adaptive", "shadow-steps", "octaves", "octave-abc"})
    if (args.count(option))
      throw UsageError(std::string("--") + option + " applies to --method raymarch only (--method particles takes "
                       "the medium and phase functions from the LUT set)");
  const bool particles = args.count("particles") > 0, dump = args.count("dump-particles") > 0;
  if (dump && particles) throw UsageError("--dump-particles applies to cloudscapes (--scene), not to --particles");
  if (!args.count("luts")) throw UsageError("missing --luts");
  if (!args.count("out") && !dump) throw UsageError("missing --out");

  const fs::path out = args.count("out") ? args["out"].as<std::string>() : std::string("unused.png");
  const std::string ext = lowerExtension(out);
  if (ext != ".png" && ext != ".exr")
    throw UsageError("--out: expected a .png or .exr file name, got '" + out.string() + "'");
  const long long width = args["width"].as<long long>(), height = args["height"].as<long long>();
  render::checkImageSize(width, height);
  const double exposure = requirePositive(args["exposure"].as<double>(), "exposure");

  render::RenderSettings settings;
  const std::string skyOrders = args["sky-orders"].as<std::string>();
  if (skyOrders != "1" && skyOrders != "all") throw UsageError("--sky-orders: expected 1 or all, got '" + skyOrders + "'");
  settings.skyOrders = skyOrders == "1" ? 1 : 0;
  settings.lightShafts = args.count("no-light-shafts") == 0;
  settings.width = static_cast<int>(width);
  settings.height = static_cast<int>(height);
  settings.terms = parseTermList(args["terms"].as<std::string>());
  settings.blend = args.count("blend") ? render::parseBlendMode(args["blend"].as<std::string>())
                                       : particles ? render::BlendMode::Alpha : render::BlendMode::Volume;
  settings.downscale = args["downscale"].as<int>();
  if (settings.downscale != 1 && settings.downscale != 2 && settings.downscale != 4)
    throw UsageError("--downscale: expected 1, 2 or 4");
  settings.fragmentsPerPixel = args["fragments-per-pixel"].as<int>();
  if (settings.fragmentsPerPixel < 1 || settings.fragmentsPerPixel > 1024)
    throw UsageError("--fragments-per-pixel: expected 1 to 1024");
  settings.tilePlan = render::parseVolumeTilePlan(args["tile-plan"].as<std::string>());
  const double poolMiB = args["volume-pool-mib"].as<double>();
  if (!std::isfinite(poolMiB) || poolMiB <= 0 || poolMiB > 1048576)
    throw UsageError("--volume-pool-mib: expected a positive number of MiB up to 1048576");
  settings.volumePoolBytes = static_cast<long double>(poolMiB) * 1048576.0L;
  settings.occlusion = args.count("no-occlusion") == 0;
  settings.outlinePolygons = args.count("box-proxies") == 0;
  settings.hiddenCulling = args.count("shade-hidden") == 0;
  settings.sunChordMap = args.count("computed-chords") == 0;
  settings.keepLighting = args.count("relight") == 0;
  const double diffusion = args["diffusion"].as<double>(), spacing = args["diffusion-spacing"].as<double>();
  if (!(diffusion >= 0.0 && diffusion <= 1.0)) throw UsageError("--diffusion: expected a share from 0 to 1");
  if (!(spacing >= 0.01 && spacing <= 10.0)) throw UsageError("--diffusion-spacing: expected 0.01 to 10 particle radii");
  settings.diffusionShare = static_cast<float>(diffusion);
  settings.diffusionSpacing = static_cast<float>(spacing);
  settings.diffusionSweeps = args["diffusion-sweeps"].as<int>();
  settings.diffusionCycles = args["diffusion-cycles"].as<int>();
  if (settings.diffusionCycles < 0 || settings.diffusionCycles > 1000)
    throw UsageError("--diffusion-cycles: expected 0 to 1000");
  settings.diffusionWarmCycles = args["diffusion-warm-cycles"].as<int>();
  if (settings.diffusionWarmCycles < 0 || settings.diffusionWarmCycles > 1000)
    throw UsageError("--diffusion-warm-cycles: expected 0 to 1000");
  if (settings.diffusionSweeps < 1 || settings.diffusionSweeps > 100000)
    throw UsageError("--diffusion-sweeps: expected 1 to 100000");
  settings.lighting = render::parseLighting(args["lighting"].as<std::string>());
  settings.sunlight = args.count("sunlight") ? render::parseSunlight(args["sunlight"].as<std::string>())
                                             : render::defaultSunlight(settings.lighting);
  int frames = args["frames"].as<int>();
  if (frames < 1 || frames > 100000) throw UsageError("--frames: expected 1 to 100000");
  const double speed = args["speed"].as<double>(), yaw = args["yaw"].as<double>();
  if (!std::isfinite(speed) || !std::isfinite(yaw)) throw UsageError("--speed/--yaw: expected finite numbers");
  const scene::QualityPreset quality = scene::qualityPreset(args["quality"].as<std::string>());

  const DrawnScene drawn = loadDrawnScene(args);
  const scene::Scene& scene = drawn.scene;
  const scene::CloudscapeScene& cloudscape = drawn.cloudscape;
  settings.view = drawn.view;
  settings.detail = drawn.detail;
  // --path FILE: the cameras and suns of a recorded flight (cloudlut view --record), one frame each.
  std::optional<scene::CameraPath> path;
  if (args.count("path")) {
    path = scene::readCameraPath(args["path"].as<std::string>());
    if (args["frames"].count() == 0) frames = static_cast<int>(path->frames.size());
    if (static_cast<std::size_t>(frames) > path->frames.size())
      throw UsageError("--frames: " + std::to_string(frames) + " frames asked, the path holds " +
                       std::to_string(path->frames.size()));
  }
  const io::LutSet luts = io::readLutSet(args["luts"].as<std::string>());
  const float radius = static_cast<float>(io::mediumFromLutSet(args["luts"].as<std::string>()).radius);
  const auto single = luts.tables.find("single_scattering");  // the renderer reports a missing table
  if (!particles && !args.count("quiet") && single != luts.tables.end()) {
    // One warning when the cloudscape needs denser particles than the scattering tables' axis
    // holds (thinner ones are faded particles, nearly transparent: clamping them is harmless).
    const glm::vec2 need = scene::cloudscapeDensityRange(cloudscape.cloud, quality, radius);
    const Axis& axis = single->second.table.axes()[3];
    if (std::log2(need.y) > axis.max + 1e-6)
      std::fprintf(stderr, "cloudlut render: warning: %s needs densities up to %.3g, the tables end at %.3g "
                   "(bake --for-scene %s); denser particles are shaded as %.3g\n", cloudscape.name.c_str(), need.y,
                   std::exp2(axis.max), cloudscape.name.c_str(), std::exp2(axis.max));
  }
  if (dump) {
    // The particles as drawn for the first frame's camera, with the tables' reference radius.
    const scene::CpuGeneration g =
        scene::generateCloudscapeAround(cloudscape.cloud, quality, settings.view.camera.eye, radius);
    std::vector<scene::Particle> list;
    for (const scene::GridParticle& p : g.particles) list.push_back(p.particle);
    const std::string file = args["dump-particles"].as<std::string>();
    io::writeFileAtomically(file, scene::sceneText(scene::sceneDocument(
                                      list, settings.view, "cloudscape " + cloudscape.name + ", quality " + quality.name, drawn.detail)));
    if (!args.count("quiet"))
      std::printf("wrote %s: %zu particles%s\n", file.c_str(), list.size(),
                  list.size() > scene::kMaxRenderParticles ? " (more than render --particles takes: use --quality low)" : "");
    if (!args.count("out")) return kExitOk;
  }

  const auto t0 = std::chrono::steady_clock::now();
  const std::unique_ptr<render::GlContext> context = render::createHeadlessContext();
  render::Renderer renderer(*context, luts);
  setUpAtmosphere(renderer, luts, settings.view.lighting);
  const double setupSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const scene::Camera start = settings.view.camera;
  for (int frame = 0; frame < frames; ++frame) {
    if (path) {
      settings.view.camera = path->frames[static_cast<std::size_t>(frame)].camera;
      settings.view.lighting.sunDirection = path->frames[static_cast<std::size_t>(frame)].sunDirection;
    } else {
      settings.view.camera = scene::cameraOnPath(start, frame, static_cast<float>(speed), static_cast<float>(yaw));
    }
    render::RenderStats stats;
    const render::Image image = particles ? renderer.render(scene.particles, settings, &stats)
                                          : renderer.renderCloudscape(cloudscape.cloud, quality, settings, &stats);
    if (const std::size_t bad = image.nonFiniteCount())
      throw std::runtime_error("the render holds " + std::to_string(bad) + " non-finite values (tables out of range?)");
    const fs::path file = frames > 1 || path ? framePath(out, frame) : out;
    if (ext == ".png" && settings.view.lighting.atmosphere)
      render::writeFilmicPng(image, file, args.count("exposure") ? std::optional<float>(static_cast<float>(exposure)) : std::nullopt);
    else if (ext == ".png") render::writePng(image, file, settings.view.lighting.skyColor, static_cast<float>(exposure));
    else render::writeExr(image, file);
    if (!args.count("quiet")) printFrameReport(file, image, stats, settings, setupSeconds, context->description());
  }
  return kExitOk;
}

const CommandRegistration registration{"render", "render a particle scene from the tables (OpenGL 4.5, headless)",
                                       runRender};

}  // namespace
}  // namespace cloudlut::cli
