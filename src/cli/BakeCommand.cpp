// `cloudlut bake`: computes the tables into a LUT directory (manifest.json + one file per table
// and format). Everything is validated before anything is computed or written; files are
// written under temporary names and renamed, the manifest last.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <unistd.h>

#include "bake/OpticalDepthBaker.h"
#include "cli/Command.h"
#include "cli/Options.h"
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
      tables.insert({"optical-depth"});
    } else if (t == "optical-depth") {
      tables.insert(t);
    } else {
      throw UsageError("--tables: unknown table '" + t + "' (optical-depth, all)");
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

int runBake(int argc, char** argv) {
  cxxopts::Options options("cloudlut bake", "Compute look-up tables into a LUT directory.");
  options.add_options()
    ("out", "output directory", cxxopts::value<std::string>()->default_value("out/luts"))
    ("tables", "tables to bake: optical-depth, all (comma-separated)", cxxopts::value<std::string>()->default_value("all"))
    ("res-od", "optical-depth table dimensions phi_s,theta_s,phi_v,theta_v", cxxopts::value<std::string>()->default_value("64,32,64,32"))
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

  if (plan.tables.count("optical-depth")) checkTableFitsInMemory(plan.od.dims, 2);
  const auto threadLimit = limitThreads(plan.threads);
  prepareOutputDirectory(plan.out);

  const ProgressFn progress = makeTtyProgress(plan.quiet);
  nlohmann::json entries = nlohmann::json::object();
  nlohmann::json timings = nlohmann::json::object();
  if (plan.tables.count("optical-depth")) {
    const auto t0 = std::chrono::steady_clock::now();
    const ReferenceParticle particle(plan.model, plan.seed);
    const Table4D table = bake::bakeOpticalDepth(particle, plan.od, progress);
    timings["optical_depth_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    finishTtyProgress();
    writeTable(plan, table, plan.precision, entries);
  }

  nlohmann::json manifest;
  manifest["format"] = "cloudlut-lut-set";
  manifest["version"] = 1;
  manifest["generator"] = std::string("cloudlut ") + CLOUDLUT_VERSION;
  manifest["parameters"] = {{"extinction_per_m", plan.od.extinction}, {"radius_m", plan.od.radius},
                            {"density_model", toString(plan.model)}, {"seed", plan.seed}};
  manifest["bake_seconds"] = timings;
  manifest["tables"] = entries;
  io::writeManifest(plan.out, manifest);
  if (!plan.quiet && isatty(STDERR_FILENO))
    std::fprintf(stderr, "wrote %zu table(s) to %s\n", entries.size(), plan.out.c_str());
  return kExitOk;
}

const CommandRegistration registration{"bake", "compute look-up tables into a LUT directory", runBake};

}  // namespace
}  // namespace cloudlut::cli
