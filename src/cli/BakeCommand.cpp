// `cloudlut bake`: computes the tables into a LUT directory (manifest.json + one file per table
// and format). Everything is validated before anything is computed or written; files are
// written under temporary names and renamed, the manifest last.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <fstream>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <unistd.h>

#include "bake/OpticalDepthBaker.h"
#include "bake/PhaseResolution.h"
#include "bake/ScatteringBaker.h"
#include "cli/Command.h"
#include "cli/Options.h"
#include "cli/SceneNeeds.h"
#include "cli/TtyProgress.h"
#include "core/Defaults.h"
#include "core/Errors.h"
#include "core/ReferenceParticle.h"
#include "io/LutIo.h"

namespace cloudlut::cli {
namespace {

namespace fs = std::filesystem;

struct BakePlan {
  fs::path out;
  std::set<std::string> tables;  // "optical-depth", "single", "multiple"
  bake::OpticalDepthSettings od;
  bake::ScatteringSettings sc;
  DensityModel model = DensityModel::Noise;
  std::uint64_t seed = 1;
  bool writeBin = true, writeExr = true;
  io::SampleType precision = io::SampleType::Half;
  int threads = 0;
  bool quiet = false;
};

std::set<std::string> parseTables(const std::string& text) {
  std::set<std::string> tables;
  std::size_t start = 0;
  while (start <= text.size()) {
    const auto pos = text.find(',', start);
    const std::string t = text.substr(start, pos == std::string::npos ? std::string::npos : pos - start);
    if (t == "all") {
      tables.insert({"optical-depth", "single", "multiple"});
    } else if (t == "optical-depth" || t == "single" || t == "multiple") {
      tables.insert(t);
    } else {
      throw UsageError("--tables: unknown table '" + t + "' (optical-depth, single, multiple, all)");
    }
    if (pos == std::string::npos) break;
    start = pos + 1;
  }
  return tables;
}

// Creates the output directory and proves it writable, or throws UsageError.
void prepareOutputDirectory(const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir)) throw UsageError("cannot create output directory '" + dir.string() + "'");
  if (access(dir.c_str(), W_OK) != 0) throw UsageError("output directory '" + dir.string() + "' is not writable");
}

void writeTable(const BakePlan& plan, const Table4D& table, io::SampleType type, nlohmann::json& entries) {
  nlohmann::json entry = io::describeTable(table, type);
  nlohmann::json files = nlohmann::json::object();
  if (plan.writeBin) {
    const std::string name = table.name() + ".bin";
    io::writeBinaryLut(table, type, plan.out / name);
    files["bin"] = name;
  }
  if (plan.writeExr) {
    const io::SampleType exrType = type == io::SampleType::U8 ? io::SampleType::Half : type;
    const std::string name = table.name() + ".exr";
    io::writeExrLut(table, exrType, plan.out / name);
    files["exr"] = name;
    if (exrType != type) entry["exr_sample_type"] = io::toString(exrType);
  }
  entry["files"] = files;
  entries[table.name()] = entry;
}

// Validates and fills the scattering settings; every bad value is a UsageError.
void configureScattering(BakePlan& plan, const cxxopts::ParseResult& args) {
  bake::ScatteringSettings& sc = plan.sc;
  sc.dims = parseDims(args["res-sc"].as<std::string>(), "res-sc");
  const std::vector<int> s = parseIntList(args["densities"].as<std::string>(), "densities");
  if (s.size() < 2) throw UsageError("--densities: at least two density slices are needed");
  for (std::size_t i = 2; i < s.size(); ++i)
    if (s[i] - s[i - 1] != s[1] - s[0] || s[1] <= s[0])
      throw UsageError("--densities: the slices must be increasing and evenly spaced in log2 rho");
  if (s[1] <= s[0]) throw UsageError("--densities: the slices must be increasing");
  if (s.front() < -20 || s.back() > 20) throw UsageError("--densities: log2 rho must lie in [-20, 20]");
  sc.sMin = s.front();
  sc.sMax = s.back();
  sc.dims[3] = static_cast<int>(s.size());
  sc.extinction = plan.od.extinction;
  sc.radius = plan.od.radius;

  const std::string phase = args["phase"].as<std::string>();
  const double g1 = args["g1"].as<double>(), gm = args["gm"].as<double>();
  if (phase == "cs" || phase == "hg") {
    if (!(std::fabs(g1) < 1.0) || !(std::fabs(gm) < 1.0)) throw UsageError("--g1 and --gm must lie strictly between -1 and 1");
    const int kind = phase == "cs" ? 2 : 1;
    sc.firstPhase = {kind, static_cast<float>(g1)};
    sc.laterPhase = {kind, static_cast<float>(gm)};
  } else if (phase == "jd") {
    const double d = args["droplet-um"].as<double>();
    if (!(d >= 5.0 && d <= 50.0)) throw UsageError("--droplet-um must lie in [5, 50] (the range of the Jendersie-d'Eon fit)");
    sc.firstPhase = sc.laterPhase = {3, static_cast<float>(d)};
  } else if (phase == "iso") {
    sc.firstPhase = sc.laterPhase = {0, 0.0f};
  } else {
    throw UsageError("--phase: expected cs, hg, jd or iso, got '" + phase + "'");
  }

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
  sc.single = plan.tables.count("single") > 0;
  sc.multiple = plan.tables.count("multiple") > 0;
}

