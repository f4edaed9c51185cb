// `cloudlut bake`: computes the tables into a LUT directory (bake/LutSetBake.h: manifest.json
// + one file per table and format). Everything is validated before anything is computed or
// written; files are written under temporary names and renamed, the manifest last.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include <unistd.h>

#include "bake/LutSetBake.h"
#include "bake/PhaseResolution.h"
#include "cli/Command.h"
#include "cli/Options.h"
#include "cli/TtyProgress.h"
#include "core/Defaults.h"
#include "core/Errors.h"
#include "scene/AtmosphereJson.h"

namespace cloudlut::cli {
namespace {

namespace fs = std::filesystem;

std::set<std::string> parseTables(const std::string& text) {
  std::set<std::string> tables;
  std::size_t start = 0;
  while (start <= text.size()) {
    const auto pos = text.find(',', start);
    const std::string t = text.substr(start, pos == std::string::npos ? std::string::npos : pos - start);
    if (t == "all") {
      tables.insert({"optical-depth", "single", "multiple"});
    } else if (t == "optical-depth" || t == "single" || t == "multiple" || t == "atmosphere") {
      tables.insert(t);
    } else {
      throw UsageError("--tables: unknown table '" + t + "' (optical-depth, single, multiple, atmosphere, all)");
    }
    if (pos == std::string::npos) break;
    start = pos + 1;
  }
  return tables;
}

// Creates the output directory's parent (the new set is staged there and swapped in) and proves
// it writable, or throws UsageError.
void prepareOutputDirectory(const fs::path& dir) {
  std::error_code ec;
  fs::path normal = fs::absolute(dir, ec).lexically_normal();
  if (normal.filename().empty()) normal = normal.parent_path();  // "out/luts/"
  const fs::path parent = normal.parent_path();
  fs::create_directories(parent, ec);
  if (ec || !fs::is_directory(parent)) throw UsageError("--out: cannot create the output directory's parent '" + parent.string() + "'");
  if (access(parent.c_str(), W_OK) != 0) throw UsageError("--out: the output directory's parent '" + parent.string() + "' is not writable");
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) throw UsageError("--out: '" + dir.string() + "' is not a directory");
}

// "64,32,64,32" from a default.
std::string dimsText(const std::array<int, 4>& d) {
  return std::to_string(d[0]) + "," + std::to_string(d[1]) + "," + std::to_string(d[2]) + "," + std::to_string(d[3]);
}

// Validates and fills the scattering settings; every bad value is a UsageError.
void configureScattering(bake::ScatteringSettings& sc, const cxxopts::ParseResult& args) {
  sc.dims = parseDims(args["res-sc"].as<std::string>(), "res-sc");
  const std::string densities = args["densities"].as<std::string>();
  const std::vector<int> s = parseIntList(densities, "densities");
  if (s.size() < 2) throw UsageError("--densities: at least two density slices are needed");
  for (std::size_t i = 2; i < s.size(); ++i)
    if (s[i] - s[i - 1] != s[1] - s[0] || s[1] <= s[0])
      throw UsageError("--densities: the slices must be increasing and evenly spaced in log2 rho");
  if (s[1] <= s[0]) throw UsageError("--densities: the slices must be increasing");
  if (s.front() < -20 || s.back() > 20) throw UsageError("--densities: log2 rho must lie in [-20, 20]");
  sc.sMin = s.front();
  sc.sMax = s.back();
  sc.dims[3] = static_cast<int>(s.size());
  // a range a:b has --slices-per-octave slices per octave (a list sets every slice itself)
  const int perOctave = args["slices-per-octave"].as<int>();
  if (perOctave < 1 || perOctave > 64) throw UsageError("--slices-per-octave: expected 1 to 64, got " + std::to_string(perOctave));
  if (densities.find(':') != std::string::npos) sc.dims[3] = (s.back() - s.front()) * perOctave + 1;
  const PhasePair phases = parsePhaseOptions(args).value();  // --phase has a default
  sc.firstPhase = phases.first;
  sc.laterPhase = phases.later;

  const std::string orders = args["orders"].as<std::string>();
  if (orders == "converged") {
    sc.orders = 0;
  } else {
    const std::vector<int> n = parseIntList(orders, "orders");
    if (n.size() != 1 || n[0] < 2 || n[0] > 10000)
      throw UsageError("--orders: expected a number of orders in [2, 10000] or 'converged', got '" + orders + "'");
    sc.orders = n[0];
  }
  const std::string method = args["method"].as<std::string>();
  if (method == "fast") sc.method = bake::ScatteringMethod::Fast;
  else if (method == "paper") sc.method = bake::ScatteringMethod::Paper;
  else throw UsageError("--method: expected fast or paper, got '" + method + "'");
}

// The atmosphere's parameters from a JSON file: an object of the fields of a scene's "sky" (or a
// scene whose "sky" holds them). FileError naming the file and the field otherwise.
glsl::AtmosphereParameters readAtmosphereFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw FileError(path, "cannot be read");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw FileError(path, std::string("not valid JSON: ") + e.what());
  }
  if (j.is_object() && j.contains("sky")) return scene::atmosphereFromJson(j["sky"], path, "sky.");
  return scene::atmosphereFromJson(j, path, "");
}

