#include "cli/SceneCli.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <chrono>
#include <cstdio>
#include <fstream>

#include <nlohmann/json.hpp>

#include "cli/Options.h"
#include "core/Errors.h"
#include "render/GlContext.h"
#include "render/ImageWriters.h"
#include "render/RayMarchRenderer.h"

namespace cloudlut::cli {

glm::vec3 parseVec3Option(const std::string& text, const std::string& option, bool colour) {
  const std::string expected = colour ? "three comma-separated non-negative numbers r,g,b"
                                      : "three comma-separated numbers x,y,z";
  glm::vec3 v(0.0f);
  std::size_t start = 0;
  for (int k = 0; k < 3; ++k) {
    const std::size_t end = k < 2 ? text.find(',', start) : text.size();
    if (end == std::string::npos) throw UsageError("--" + option + ": expected " + expected + ", got '" + text + "'");
    const std::string part = text.substr(start, end - start);
    double value = 0.0;
    const auto r = std::from_chars(part.data(), part.data() + part.size(), value);
    if (part.empty() || r.ec != std::errc() || r.ptr != part.data() + part.size() || !std::isfinite(value) ||
        std::abs(value) > 1e30 || (colour && value < 0.0))
      throw UsageError("--" + option + ": expected " + expected + ", got '" + text + "'");
    v[k] = static_cast<float>(value);
    start = end + 1;
  }
  return v;
}

void addViewOptions(cxxopts::Options& options) {
  options.add_options()
    ("eye", "camera position x,y,z (overrides the scene)", cxxopts::value<std::string>())
    ("target", "point the camera looks at x,y,z (overrides the scene)", cxxopts::value<std::string>())
    ("up", "camera up vector x,y,z (overrides the scene; default 0,1,0)", cxxopts::value<std::string>())
    ("fov", "vertical field of view, degrees (overrides the scene; default 45)", cxxopts::value<double>())
    ("sun", "direction toward the sun x,y,z (overrides the scene)", cxxopts::value<std::string>())
    ("sun-color", "sun irradiance r,g,b (overrides the scene; default 1,1,1)", cxxopts::value<std::string>())
    ("sky-color", "sky radiance r,g,b (overrides the scene; 0,0,0 = no sky)", cxxopts::value<std::string>());
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
  if (o.up && !(glm::length(*o.up) > 0.0f)) throw UsageError("--up: must not be zero");
  return o;
}

namespace {

reference::McPhase phaseFromJson(const nlohmann::json& j, const std::string& file, const std::string& field) {
  if (!j.is_object() || !j.contains("kind") || !j["kind"].is_number_integer() || !j.contains("param") ||
      !j["param"].is_number())
    throw FileError(file, field + ": expected {\"kind\": integer, \"param\": number}");
  const int kind = j["kind"].get<int>();
  if (kind < 0 || kind > 3) throw FileError(file, field + ": unknown phase kind " + std::to_string(kind));
  return {kind, j["param"].get<float>()};
}

}  // namespace

MediumSpec mediumFromLutSet(const std::string& dir) {
  const std::string file = (std::filesystem::path(dir) / "manifest.json").string();
  std::ifstream in(file);
  if (!in) throw FileError(file, "cannot open the LUT set's manifest");
  nlohmann::json m;
  try {
    m = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw FileError(file, std::string("not JSON (") + e.what() + ")");
  }
  MediumSpec spec;
  spec.source = file;
  try {
    const nlohmann::json& od = m.at("tables").at("optical_depth").at("parameters");
    const auto model = parseDensityModel(od.at("density_model").get<std::string>());
    if (!model) throw FileError(file, "optical_depth: unknown density_model");
    spec.model = *model;
    spec.seed = od.at("seed").get<std::uint64_t>();
    spec.extinction = od.at("extinction_per_m").get<double>();
    spec.radius = od.at("radius_m").get<double>();
  } catch (const nlohmann::json::exception&) {
    throw FileError(file, "tables.optical_depth.parameters: expected density_model, seed, extinction_per_m, radius_m");
  }
  if (!(spec.extinction > 0) || !(spec.radius > 0)) throw FileError(file, "optical_depth: extinction and radius must be positive");
  for (const char* table : {"single_scattering", "multiple_scattering"}) {
    if (!m["tables"].contains(table)) continue;
    const nlohmann::json& p = m["tables"][table].value("parameters", nlohmann::json::object());
    if (p.contains("first_phase")) spec.first = phaseFromJson(p["first_phase"], file, std::string(table) + ".first_phase");
    if (p.contains("later_phase")) spec.later = phaseFromJson(p["later_phase"], file, std::string(table) + ".later_phase");
  }
  return spec;
}

void addMediumOptions(cxxopts::Options& options, bool withLuts) {
  if (withLuts)
    options.add_options()("luts", "LUT directory whose manifest gives the density model, seed, beta, R and phase functions",
                          cxxopts::value<std::string>());
  options.add_options()
    ("density-model", "reference particle density: noise, threshold, pyroclastic, radial, sphere (default: the LUT set's, else noise)",
     cxxopts::value<std::string>())
    ("model-seed", "seed of the density model (default: the LUT set's, else 1)", cxxopts::value<unsigned long long>())
    ("extinction", "extinction coefficient beta, 1/m (default: the LUT set's, else 0.07)", cxxopts::value<double>())
    ("radius", "reference particle radius R, m (default: the LUT set's, else 183.8)", cxxopts::value<double>())
    ("phase", "phase functions: cs (Cornette-Shanks), hg (Henyey-Greenstein), jd (Jendersie-d'Eon), iso "
              "(default: the LUT set's, else cs with g1 0.9, gm 0.7)", cxxopts::value<std::string>())
    ("g1", "g of sunlight's first scattering (cs, hg)", cxxopts::value<double>()->default_value("0.9"))
    ("gm", "g of every later scattering (cs, hg)", cxxopts::value<double>()->default_value("0.7"))
    ("droplet-um", "droplet diameter in um (jd)", cxxopts::value<double>()->default_value("10"));
}

MediumSpec parseMedium(const cxxopts::ParseResult& args) {
  MediumSpec spec = args.count("luts") ? mediumFromLutSet(args["luts"].as<std::string>()) : MediumSpec{};
  if (args.count("density-model")) {
    const auto model = parseDensityModel(args["density-model"].as<std::string>());
    if (!model)
      throw UsageError("--density-model: unknown model '" + args["density-model"].as<std::string>() +
                       "' (noise, threshold, pyroclastic, radial, sphere)");
    spec.model = *model;
  }
  if (args.count("model-seed")) spec.seed = args["model-seed"].as<unsigned long long>();
  if (args.count("extinction")) spec.extinction = requirePositive(args["extinction"].as<double>(), "extinction");
  if (args.count("radius")) spec.radius = requirePositive(args["radius"].as<double>(), "radius");
  if (args.count("phase")) {
    const std::string phase = args["phase"].as<std::string>();
    const double g1 = args["g1"].as<double>(), gm = args["gm"].as<double>();
    if (phase == "cs" || phase == "hg") {
      if (!(g1 > -1.0 && g1 < 1.0) || !(gm > -1.0 && gm < 1.0)) throw UsageError("--g1 and --gm must lie in (-1, 1)");
      const int kind = phase == "cs" ? 2 : 1;
      spec.first = {kind, static_cast<float>(g1)};
      spec.later = {kind, static_cast<float>(gm)};
    } else if (phase == "jd") {
      const double d = args["droplet-um"].as<double>();
      if (!(d >= 5.0 && d <= 50.0)) throw UsageError("--droplet-um must lie in [5, 50] (the fit's range)");
      spec.first = spec.later = {3, static_cast<float>(d)};
    } else if (phase == "iso") {
      spec.first = spec.later = {0, 0.0f};
    } else {
      throw UsageError("--phase must be cs, hg, jd or iso");
    }
  }
  return spec;
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

int runRayMarchRender(const cxxopts::ParseResult& args) {
  for (const char* required : {"particles", "out"})
    if (!args.count(required)) throw UsageError(std::string("missing --") + required);
  const std::filesystem::path out = args["out"].as<std::string>();
  std::string ext = out.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext != ".png" && ext != ".exr") throw UsageError("--out: expected a .png or .exr file name, got '" + out.string() + "'");
  const long long width = args["width"].as<long long>(), height = args["height"].as<long long>();
  render::checkImageSize(width, height);
  const double exposure = requirePositive(args["exposure"].as<double>(), "exposure");

  render::RayMarchSettings s;
  s.width = static_cast<int>(width);
  s.height = static_cast<int>(height);
  s.terms = parseTermList(args["terms"].as<std::string>());
  s.steps = args["steps"].as<int>();
  s.adaptive = args.count("adaptive") > 0;
  s.shadowSteps = args["shadow-steps"].as<int>();
  s.octaves = args["octaves"].as<int>();
  const glm::vec3 abc = parseVec3Option(args["octave-abc"].as<std::string>(), "octave-abc", true);
  s.a = abc.x;
  s.b = abc.y;
  s.c = abc.z;
  const MediumSpec medium = parseMedium(args);
  s.first = {medium.first.kind, medium.first.param};
  s.later = {medium.later.kind, medium.later.param};
  s.unitOpticalRadius = static_cast<float>(medium.unitOpticalRadius());
  const scene::ViewSettings overrides = parseViewOverrides(args);
  const scene::Scene scene = scene::readScene(args["particles"].as<std::string>());
  s.view = scene::resolveView(scene, overrides);

  const auto t0 = std::chrono::steady_clock::now();
  const ReferenceParticle particle(medium.model, medium.seed);
  const std::unique_ptr<render::GlContext> context = render::createHeadlessContext();
  render::RayMarchRenderer marcher(*context, particle);
  const double setup = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  render::RenderStats stats;
  const render::Image image = marcher.render(scene.particles, s, &stats);
  if (const std::size_t bad = image.nonFiniteCount())
    throw std::runtime_error("the ray-marched image holds " + std::to_string(bad) + " non-finite values");
  if (ext == ".png") render::writePng(image, out, s.view.lighting.skyColor, static_cast<float>(exposure));
  else render::writeExr(image, out);
  if (!args.count("quiet"))
    std::printf("wrote %s: %dx%d, %zu particles, raymarch %d steps%s, render %.1f ms (setup %.1f ms, %s)\n", out.c_str(),
                image.width, image.height, scene.particles.size(), s.steps, s.adaptive ? " adaptive" : "",
                1e3 * stats.renderSeconds, 1e3 * setup, context->description().c_str());
  return kExitOk;
}

io::ExrImage renderReferenceScene(const std::vector<scene::Particle>& particles, const scene::View& view,
                                  const MediumSpec& medium, const reference::ScenePtSettings& settings, int width,
                                  int height, const ProgressFn& progress, ReferenceSceneStats* stats) {
  const ReferenceParticle model(medium.model, medium.seed);
  reference::SceneMedium m;
  m.model = &model;
  m.unitOpticalRadius = medium.unitOpticalRadius();
  for (const scene::Particle& p : particles)
    m.particles.push_back({glm::dvec3(p.center), glm::dmat3(p.toParticle()), static_cast<double>(p.density)});
  reference::SceneLight light;
  light.sunDirection = glm::normalize(glm::dvec3(view.lighting.sunDirection));
  reference::ScenePtSettings st = settings;
  st.first = medium.first;
  st.later = medium.later;
  const scene::CameraFrame camera(view.camera, width, height);
  const glm::dvec3 eye(camera.eye());
  const auto ray = [&](double px, double py, glm::dvec3& o, glm::dvec3& d) {
    o = eye;
    d = glm::dvec3(camera.rayDirection(static_cast<float>(px), static_cast<float>(py)));
  };
  const reference::ScenePtImage img = reference::renderScene(m, light, st, width, height, ray, progress);
  if (stats) {
    stats->seconds = img.seconds;
    stats->meanVertices = img.meanVertices;
  }
  io::ExrImage out(width, height);
  const char* rgb[3] = {"R", "G", "B"};
  const char* se[3] = {"stderr.R", "stderr.G", "stderr.B"};
  const glm::dvec3 sun(view.lighting.sunColor), sky(view.lighting.skyColor);
  for (std::size_t i = 0; i < img.pixels.size(); ++i) {
    const reference::RayEstimate& e = img.pixels[i];
    for (int c = 0; c < 3; ++c) {
      out.channel(rgb[c])[i] = static_cast<float>(sun[c] * (e.single + e.multiple) + sky[c] * e.sky);
      const double var = sun[c] * sun[c] * e.sunSe * e.sunSe + sky[c] * sky[c] * e.skySe * e.skySe +
                         2.0 * sun[c] * sky[c] * e.sunSkyCov;
      out.channel(se[c])[i] = static_cast<float>(std::sqrt(std::max(var, 0.0)));
    }
    out.channel("A")[i] = static_cast<float>(1.0 - e.transmittance);
    out.channel("stderr.A")[i] = static_cast<float>(e.transmittanceSe);
    out.channel("single")[i] = static_cast<float>(e.single);
    out.channel("multiple")[i] = static_cast<float>(e.multiple);
    out.channel("ambient")[i] = static_cast<float>(e.sky);
  }
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "{\"density_model\": \"%s\", \"seed\": %llu, \"unit_optical_radius\": %.9g, \"first_phase\": [%d, %.6g], "
                "\"later_phase\": [%d, %.6g], \"spp\": %d, \"rng_seed\": %llu, \"max_order\": %d, \"jitter\": %s}",
                toString(medium.model).c_str(), static_cast<unsigned long long>(medium.seed), medium.unitOpticalRadius(),
                st.first.kind, static_cast<double>(st.first.param), st.later.kind, static_cast<double>(st.later.param),
                st.samplesPerPixel, static_cast<unsigned long long>(st.seed), st.maxOrder, st.jitter ? "true" : "false");
  out.attributes["cloudlutReference"] = buf;
  return out;
}

}  // namespace cloudlut::cli