// Phase function by name for messages: "cs g=0.7", "jd d=10 um", "iso".
std::string describePhase(const bake::PhaseSpec& p) {
  char buf[64];
  if (p.kind == 1 || p.kind == 2) std::snprintf(buf, sizeof buf, "%s g=%g", p.kind == 1 ? "hg" : "cs", p.param);
  else if (p.kind == 3) std::snprintf(buf, sizeof buf, "jd d=%g um", p.param);
  else std::snprintf(buf, sizeof buf, "iso");
  return buf;
}

// One warning line on stderr (printed even with --quiet: it is not progress) when a phase
// function is too sharp for a direction grid the bake convolves it on: the expected relative
// error in 1 − g (bake/PhaseResolution.h) and the resolution that would bring it under the
// tolerance (2%, see kPhaseResolutionTolerance).
void warnPhaseResolution(const bake::ScatteringSettings& sc) {
  constexpr double kTolerance = bake::kPhaseResolutionTolerance, kDeg = 180.0 / 3.14159265358979323846;
  const auto checks = bake::checkPhaseResolution(sc, kTolerance);
  if (checks.empty()) return;
  std::string line = "cloudlut bake: warning: direction grid too coarse for the phase function:";
  for (std::size_t i = 0; i < checks.size(); ++i) {
    const auto& c = checks[i];
    char buf[512];
    std::snprintf(buf, sizeof buf,
                  "%s %s phase %s (g=%.3f; forward peak %.4g sr^-1, half-width %.2f deg) on %s (spacing %.2f deg): "
                  "expected error %.1f%% in 1-g; spacing <= %.2f deg brings it under %.0f%% (%s)",
                  i ? ";" : "", c.which.c_str(), describePhase(c.phase).c_str(), c.estimate.asymmetry,
                  c.estimate.peakValue, c.estimate.peakHalfWidth * kDeg, c.grid.c_str(), c.spacing * kDeg,
                  100.0 * c.estimate.relativeError, c.neededSpacing * kDeg, 100.0 * kTolerance, c.advice.c_str());
    line += buf;
  }
  std::fprintf(stderr, "%s\n", line.c_str());
}