int runBake(int argc, char** argv) {
  cxxopts::Options options("cloudlut bake", "Compute look-up tables into a LUT directory.");
  options.add_options()
    ("out", "output directory", cxxopts::value<std::string>()->default_value("out/luts"))
    ("tables", "tables to bake: optical-depth, single, multiple, atmosphere, all (= the cloud tables; comma-separated)", cxxopts::value<std::string>()->default_value("all"))
    ("res-od", "optical-depth table dimensions phi_s,theta_s,phi_v,theta_v", cxxopts::value<std::string>()->default_value(dimsText(defaults::kOpticalDepthDims)))
    ("res-sc", "scattering table dimensions theta_s,phi_v,theta_v,density", cxxopts::value<std::string>()->default_value(dimsText(defaults::kScatteringDims)))
    ("densities", "density slices as log2 rho: a range a:b or an evenly spaced list a,b,c (sets the 4th dimension)",
     cxxopts::value<std::string>()->default_value(std::to_string(defaults::kDensitySlopeMin) + ":" + std::to_string(defaults::kDensitySlopeMax)))
    ("slices-per-octave", "density slices per octave of a --densities range", cxxopts::value<int>()->default_value(std::to_string(defaults::kDensitySlicesPerOctave)))
    ("orders", "highest scattering order in the multiple table, or 'converged' for all of them", cxxopts::value<std::string>()->default_value(std::to_string(defaults::kScatteringOrders)))
    ("method", "scattering method: fast (ours) or paper (the seed's algorithm, slow)", cxxopts::value<std::string>()->default_value("fast"))
    ("for-scene", "bake only what a scene needs (particle JSON, cloudscape preset or file): its density range, and the smallest optical-depth and scattering tables within --tolerance; overrides --densities, --res-od and --res-sc", cxxopts::value<std::string>())
    ("quality", "--for-scene with a cloudscape: grid preset low, medium or high", cxxopts::value<std::string>()->default_value("medium"))
    ("tolerance", "--for-scene: largest 95th-percentile interpolation error: absolute in opacity for the optical-depth table, relative in single scattering for the scattering tables", cxxopts::value<double>()->default_value("0.01"))
    ("density-model", "reference particle: noise, threshold, pyroclastic, radial, sphere", cxxopts::value<std::string>()->default_value("noise"))
    ("seed", "noise seed", cxxopts::value<std::uint64_t>()->default_value("1"))
    ("steps", "density samples per particle diameter along each chord (0 = the model's measured default)", cxxopts::value<int>()->default_value("0"))
    ("format", "file format: exr, bin, both", cxxopts::value<std::string>()->default_value("both"))
    ("precision", "sample type: float, half, u8 (u8: optical depth only; EXR stores it as half)", cxxopts::value<std::string>()->default_value("half"))
    ("extinction", "extinction coefficient beta, 1/m", cxxopts::value<double>()->default_value(defaultText(defaults::kExtinctionPerMetre)))
    ("radius", "particle radius R, m", cxxopts::value<double>()->default_value(defaultText(defaults::kParticleRadiusMetres)))
    ("threads", "worker threads (0 = all cores)", cxxopts::value<int>()->default_value("0"))
    ("atmosphere", "--tables atmosphere: a JSON file of the atmosphere's parameters (a scene's \"sky\" object; docs/SCENE_FORMAT.md)", cxxopts::value<std::string>())
    ("quiet", "no progress output");
  addPhaseOptions(options, false);
  cxxopts::ParseResult args;
  if (!parseOptions(options, argc, argv, args)) return kExitOk;

  bake::LutSetPlan plan;
  plan.generator = std::string("cloudlut ") + CLOUDLUT_VERSION;
  plan.out = args["out"].as<std::string>();
  const std::set<std::string> tables = parseTables(args["tables"].as<std::string>());
  plan.opticalDepth = tables.count("optical-depth") > 0;
  plan.sc.single = tables.count("single") > 0;
  plan.sc.multiple = tables.count("multiple") > 0;
  plan.atmosphere = tables.count("atmosphere") > 0;
  if (args.count("atmosphere")) {
    if (!plan.atmosphere) throw UsageError("--atmosphere needs --tables atmosphere");
    plan.atmosphereParameters = readAtmosphereFile(args["atmosphere"].as<std::string>());
  }
  plan.od.dims = parseDims(args["res-od"].as<std::string>(), "res-od");
  const auto model = parseDensityModel(args["density-model"].as<std::string>());
  if (!model) throw UsageError("--density-model: unknown model '" + args["density-model"].as<std::string>() + "' (noise, threshold, pyroclastic, radial, sphere)");
  plan.model = *model;
  plan.seed = args["seed"].as<std::uint64_t>();
  plan.od.steps = args["steps"].as<int>();
  if (plan.od.steps < 0 || plan.od.steps > 65536) throw UsageError("--steps must be in [1, 65536] (or 0 for the default)");
  plan.od.extinction = plan.sc.extinction = args["extinction"].as<double>();
  plan.od.radius = plan.sc.radius = args["radius"].as<double>();
  checkExtinctionRadius(plan.od.extinction, plan.od.radius);
  const std::string format = args["format"].as<std::string>();
  if (format != "exr" && format != "bin" && format != "both") throw UsageError("--format: expected exr, bin or both, got '" + format + "'");
  plan.formats = {.bin = format != "exr", .exr = format != "bin"};
  const auto precision = io::parseSampleType(args["precision"].as<std::string>());
  if (!precision) throw UsageError("--precision: expected float, half or u8, got '" + args["precision"].as<std::string>() + "'");
  plan.precision = *precision;
  if (plan.precision == io::SampleType::U8 && format == "exr")
    throw UsageError("--precision u8 cannot be stored in EXR; use --format bin or both");
  const bool quiet = args.count("quiet") > 0;
  if (plan.scattering()) configureScattering(plan.sc, args);

  if (args.count("for-scene")) {
    plan.tolerance = args["tolerance"].as<double>();
    if (!(plan.tolerance > 0.0 && plan.tolerance < 1.0)) throw UsageError("--tolerance must lie in (0, 1)");
    plan.forScene = bake::readSceneNeeds(args["for-scene"].as<std::string>(), args["quality"].as<std::string>(),
                                           args["radius"].as<double>());
    if (plan.scattering()) {
      const auto s = bake::densitySlicesFor(*plan.forScene);
      plan.sc.sMin = s[0];
      plan.sc.sMax = s[1];
      plan.sc.dims[3] = s[1] - s[0] + 1;
    }
  }

  if (plan.opticalDepth) checkTableFitsInMemory(plan.od.dims, 2);
  if (plan.scattering()) checkTableFitsInMemory(plan.sc.dims, 1, 2);
  const auto threadLimit = limitThreads(args["threads"].as<int>());
  prepareOutputDirectory(plan.out);
  // printed even with --quiet: it is not progress
  if (plan.scattering())
    if (const std::string warning = bake::phaseResolutionWarning(plan.sc, "cloudlut bake"); !warning.empty())
      std::fprintf(stderr, "%s\n", warning.c_str());

  const nlohmann::json manifest = bake::bakeLutSet(plan, makeTtyProgress(quiet), finishTtyProgress);
  if (plan.forScene && !quiet) std::printf("%s", bake::forSceneSummary(plan, manifest).c_str());
  if (!quiet && isatty(STDERR_FILENO))
    std::fprintf(stderr, "wrote %zu table(s) to %s\n", manifest["tables"].size(), plan.out.c_str());
  return kExitOk;
}

const CommandRegistration registration{"bake", "compute look-up tables into a LUT directory", runBake};

}  // namespace
}  // namespace cloudlut::cli
