#include "cli/SceneOptions.h"

#include <algorithm>
#include <cstdio>

#include "cli/Options.h"
#include "core/Defaults.h"
#include "core/Errors.h"
#include "io/LutSetMedium.h"
#include "render/Renderer.h"

namespace cloudlut::cli {

DrawnScene loadDrawnScene(const cxxopts::ParseResult& args) {
  DrawnScene d;
  d.particles = args.count("particles") > 0;
  if (d.particles && args.count("scene")) throw UsageError("give either --particles or --scene, not both");
  scene::ViewSettings overrides = parseViewOverrides(args);
  overrides.atmosphere = parseSkyModel(args);
  if (d.particles) {
    d.scene = scene::readScene(args["particles"].as<std::string>());
    scene::checkRenderParticleCount(d.scene.particles.size(), args["particles"].as<std::string>());
  } else {
    d.cloudscape = scene::loadCloudscape(args.count("scene") ? args["scene"].as<std::string>()
                                                              : std::string(scene::kDefaultCloudscape));
    d.scene.view = d.cloudscape.view;
    if (!d.scene.view.target && !overrides.target) d.scene.view.target = glm::vec3(0.0f, 1500.0f, -6000.0f);
    if (!d.scene.view.eye && !overrides.eye) d.scene.view.eye = glm::vec3(0.0f, 600.0f, 0.0f);
  }
  d.view = scene::resolveView(d.scene, overrides);
  // Under the atmosphere the sky's radiance and the ground's return are its own (SkyPass::
  // cloudLighting): options that set them would be silently dropped.
  for (const char* option : {"sky-color", "sky-below"})
    if (d.view.lighting.atmosphere && args.count(option))
      throw UsageError(std::string("--") + option + ": the sky is the atmosphere here, which sets it; add " +
                       "--sky-model uniform to light the clouds by a uniform sky");
  DetailNoise fallback = scene::defaultDetailNoise(d.scene.particles);
  if (!d.particles) fallback.scale = scene::kDefaultDetailScaleFraction * d.cloudscape.cloud.cellSize *
                                     d.cloudscape.cloud.particleSize.y;  // of the largest ring-0 particle
  d.detail = parseDetailNoise(args, d.particles ? d.scene.detail : d.cloudscape.detail, fallback);
  return d;
}

void addSkyModelOption(cxxopts::Options& options) {
  options.add_options()("sky-model", "the sky that lights the clouds: atmosphere (the sun colour is the sunlight above "
                        "it) or uniform (--sky-color, --sky-below) (default: the scene's; cloudscape presets: "
                        "atmosphere)", cxxopts::value<std::string>());
}

std::optional<bool> parseSkyModel(const cxxopts::ParseResult& args) {
  if (!args.count("sky-model")) return std::nullopt;
  const std::string model = args["sky-model"].as<std::string>();
  if (model != "atmosphere" && model != "uniform")
    throw UsageError("--sky-model: expected atmosphere or uniform, got '" + model + "'");
  return model == "atmosphere";
}

void requireUniformSky(const scene::View& view, const cxxopts::ParseResult& args, const std::string& sceneFile,
                       const char* method) {
  if (!view.lighting.atmosphere) return;
  if (args.count("sky-model"))
    throw UsageError(std::string("--sky-model atmosphere: the ") + method + " lights by a uniform sky only (--sky-model uniform)");
  throw UsageError(sceneFile + ": sky.model is \"atmosphere\", and the " + method +
                   " lights by a uniform sky only; add --sky-model uniform");
}

void addDetailNoiseOption(cxxopts::Options& options) {
  options.add_options()("detail-noise", "the density's detail noise: on (the scene's \"detail_noise\", else a "
                        "default) or off (default: the scene's; cloudscape presets have it)", cxxopts::value<std::string>());
}

DetailNoise parseDetailNoise(const cxxopts::ParseResult& args, const std::optional<DetailNoise>& fromScene,
                             const DetailNoise& fallback) {
  if (!args.count("detail-noise")) return fromScene.value_or(DetailNoise{});
  const std::string v = args["detail-noise"].as<std::string>();
  if (v == "off") return DetailNoise{};
  if (v == "on") return fromScene && fromScene->enabled() ? *fromScene : fallback;
  throw UsageError("--detail-noise: expected on or off, got '" + v + "'");
}

void addViewOptions(cxxopts::Options& options) {
  options.add_options()
    ("eye", "camera position x,y,z (overrides the scene)", cxxopts::value<std::string>())
    ("target", "point the camera looks at x,y,z (overrides the scene)", cxxopts::value<std::string>())
    ("up", "camera up vector x,y,z (overrides the scene; default 0,1,0)", cxxopts::value<std::string>())
    ("fov", "vertical field of view, degrees (overrides the scene; default 45)", cxxopts::value<double>())
    ("sun", "direction toward the sun x,y,z (overrides the scene)", cxxopts::value<std::string>())
    ("sun-color", "sun irradiance r,g,b (overrides the scene; default 1,1,1)", cxxopts::value<std::string>())
    ("sky-color", "sky radiance r,g,b (overrides the scene; 0,0,0 = no sky)", cxxopts::value<std::string>())
    ("sky-below", "radiance of the sky below the horizon (the ground's return) as a fraction of the sky colour; "
     "1 = a uniform sky (default; the atmosphere uses its ground albedo)", cxxopts::value<double>());
}

scene::ViewSettings parseViewOverrides(const cxxopts::ParseResult& args) {
  scene::ViewSettings o;
  if (args.count("eye")) o.eye = parseVec3Option(args["eye"].as<std::string>(), "eye", false);
  if (args.count("target")) o.target = parseVec3Option(args["target"].as<std::string>(), "target", false);
  if (args.count("up")) o.up = parseVec3Option(args["up"].as<std::string>(), "up", false);
  if (args.count("fov")) {
    const double fov = args["fov"].as<double>();
    if (!(fov > 0.0 && fov <= 179.0)) throw UsageError("--fov: expected degrees in (0, 179]");
    o.fovDeg = static_cast<float>(fov);
  }
  if (args.count("sun")) o.sunDirection = parseVec3Option(args["sun"].as<std::string>(), "sun", false);
  if (args.count("sun-color")) o.sunColor = parseVec3Option(args["sun-color"].as<std::string>(), "sun-color", true);
  if (args.count("sky-color")) o.skyColor = parseVec3Option(args["sky-color"].as<std::string>(), "sky-color", true);
  if (args.count("sky-below")) {
    const double below = args["sky-below"].as<double>();
    if (!(below >= 0.0 && below <= 1e3)) throw UsageError("--sky-below: expected a fraction of the sky in [0, 1000]");
    o.skyBelow = static_cast<float>(below);
  }
  if (o.up && !(glm::length(*o.up) > 0.0f)) throw UsageError("--up: must not be zero");
  return o;
}

void addMediumOptions(cxxopts::Options& options, bool withLuts) {
  if (withLuts)
    options.add_options()("luts", "LUT directory whose manifest gives the density model, seed, beta, R and phase functions",
                          cxxopts::value<std::string>());
  char extinction[96], radius[96];
  std::snprintf(extinction, sizeof extinction, "extinction coefficient beta, 1/m (default: the LUT set's, else %g)",
                defaults::kExtinctionPerMetre);
  std::snprintf(radius, sizeof radius, "reference particle radius R, m (default: the LUT set's, else %g)",
                defaults::kParticleRadiusMetres);
  options.add_options()
    ("density-model", "reference particle density: noise, threshold, pyroclastic, radial, sphere (default: the LUT set's, else noise)",
     cxxopts::value<std::string>())
    ("model-seed", "seed of the density model (default: the LUT set's, else 1)", cxxopts::value<unsigned long long>())
    ("extinction", extinction, cxxopts::value<double>())
    ("radius", radius, cxxopts::value<double>());
  addPhaseOptions(options, true);
}

Medium parseMedium(const cxxopts::ParseResult& args) {
  Medium medium = args.count("luts") ? io::mediumFromLutSet(args["luts"].as<std::string>()) : Medium{};
  if (args.count("density-model")) {
    const auto model = parseDensityModel(args["density-model"].as<std::string>());
    if (!model)
      throw UsageError("--density-model: unknown model '" + args["density-model"].as<std::string>() +
                       "' (noise, threshold, pyroclastic, radial, sphere)");
    medium.model = *model;
  }
  if (args.count("model-seed")) medium.seed = args["model-seed"].as<unsigned long long>();
  if (args.count("extinction")) medium.extinction = args["extinction"].as<double>();
  if (args.count("radius")) medium.radius = args["radius"].as<double>();
  checkExtinctionRadius(medium.extinction, medium.radius);
  if (const std::optional<PhasePair> phases = parsePhaseOptions(args)) {
    medium.first = phases->first;
    medium.later = phases->later;
  }
  return medium;
}

unsigned parseTermList(const std::string& text) {
  unsigned terms = 0;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = std::min(text.find(',', start), text.size());
    const std::string t = text.substr(start, end - start);
    if (t == "single") terms |= render::kTermSingle;
    else if (t == "multiple") terms |= render::kTermMultiple;
    else if (t == "ambient") terms |= render::kTermAmbient;
    else if (t == "all") terms |= render::kAllTerms;
    else throw UsageError("--terms: unknown term '" + t + "' (single, multiple, ambient, all)");
    start = end + 1;
  }
  return terms;
}

