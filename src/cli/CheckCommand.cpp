// `cloudlut check DIR --golden DIR`: regression-checks LUT values against golden tables.
// A value v passes against its golden value g when |v - g| <= atol + rtol·|g| (NaN never
// passes). Exit 0 when every value of every golden table passes, 1 otherwise.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "cli/Command.h"
#include "cli/Options.h"
#include "core/Errors.h"
#include "io/LutIo.h"

namespace cloudlut::cli {
namespace {

struct BadCell {
  double excess;  // |v - g| - tolerance
  std::size_t node;
  int channel;
  float value, golden;
};

std::string describeNode(const Table4D& t, std::size_t node) {
  const auto d = t.dims();
  std::size_t rest = node;
  std::string s;
  for (int k = 0; k < 4; ++k) {
    const int i = static_cast<int>(rest % static_cast<std::size_t>(d[k]));
    rest /= static_cast<std::size_t>(d[k]);
    char buf[96];
    std::snprintf(buf, sizeof buf, "%s%s[%d]=%.5g", k ? " " : "", t.axes()[k].name.c_str(), i, t.axes()[k].value(i));
    s += buf;
  }
  return s;
}

int runCheck(int argc, char** argv) {
  cxxopts::Options options("cloudlut check", "Regression-check LUT values against golden tables.");
  options.add_options()
    ("dir", "LUT directory to check", cxxopts::value<std::string>())
    ("golden", "golden LUT directory", cxxopts::value<std::string>())
    ("rtol", "relative tolerance", cxxopts::value<double>()->default_value("1e-3"))
    ("atol", "absolute tolerance", cxxopts::value<double>()->default_value("1e-4"))
    ("worst", "how many of the worst cells to print", cxxopts::value<int>()->default_value("10"));
  options.parse_positional({"dir"});
  options.positional_help("DIR");
  cxxopts::ParseResult args;
  if (!parseOptions(options, argc, argv, args)) return kExitOk;
  if (!args.count("dir")) throw UsageError("missing DIR (the LUT directory to check)");
  if (!args.count("golden")) throw UsageError("missing --golden DIR");
  const double rtol = args["rtol"].as<double>(), atol = args["atol"].as<double>();
  if (!(rtol >= 0.0) || !(atol >= 0.0)) throw UsageError("--rtol and --atol must be non-negative");
  const int worst = args["worst"].as<int>();
  if (worst < 0) throw UsageError("--worst must be 0 or positive (how many of the worst cells to print)");
  const std::size_t worstCount = static_cast<std::size_t>(worst);

  const io::LutSet golden = io::readLutSet(args["golden"].as<std::string>());
  const io::LutSet actual = io::readLutSet(args["dir"].as<std::string>());
  bool allPass = true;
  for (const auto& [name, g] : golden.tables) {
    const auto it = actual.tables.find(name);
    if (it == actual.tables.end()) {
      std::printf("%s: missing (the golden set has it)\n", name.c_str());
      allPass = false;
      continue;
    }
    const Table4D& a = it->second.table;
    const Table4D& gt = g.table;
    if (a.dims() != gt.dims() || a.channelCount() != gt.channelCount()) {
      std::printf("%s: dimensions or channels differ from the golden table\n", name.c_str());
      allPass = false;
      continue;
    }
    std::vector<BadCell> bad;
    std::size_t outCount = 0;
    double maxAbs = 0.0;
    for (std::size_t n = 0; n < gt.nodeCount(); ++n)
      for (int c = 0; c < gt.channelCount(); ++c) {
        const float v = a.at(n, c), ref = gt.at(n, c);
        const double diff = std::fabs(static_cast<double>(v) - ref);
        const double tol = atol + rtol * std::fabs(static_cast<double>(ref));
        if (std::isfinite(diff)) maxAbs = std::max(maxAbs, diff);
        if (diff <= tol) continue;  // NaN fails here
        ++outCount;
        const double excess = std::isfinite(diff) ? diff - tol : 1e300;
        bad.push_back({excess, n, c, v, ref});
        if (bad.size() > std::max<std::size_t>(4096, 2 * worstCount)) {  // keep only the worst few in memory
          const std::size_t keep = std::min(bad.size(), worstCount);
          std::partial_sort(bad.begin(), bad.begin() + static_cast<std::ptrdiff_t>(keep), bad.end(),
                            [](const BadCell& x, const BadCell& y) { return x.excess > y.excess; });
          bad.resize(keep);
        }
      }
    const std::size_t total = gt.nodeCount() * static_cast<std::size_t>(gt.channelCount());
    if (outCount == 0) {
      std::printf("%s: ok, %zu values within tolerance (max |difference| %.3g)\n", name.c_str(), total, maxAbs);
      continue;
    }
    allPass = false;
    std::printf("%s: %zu of %zu values out of tolerance (rtol %g, atol %g); worst:\n", name.c_str(), outCount, total, rtol, atol);
    const std::size_t shown = std::min(bad.size(), worstCount);
    std::partial_sort(bad.begin(), bad.begin() + static_cast<std::ptrdiff_t>(shown), bad.end(),
                      [](const BadCell& x, const BadCell& y) { return x.excess > y.excess; });
    for (std::size_t i = 0; i < shown; ++i)
      std::printf("  %s channel %s: %.7g, golden %.7g\n", describeNode(gt, bad[i].node).c_str(),
                  gt.channels()[bad[i].channel].name.c_str(), bad[i].value, bad[i].golden);
  }
  return allPass ? kExitOk : kExitFailed;
}

const CommandRegistration registration{"check", "regression-check LUT values against golden tables", runCheck};

}  // namespace
}  // namespace cloudlut::cli