// What --for-scene skipped and saved against the default bake (64×32×64×32, 8 density slices).
void printSceneReport(const BakePlan& plan, const SceneNeeds& needs, const nlohmann::json& forScene,
                      const nlohmann::json& timings) {
  std::printf("for scene %s (%s", needs.source.c_str(), needs.kind.c_str());
  if (needs.particles) std::printf(", %zu particles", needs.particles);
  std::printf("): density scales %.4g to %.4g\n", needs.rhoMin, needs.rhoMax);
  double bytes = 0, defaultBytes = 0, seconds = 0, defaultSeconds = 0;
  const double sampleBytes = plan.precision == io::SampleType::Float ? 4 : 2;
  if (plan.tables.count("optical-depth")) {
    const auto& d = plan.od.dims;
    const double nodes = double(d[0]) * d[1] * d[2] * d[3], defaultNodes = 64.0 * 32 * 64 * 32;
    const double odBytes = plan.precision == io::SampleType::U8 ? 1 : sampleBytes;
    bytes += 2 * odBytes * nodes;
    defaultBytes += 2 * odBytes * defaultNodes;
    const double t = forScene.value("optical_depth_bake_s", 0.0);
    seconds += t;
    defaultSeconds += t * defaultNodes / nodes;  // the bake's time is proportional to its chords
    const double err = forScene.value("optical_depth_opacity_error_p95", 0.0), tol = forScene.value("tolerance", 0.0);
    std::printf("  optical depth: %dx%dx%dx%d (95th-percentile opacity error %.4f, tolerance %.4f%s)\n", d[0], d[1], d[2],
                d[3], err, tol, err > tol ? "; NOT met: the largest table a GL 3D texture holds" : "");
  }
  if (plan.tables.count("single") || plan.tables.count("multiple")) {
    const auto& d = plan.sc.dims;
    const int tables = int(plan.tables.count("single") + plan.tables.count("multiple"));
    bytes += tables * sampleBytes * double(d[0]) * d[1] * d[2] * d[3];
    const auto& dd = defaults::kScatteringDims;
    defaultBytes += tables * sampleBytes * double(dd[0]) * dd[1] * dd[2] * dd[3];
    const double t = timings.value("scattering_s", 0.0);
    seconds += t;
    defaultSeconds += t * dd[3] / d[3];  // each density slice costs about the same (the volume solve dominates)
    std::printf("  scattering: density slices log2 rho = %g..%g, %d per octave (the default: -4..3, 1 per octave)\n",
                plan.sc.sMin, plan.sc.sMax, forScene.value("scattering_slices_per_octave", 1));
    if (forScene.contains("single_scattering_error_p95")) {
      const double err = forScene.value("single_scattering_error_p95", 0.0), tol = forScene.value("tolerance", 0.0);
      std::printf("  scattering: %dx%dx%dx%d (95th-percentile single-scattering error %.4f at the slices, %.4f between "
                  "them; tolerance %.4f%s)\n",
                  d[0], d[1], d[2], d[3], forScene.value("single_scattering_error_p95_at_slices", 0.0), err, tol,
                  err > tol ? "; NOT met by the largest candidate" : "");
    }
  }
  std::printf("  saved: %.1f of %.1f MB per format (%.0f%%), about %.1f of %.1f s (estimated from this bake's rates)\n",
              (defaultBytes - bytes) / 1e6, defaultBytes / 1e6, 100.0 * (defaultBytes - bytes) / defaultBytes,
              defaultSeconds - seconds, defaultSeconds);
}

