// `cloudlut bench`: speed against accuracy, every figure measured in one run.
#include <cstdio>
#include <filesystem>
#include <set>
#include <sstream>
#include <string>

#include "bench/BenchSuites.h"
#include "cli/Command.h"
#include "cli/Options.h"
#include "cli/TtyProgress.h"
#include "core/Errors.h"

namespace cloudlut::cli {
namespace {

int runBench(int argc, char** argv) {
  cxxopts::Options options("cloudlut bench", "Measure speed and accuracy; write OUT/bench.csv.");
  options.add_options()
    ("out", "output directory", cxxopts::value<std::string>()->default_value("out/bench"))
    ("suite", "suites to run: optical-depth, scattering, tables, ground-truth, render, render-count (only its particle-count rows), atmosphere, atmosphere-frame (only its frame-cost rows), all", cxxopts::value<std::string>()->default_value("all"))
    ("quick", "reduced resolutions for a fast look")
    ("scenes", "ground-truth: only these bench scenes (comma-separated; default: all)", cxxopts::value<std::string>())
    ("threads", "worker threads (0 = all cores)", cxxopts::value<int>()->default_value("0"))
    ("quiet", "no progress output");
  cxxopts::ParseResult args;
  if (!parseOptions(options, argc, argv, args)) return kExitOk;
  const std::string suite = args["suite"].as<std::string>();
  const std::set<std::string> known{"optical-depth", "scattering", "tables", "ground-truth", "render", "render-count", "atmosphere", "atmosphere-frame", "all"};
  if (!known.count(suite)) throw UsageError("--suite: unknown suite '" + suite + "' (optical-depth, scattering, tables, ground-truth, render, render-count, atmosphere, atmosphere-frame, all)");
  const std::filesystem::path out = args["out"].as<std::string>();
  std::error_code ec;
  std::filesystem::create_directories(out, ec);
  if (ec || !std::filesystem::is_directory(out)) throw UsageError("cannot create output directory '" + out.string() + "'");

  bench::BenchOptions opts;
  opts.quick = args.count("quick") > 0;
  opts.threads = args["threads"].as<int>();
  if (args.count("scenes")) {
    std::stringstream list(args["scenes"].as<std::string>());
    for (std::string name; std::getline(list, name, ',');)
      if (!name.empty()) opts.scenes.push_back(name);
  }
  if (opts.threads < 0) throw UsageError("--threads must be 0 (all cores) or positive");
  opts.progress = makeTtyProgress(args.count("quiet") > 0);
  bench::BenchReport report;
  if (suite == "optical-depth" || suite == "all") bench::benchOpticalDepth(report, opts);
  if (suite == "scattering" || suite == "all") bench::benchScattering(report, opts, out);
  if (suite == "tables" || suite == "all") bench::benchTableLayout(report, opts);
  if (suite == "ground-truth" || suite == "all") bench::benchGroundTruth(report, opts, out);
  if (suite == "render" || suite == "all") bench::benchRender(report, opts);
  if (suite == "render-count") bench::benchRenderParticleCount(report, opts);
  if (suite == "atmosphere" || suite == "all") bench::benchAtmosphere(report, opts);
  if (suite == "atmosphere-frame") bench::benchAtmosphereFrame(report, opts);
  finishTtyProgress();
  report.writeCsv(out / "bench.csv");
  report.print();
  std::printf("\nwrote %s\n", (out / "bench.csv").c_str());
  return kExitOk;
}

const CommandRegistration registration{"bench", "measure speed against accuracy (CSV for the charts)", runBench};

}  // namespace
}  // namespace cloudlut::cli