void addRayMarchOptions(cxxopts::Options& options) {
  options.add_options()
    ("method", "particles (the LUT renderer) or raymarch (the ray-marched baseline; --luts then only supplies "
               "the density model and phase functions)", cxxopts::value<std::string>()->default_value("particles"))
    ("steps", "raymarch: view-ray steps", cxxopts::value<int>()->default_value("64"))
    ("adaptive", "raymarch: skip empty space, spread the steps over the occupied length")
    ("shadow-steps", "raymarch: steps of each shadow ray toward the sun", cxxopts::value<int>()->default_value("6"))
    ("octaves", "raymarch: Wrenninge multiple-scattering octaves (1 = single scattering)", cxxopts::value<int>()->default_value("8"))
    ("octave-abc", "raymarch: per-octave attenuation a (extinction), b (contribution), c (anisotropy)",
     cxxopts::value<std::string>()->default_value("0.5,0.5,0.5"));
  addMediumOptions(options, false);
}

bool wantsRayMarch(const cxxopts::ParseResult& args) {
  const std::string m = args["method"].as<std::string>();
  if (m == "raymarch") return true;
  if (m == "particles") return false;
  throw UsageError("--method: unknown method '" + m + "' (particles, raymarch)");
}

}  // namespace cloudlut::cli