int runBake(int argc, char** argv) {
  cxxopts::Options options("cloudlut bake", "Compute look-up tables into a LUT directory.");
  options.add_options()
    ("out", "output directory", cxxopts::value<std::string>()->default_value("out/luts"))
    ("tables", "tables to bake: optical-depth, all (comma-separated)", cxxopts::value<std::string>()->default_value("all"))
    ("res-od", "optical-depth table dimensions phi_s,theta_s,phi_v,theta_v", cxxopts::value<std::string>()->default_value("64,32,64,32"))
    ("res-sc", "scattering table dimensions theta_s,phi_v,theta_v,density", cxxopts::value<std::string>()->default_value("32,64,16,8"))
    ("densities", "density slices as log2 rho: a range a:b or an evenly spaced list a,b,c (sets the 4th dimension)", cxxopts::value<std::string>()->default_value("-4:3"))
    ("phase", "phase function: cs (Cornette-Shanks), hg (Henyey-Greenstein), jd (Jendersie-d'Eon), iso", cxxopts::value<std::string>()->default_value("cs"))
    ("g1", "asymmetry g of the first scattering of sunlight (cs, hg)", cxxopts::value<double>()->default_value("0.9"))
    ("gm", "asymmetry g of every later scattering (cs, hg)", cxxopts::value<double>()->default_value("0.7"))
    ("droplet-um", "droplet diameter in micrometres for jd (one phase for every order)", cxxopts::value<double>()->default_value("10"))
    ("orders", "highest scattering order in the multiple table, or 'converged' for all of them", cxxopts::value<std::string>()->default_value("18"))
    ("method", "scattering method: fast (ours) or paper (the seed's algorithm, slow)", cxxopts::value<std::string>()->default_value("fast"))
    ("for-scene", "bake only what a scene needs (particle JSON, cloudscape preset or file): its density range, and the smallest optical-depth and scattering tables within --tolerance; overrides --densities, --res-od and --res-sc", cxxopts::value<std::string>())
    ("quality", "--for-scene with a cloudscape: grid preset low, medium or high", cxxopts::value<std::string>()->default_value("medium"))
    ("tolerance", "--for-scene: largest 95th-percentile interpolation error: absolute in opacity for the optical-depth table, relative in single scattering for the scattering tables", cxxopts::value<double>()->default_value("0.01"))
    ("density-model", "reference particle: noise, threshold, pyroclastic, radial, sphere", cxxopts::value<std::string>()->default_value("noise"))
    ("seed", "noise seed", cxxopts::value<std::uint64_t>()->default_value("1"))
    ("steps", "density samples per particle diameter along each chord (0 = the model's measured default)", cxxopts::value<int>()->default_value("0"))
    ("format", "file format: exr, bin, both", cxxopts::value<std::string>()->default_value("both"))
    ("precision", "sample type: float, half, u8 (u8: optical depth only; EXR stores it as half)", cxxopts::value<std::string>()->default_value("half"))
    ("extinction", "extinction coefficient beta, 1/m", cxxopts::value<double>()->default_value("0.07"))
    ("radius", "particle radius R, m", cxxopts::value<double>()->default_value("183.8"))
    ("threads", "worker threads (0 = all cores)", cxxopts::value<int>()->default_value("0"))
    ("quiet", "no progress output");
  cxxopts::ParseResult args;
  if (!parseOptions(options, argc, argv, args)) return kExitOk;

  BakePlan plan;
  plan.out = args["out"].as<std::string>();
  plan.tables = parseTables(args["tables"].as<std::string>());
  plan.od.dims = parseDims(args["res-od"].as<std::string>(), "res-od");
  const auto model = parseDensityModel(args["density-model"].as<std::string>());
  if (!model) throw UsageError("--density-model: unknown model '" + args["density-model"].as<std::string>() + "' (noise, threshold, pyroclastic, radial, sphere)");
  plan.model = *model;
  plan.seed = args["seed"].as<std::uint64_t>();
  plan.od.steps = args["steps"].as<int>();
  if (plan.od.steps < 0 || plan.od.steps > 65536) throw UsageError("--steps must be in [1, 65536] (or 0 for the default)");
  plan.od.extinction = requirePositive(args["extinction"].as<double>(), "extinction");
  plan.od.radius = requirePositive(args["radius"].as<double>(), "radius");
  const std::string format = args["format"].as<std::string>();
  if (format != "exr" && format != "bin" && format != "both") throw UsageError("--format: expected exr, bin or both, got '" + format + "'");
  plan.writeBin = format != "exr";
  plan.writeExr = format != "bin";
  const auto precision = io::parseSampleType(args["precision"].as<std::string>());
  if (!precision) throw UsageError("--precision: expected float, half or u8, got '" + args["precision"].as<std::string>() + "'");
  plan.precision = *precision;
  if (plan.precision == io::SampleType::U8 && format == "exr")
    throw UsageError("--precision u8 cannot be stored in EXR; use --format bin or both");
  plan.threads = args["threads"].as<int>();
  plan.quiet = args.count("quiet") > 0;
  const bool scattering = plan.tables.count("single") || plan.tables.count("multiple");
  if (scattering) configureScattering(plan, args);

  std::optional<SceneNeeds> needs;
  if (args.count("for-scene")) {
    const double tolerance = args["tolerance"].as<double>();
    if (!(tolerance > 0.0 && tolerance < 1.0)) throw UsageError("--tolerance must lie in (0, 1)");
    needs = readSceneNeeds(args["for-scene"].as<std::string>(), args["quality"].as<std::string>());
    if (scattering) {
      const auto s = densitySlicesFor(*needs);
      plan.sc.sMin = s[0];
      plan.sc.sMax = s[1];
      plan.sc.dims[3] = s[1] - s[0] + 1;
    }
  }

  if (plan.tables.count("optical-depth")) checkTableFitsInMemory(plan.od.dims, 2);
  if (scattering) checkTableFitsInMemory(plan.sc.dims, 1, 2);
  const auto threadLimit = limitThreads(plan.threads);
  prepareOutputDirectory(plan.out);

  if (scattering) warnPhaseResolution(plan.sc);

  const ProgressFn progress = makeTtyProgress(plan.quiet);
  nlohmann::json entries = nlohmann::json::object();
  nlohmann::json timings = nlohmann::json::object();
  nlohmann::json forScene = nlohmann::json::object();
  if (plan.tables.count("optical-depth")) {
    const auto t0 = std::chrono::steady_clock::now();
    const ReferenceParticle particle(plan.model, plan.seed);
    if (needs) {
      reportProgress(progress, "choosing the resolution", 0.0);
      const int steps = plan.od.steps > 0 ? plan.od.steps : bake::defaultSteps(plan.model);
      const OpticalDepthChoice choice = chooseOpticalDepthResolution(
          particle, *needs, args["tolerance"].as<double>(), plan.od.extinction * plan.od.radius, steps);
      plan.od.dims = choice.dims;
      forScene["optical_depth_dims"] = choice.dims;
      forScene["optical_depth_opacity_error_p95"] = choice.errorP95;
    }
    const auto tBake = std::chrono::steady_clock::now();
    const Table4D table = bake::bakeOpticalDepth(particle, plan.od, progress);
    forScene["optical_depth_bake_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - tBake).count();
    timings["optical_depth_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    finishTtyProgress();
    writeTable(plan, table, plan.precision, entries);
  }
  nlohmann::json scatteringReport;
  if (scattering && needs) {
    reportProgress(progress, "choosing the scattering resolution", 0.0);
    const ScatteringChoice choice = chooseScatteringResolution(plan.sc, args["tolerance"].as<double>());
    plan.sc.dims = choice.dims;
    forScene["scattering_dims"] = plan.sc.dims;
    forScene["scattering_slices_per_octave"] = choice.slicesPerOctave;
    forScene["single_scattering_error_p95_at_slices"] = choice.angularErrorP95;
    forScene["single_scattering_error_p95"] = choice.errorP95;
  }
  if (scattering) {
    const auto t0 = std::chrono::steady_clock::now();
    bake::ScatteringResult result = bake::bakeScattering(plan.sc, progress);
    timings["scattering_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    finishTtyProgress();
    // Radiance is not confined to [0, 1]: 8-bit storage is for the optical-depth table only.
    const io::SampleType type = plan.precision == io::SampleType::U8 ? io::SampleType::Half : plan.precision;
    if (result.single) writeTable(plan, *result.single, type, entries);
    if (result.multiple) writeTable(plan, *result.multiple, type, entries);
    scatteringReport = result.report;
  }

  nlohmann::json manifest;
  manifest["format"] = "cloudlut-lut-set";
  manifest["version"] = io::kFormatVersion;
  manifest["generator"] = std::string("cloudlut ") + CLOUDLUT_VERSION;
  manifest["parameters"] = {{"extinction_per_m", plan.od.extinction}, {"radius_m", plan.od.radius},
                            {"density_model", toString(plan.model)}, {"seed", plan.seed}};
  if (scattering) {
    manifest["parameters"]["orders"] = plan.sc.orders > 0 ? nlohmann::json(plan.sc.orders) : nlohmann::json("converged");
    manifest["parameters"]["method"] = bake::toString(plan.sc.method);
    manifest["scattering_report"] = scatteringReport;
  }
  manifest["bake_seconds"] = timings;
  if (needs) {
    forScene["scene"] = needs->source;
    forScene["kind"] = needs->kind;
    forScene["density_range"] = {needs->rhoMin, needs->rhoMax};
    forScene["tolerance"] = args["tolerance"].as<double>();
    manifest["for_scene"] = forScene;
  }
  manifest["tables"] = entries;
  io::writeManifest(plan.out, manifest);
  if (needs && !plan.quiet) printSceneReport(plan, *needs, forScene, timings);
  if (!plan.quiet && isatty(STDERR_FILENO))
    std::fprintf(stderr, "wrote %zu table(s) to %s\n", entries.size(), plan.out.c_str());
  return kExitOk;
}

const CommandRegistration registration{"bake", "compute look-up tables into a LUT directory", runBake};

}  // namespace
}  // namespace cloudlut::cli
