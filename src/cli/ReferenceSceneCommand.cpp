// `cloudlut reference scene --particles FILE.json`: path-traced ground truth of a particle scene
// (reference/ScenePathTracer.h), written as a linear EXR with per-pixel standard errors.
// Dispatched from ReferenceCommand.cpp.
#include <cmath>
#include <cstdio>
#include <string>

#include "cli/Command.h"
#include "cli/Options.h"
#include "cli/SceneOptions.h"
#include "cli/TtyProgress.h"
#include "core/Errors.h"
#include "reference/ReferenceImage.h"
#include "reference/ScenePathTracer.h"
#include "render/Renderer.h"

namespace cloudlut::cli {

int runReferenceScene(int argc, char** argv) {
  cxxopts::Options options(
      "cloudlut reference scene",
      "Path-traced ground truth of a particle scene (docs/SCENE_FORMAT.md): delta tracking of the exact medium\n"
      "(overlapping particles whose densities add, each the reference particle's density model), next-event\n"
      "estimation to the sun with the first phase function, the later phase function for every continuation,\n"
      "an optional sky (uniform, or --sky-below F times as bright below the horizon as above it). Writes a linear\n"
      "EXR: R, G, B, A = 1 - transmittance, stderr.R/G/B/A (standard error of each pixel's mean), single, multiple\n"
      "(per unit sun irradiance) and ambient (per unit sky radiance above the horizon).\n"
      "Negative coordinates: write --eye=-1,2,3.");
  options.add_options()
    ("particles", "scene file (JSON, docs/SCENE_FORMAT.md)", cxxopts::value<std::string>())
    ("out", "output EXR", cxxopts::value<std::string>()->default_value("reference.exr"))
    ("width", "image width in pixels", cxxopts::value<long long>()->default_value("96"))
    ("height", "image height in pixels", cxxopts::value<long long>()->default_value("64"))
    ("spp", "paths per pixel", cxxopts::value<int>()->default_value("256"))
    ("seed", "random seed (the image is the same for any number of threads)",
     cxxopts::value<unsigned long long>()->default_value("1"))
    ("max-order", "stop paths after this many scattering events (0 = no limit)", cxxopts::value<int>()->default_value("0"))
    ("max-seconds", "give up (exit 1, nothing written) when the path tracing takes longer than this; 0 = no limit",
     cxxopts::value<double>()->default_value("0"))
    ("jitter", "sample each pixel's area instead of its centre (the renderers sample centres)")
    ("brute-force", "test every particle along every ray instead of the BVH's candidates (same image, slower)")
    ("threads", "worker threads (0 = all cores)", cxxopts::value<int>()->default_value("0"))
    ("quiet", "no progress bar, no summary");
  addViewOptions(options);
  addSkyModelOption(options);  // uniform only: the path tracer has no atmosphere
  addDetailNoiseOption(options);
  addMediumOptions(options, true);
  cxxopts::ParseResult args;
  if (!parseOptions(options, argc, argv, args)) return kExitOk;
  if (!args.count("particles")) throw UsageError("missing --particles FILE.json");
  const std::string out = args["out"].as<std::string>();
  if (out.size() < 5 || (out.substr(out.size() - 4) != ".exr" && out.substr(out.size() - 4) != ".EXR"))
    throw UsageError("--out: expected an .exr file name, got '" + out + "'");
  const long long width = args["width"].as<long long>(), height = args["height"].as<long long>();
  render::checkImageSize(width, height);
  reference::ScenePtSettings st;
  const int spp = args["spp"].as<int>();
  if (spp < 2 || spp > (1 << 24)) throw UsageError("--spp must lie in [2, 16777216] (two at least, for a standard error)");
  st.samplesPerPixel = spp;
  st.seed = args["seed"].as<unsigned long long>();
  st.maxOrder = args["max-order"].as<int>();
  if (st.maxOrder < 0) throw UsageError("--max-order must be 0 (no limit) or positive");
  st.jitter = args.count("jitter") > 0;
  st.bruteForce = args.count("brute-force") > 0;
  st.maxSeconds = args["max-seconds"].as<double>();
  if (!(st.maxSeconds >= 0.0) || !std::isfinite(st.maxSeconds)) throw UsageError("--max-seconds must be 0 (no limit) or positive");
  const int threadCount = args["threads"].as<int>();
  if (threadCount < 0) throw UsageError("--threads must be 0 (all cores) or positive");
  const auto threads = limitThreads(threadCount);
  const Medium medium = parseMedium(args);
  scene::ViewSettings overrides = parseViewOverrides(args);
  overrides.atmosphere = parseSkyModel(args);
  const scene::Scene scene = scene::readScene(args["particles"].as<std::string>());
  const scene::View view = scene::resolveView(scene, overrides);
  requireUniformSky(view, args, args["particles"].as<std::string>(), "path tracer");
  const DetailNoise detail = parseDetailNoise(args, scene.detail, scene::defaultDetailNoise(scene.particles));

  const bool quiet = args.count("quiet") > 0;
  reference::ReferenceSceneStats stats;
  io::ExrImage image;
  try {
    image = reference::renderReferenceScene(scene.particles, view, medium, st, static_cast<int>(width),
                                            static_cast<int>(height), makeTtyProgress(quiet), &stats, detail);
  } catch (const std::invalid_argument& e) {  // a particle too thick to trace
    throw FileError(args["particles"].as<std::string>(), e.what());
  } catch (const reference::WorkLimitExceeded& e) {
    throw FileError(out, std::string("not written: ") + e.what() + " (--max-seconds)");
  }
  finishTtyProgress();
  if (stats.truncatedPaths > 0)  // printed even with --quiet: the image is biased
    std::fprintf(stderr, "cloudlut reference scene: warning: %lld paths were cut at %d scattering events (the image "
                 "is too dark where they ran); lower the density or the extinction\n",
                 stats.truncatedPaths, reference::kMaxPathVertices);
  io::writeExrImage(image, out);
  if (!quiet) {
    double maxSe = 0, meanSe = 0;
    const auto& se = image.channel("stderr.G");
    for (float v : se) {
      maxSe = std::max(maxSe, static_cast<double>(v));
      meanSe += v;
    }
    meanSe /= static_cast<double>(se.size());
    std::printf("wrote %s: %lldx%lld, %zu particles, %d spp, model %s (%s), %.2f s, %.1f vertices per path, "
                "standard error of G mean %.3g max %.3g\n",
                out.c_str(), width, height, scene.particles.size(), spp, toString(medium.model).c_str(),
                medium.source.c_str(), stats.seconds, stats.meanVertices, meanSe, maxSe);
  }
  return kExitOk;
}

}  // namespace cloudlut::cli
