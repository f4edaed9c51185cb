// `cloudlut query DIR --csv IN`: evaluates the tables at arbitrary geometry, with the
// renderer's interpolation (core/TableLookup.h).
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <glm/geometric.hpp>

#include "cli/Command.h"
#include "cli/Options.h"
#include "io/QueryCsv.h"
#include "core/Defaults.h"
#include "core/Errors.h"
#include "core/Phase.h"
#include "core/TableLookup.h"
#include "io/LutIo.h"

namespace cloudlut::cli {
namespace {

// The phase function a scattering table was baked with for sunlight's first scattering,
// as recorded in its parameters: {"first_phase": {"kind": K, "param": P}}.
float firstScatteringPhase(const Table4D& single, float mu) {
  return phaseValue(recordedPhase(single.parameters(), "first_phase", defaults::kFirstPhase), mu);
}

std::string formatValue(float v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.7g", static_cast<double>(v));
  return buf;
}

int runQuery(int argc, char** argv) {
  cxxopts::Options options("cloudlut query", "Evaluate the tables of a LUT directory at arbitrary geometry.");
  options.add_options()
    ("dir", "LUT directory", cxxopts::value<std::string>())
    ("csv", "input CSV: header, then sx,sy,sz,vx,vy,vz,lx,ly,lz,density", cxxopts::value<std::string>())
    ("out", "output CSV (default: standard output)", cxxopts::value<std::string>());
  options.parse_positional({"dir"});
  options.positional_help("DIR");
  cxxopts::ParseResult args;
  if (!parseOptions(options, argc, argv, args)) return kExitOk;
  if (!args.count("dir")) throw UsageError("missing DIR (the LUT directory)");
  if (!args.count("csv")) throw UsageError("missing --csv IN");

  const io::QueryCsv csv = io::readQueryCsv(args["csv"].as<std::string>());
  const io::LutSet set = io::readLutSet(args["dir"].as<std::string>());
  const auto find = [&](const char* name) -> const Table4D* {
    const auto it = set.tables.find(name);
    return it == set.tables.end() ? nullptr : &it->second.table;
  };
  const Table4D* od = find("optical_depth");
  const Table4D* single = find("single_scattering");
  const Table4D* multiple = find("multiple_scattering");

  std::ostringstream out;
  out << csv.header << ",optical_depth,transmittance,optical_radius,single,multiple\n";
  for (const io::QueryRow& row : csv.rows) {
    if (glm::dot(row.S, row.v) >= 0.0f)
      throw FileError(args["csv"].as<std::string>(), "row '" + row.text + "': v must point into the sphere (dot(S, v) < 0)");
    out << row.text;
    if (od) {
      const OpticalDepthSample s = lookupOpticalDepth(*od, row.S, row.v, row.density);
      out << ',' << formatValue(s.opticalDepth) << ',' << formatValue(s.transmittance);
    } else {
      out << ",,";
    }
    const Table4D* any = single ? single : multiple;
    if (any) out << ',' << formatValue(unitOpticalRadius(*any) * row.density); else out << ',';
    if (single) {
      const float mu = glm::dot(row.v, row.l);
      out << ',' << formatValue(firstScatteringPhase(*single, mu) * lookupScattering(*single, row.S, row.v, row.l, row.density));
    } else {
      out << ',';
    }
    if (multiple) out << ',' << formatValue(lookupScattering(*multiple, row.S, row.v, row.l, row.density));
    else out << ',';
    out << '\n';
  }
  if (args.count("out")) io::writeFileAtomically(args["out"].as<std::string>(), out.str());
  else std::fputs(out.str().c_str(), stdout);
  return kExitOk;
}

const CommandRegistration registration{"query", "evaluate the tables at arbitrary geometry", runQuery};

}  // namespace
}  // namespace cloudlut::cli
