// `cloudlut info PATH`: what a LUT file or a LUT directory holds.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <string>

#include "bake/EnergyBalance.h"
#include "cli/Command.h"
#include "cli/Options.h"
#include "core/AngularClosure.h"
#include "core/Errors.h"
#include "io/LutIo.h"

namespace cloudlut::cli {
namespace {

namespace fs = std::filesystem;

nlohmann::json channelStatistics(const Table4D& table) {
  nlohmann::json stats = nlohmann::json::array();
  const std::size_t nodes = table.nodeCount();
  for (int c = 0; c < table.channelCount(); ++c) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo, sum = 0.0;
    std::size_t nonFinite = 0;
    for (std::size_t n = 0; n < nodes; ++n) {
      const double v = table.at(n, c);
      if (!std::isfinite(v)) { ++nonFinite; continue; }
      lo = std::min(lo, v);
      hi = std::max(hi, v);
      sum += v;
    }
    const std::size_t finite = nodes - nonFinite;
    stats.push_back({{"name", table.channels()[c].name},
                     {"meaning", table.channels()[c].meaning},
                     {"min", finite ? lo : 0.0},
                     {"max", finite ? hi : 0.0},
                     {"mean", finite ? sum / static_cast<double>(finite) : 0.0},
                     {"non_finite", nonFinite}});
  }
  return stats;
}

nlohmann::json describeLoaded(const io::LoadedTable& loaded) {
  nlohmann::json d = io::describeTable(loaded.table, loaded.sampleType);
  d["file"] = loaded.path.string();
  d["checksum_status"] = "ok";
  d["statistics"] = channelStatistics(loaded.table);
  return d;
}

std::string formatNumber(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
}

void printTable(const nlohmann::json& d) {
  std::printf("table %s\n", d.value("name", std::string("?")).c_str());
  std::printf("  file      %s (%s samples, checksum %s)\n", d["file"].get<std::string>().c_str(),
              d.value("sample_type", std::string("?")).c_str(), d["checksum_status"].get<std::string>().c_str());
  const auto& dims = d["dims"];
  std::printf("  dims      %d x %d x %d x %d\n", dims[0].get<int>(), dims[1].get<int>(), dims[2].get<int>(), dims[3].get<int>());
  int k = 0;
  for (const auto& a : d["axes"]) {
    const double warp = a.value("warp", 0.0);
    const std::string warpText = warp > 0.0 ? ", nodes concentrated about the middle (warp " + formatNumber(warp) + ")" : "";
    // version 3 layout flags (FORMAT.md section 1)
    const std::string layout = std::string(a.value("folded", false) ? ", folded (mirror-symmetric about its max)" : "") +
                               (a.value("linear_in_exp2", false) ? ", interpolated linearly in 2^value" : "");
    std::printf("  axis %d    %-8s [%g, %g] %s, %d nodes%s%s%s\n", k++, a.value("name", std::string()).c_str(),
                a.value("min", 0.0), a.value("max", 0.0), a.value("unit", std::string()).c_str(),
                a.value("size", 0), a.value("periodic", false) ? ", periodic" : "", warpText.c_str(), layout.c_str());
  }
  for (const auto& s : d["statistics"]) {
    std::printf("  channel   %-13s min %.6g  max %.6g  mean %.6g%s\n      %s\n", s["name"].get<std::string>().c_str(),
                s["min"].get<double>(), s["max"].get<double>(), s["mean"].get<double>(),
                s["non_finite"].get<std::size_t>() ? ("  NON-FINITE " + std::to_string(s["non_finite"].get<std::size_t>())).c_str() : "",
                s["meaning"].get<std::string>().c_str());
  }
  if (!d.contains("parameters")) return;
  nlohmann::json params = d["parameters"];
  // the angular closure's values in one line of their range (the record itself: info --json)
  if (params.is_object() && params.contains("angular_closure")) {
    std::string problem;
    if (const auto closure = angularClosureFromJson(params["angular_closure"], problem)) {
      const auto [lo, hi] = std::minmax_element(closure->values.begin(), closure->values.end());
      std::printf("  closure   angular closure of the own term: %d density nodes from log2 rho %g by %g, %d exit-direction bins, K %.3f to %.3f\n",
                  closure->densityNodes, closure->log2RhoFirst, closure->log2RhoStep, closure->muBins, *lo, *hi);
    }
    params.erase("angular_closure");
  }
  std::printf("  params    %s\n", params.dump().c_str());
}

// `info DIR --energy`: the energy balance of the scattering tables (bake/EnergyBalance.h).
int printEnergy(const io::LutSet& set, bool json) {
  const auto find = [&](const char* name) -> const Table4D* {
    const auto it = set.tables.find(name);
    return it == set.tables.end() ? nullptr : &it->second.table;
  };
  const Table4D* single = find("single_scattering");
  const Table4D* multiple = find("multiple_scattering");
  if (!single && !multiple) throw FileError(set.dir.string(), "no scattering tables to integrate");
  const bake::EnergyBalance balance = bake::computeEnergyBalance(single, multiple);
  if (json) {
    nlohmann::json j = balance.toJson();
    if (multiple) j["orders"] = multiple->parameters().value("orders", nlohmann::json());
    std::printf("%s\n", j.dump(2).c_str());
    return kExitOk;
  }
  const std::string orders = multiple ? multiple->parameters().value("orders", nlohmann::json("?")).dump() : "none";
  std::printf("energy balance of %s (multiple scattering orders: %s)\n", set.dir.c_str(), orders.c_str());
  std::printf("%10s %14s %12s %10s %10s %10s\n", "rho", "optical radius", "unscattered", "single", "multiple", "total");
  for (const bake::EnergySlice& e : balance.slices) {
    auto share = [](double v) { return v < 0 ? std::string("-") : std::to_string(v).substr(0, 6); };
    std::printf("%10.4g %14.4g %12s %10s %10s %10s\n", e.rho, e.sigma, share(e.unscattered).c_str(),
                share(e.single).c_str(), share(e.multiple).c_str(), share(e.total).c_str());
  }
  return kExitOk;
}

int runInfo(int argc, char** argv) {
  cxxopts::Options options("cloudlut info", "Describe a LUT file or a LUT directory.");
  options.add_options()("path", "LUT file or directory", cxxopts::value<std::string>())(
      "json", "print JSON for scripts")(
      "energy", "integrate the scattering tables: share of the incident power leaving unscattered, singly and multiply scattered, per density");
  options.parse_positional({"path"});
  options.positional_help("PATH");
  cxxopts::ParseResult args;
  if (!parseOptions(options, argc, argv, args)) return kExitOk;
  if (!args.count("path")) throw UsageError("missing PATH (a LUT file or directory)");
  const fs::path path = args["path"].as<std::string>();
  if (!fs::exists(path)) throw FileError(path.string(), "no such file or directory");

  nlohmann::json report;
  if (args.count("energy")) {
    if (!fs::is_directory(path)) throw UsageError("--energy needs a LUT directory with scattering tables");
    return printEnergy(io::readLutSet(path), args.count("json") > 0);
  }
  if (fs::is_directory(path)) {
    const io::LutSet set = io::readLutSet(path);
    report["directory"] = path.string();
    report["manifest"] = {{"format", set.manifest.value("format", std::string())},
                          {"version", set.manifest.value("version", 0)},
                          {"generator", set.manifest.value("generator", std::string())},
                          {"parameters", set.manifest.value("parameters", nlohmann::json::object())}};
    report["tables"] = nlohmann::json::array();
    for (const auto& [name, entry] : set.manifest["tables"].items()) {
      // Every file listed is read and verified, not only the one readLutSet preferred.
      const nlohmann::json files = entry.value("files", nlohmann::json::object());
      for (const auto& [kind, file] : files.items()) {
        report["tables"].push_back(describeLoaded(io::readLut(path / file.get<std::string>())));
      }
    }
  } else {
    report["tables"] = nlohmann::json::array({describeLoaded(io::readLut(path))});
  }

  if (args.count("json")) {
    std::printf("%s\n", report.dump(2).c_str());
  } else {
    if (report.contains("directory"))
      std::printf("LUT set %s (%s v%d, %s)\n", report["directory"].get<std::string>().c_str(),
                  report["manifest"]["format"].get<std::string>().c_str(),
                  report["manifest"]["version"].get<int>(),
                  report["manifest"]["generator"].get<std::string>().c_str());
    for (const auto& t : report["tables"]) printTable(t);
  }
  return kExitOk;
}

const CommandRegistration registration{"info", "describe a LUT file or directory", runInfo};

}  // namespace
}  // namespace cloudlut::cli
