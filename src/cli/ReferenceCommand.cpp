// `cloudlut reference sphere --csv IN`: Monte Carlo ground truth for the homogeneous unit
// sphere at the geometry of a query CSV (reference/SphereMonteCarlo.h).
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include <glm/geometric.hpp>

#include "cli/Command.h"
#include "cli/Options.h"
#include "io/LutIo.h"
#include "io/QueryCsv.h"
#include "cli/TtyProgress.h"
#include "core/Defaults.h"
#include "core/Errors.h"
#include "reference/ScenePathTracer.h"
#include "reference/SphereMonteCarlo.h"

namespace cloudlut::cli {

int runReferenceScene(int argc, char** argv);  // ReferenceSceneCommand.cpp

namespace {

std::string formatValue(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.7g", v);
  return buf;
}

int runReference(int argc, char** argv) {
  if (argc > 1 && std::string(argv[1]) == "scene") return runReferenceScene(argc - 1, argv + 1);
  cxxopts::Options options("cloudlut reference",
                           "Monte Carlo reference radiance for the homogeneous unit sphere.\n"
                           "  cloudlut reference sphere --csv IN [--out OUT] ...\n"
                           "  cloudlut reference scene --particles FILE.json ...  (a particle scene; see its --help)\n"
                           "Writes the input columns, then single,single_se,multiple18,multiple18_se,"
                           "multiple_all,multiple_all_se (radiance per unit sun irradiance, sr^-1; "
                           "single includes the first phase function).");
  options.add_options()
    ("target", "what to simulate: sphere", cxxopts::value<std::string>())
    ("csv", "input CSV: header, then sx,sy,sz,vx,vy,vz,lx,ly,lz,density", cxxopts::value<std::string>())
    ("out", "output CSV (default: standard output)", cxxopts::value<std::string>())
    ("paths", "paths per row", cxxopts::value<long long>()->default_value("100000"))
    ("seed", "random seed", cxxopts::value<unsigned long long>()->default_value("1"))
    ("threads", "worker threads (0 = all cores)", cxxopts::value<int>()->default_value("0"))
    ("extinction", "extinction coefficient beta, 1/m",
     cxxopts::value<double>()->default_value(defaultText(defaults::kExtinctionPerMetre)))
    ("radius", "particle radius R, m", cxxopts::value<double>()->default_value(defaultText(defaults::kParticleRadiusMetres)))
    ("quiet", "no progress bar");
  addPhaseOptions(options, false);
  options.parse_positional({"target"});
  options.positional_help("sphere");
  cxxopts::ParseResult args;
  if (!parseOptions(options, argc, argv, args)) return kExitOk;
  if (!args.count("target")) throw UsageError("missing target (only 'sphere' is supported)");
  if (args["target"].as<std::string>() != "sphere")
    throw UsageError("unknown target '" + args["target"].as<std::string>() + "' (only 'sphere' is supported)");
  if (!args.count("csv")) throw UsageError("missing --csv IN");

  const long long paths = args["paths"].as<long long>();
  if (paths < 2) throw UsageError("--paths must be at least 2");
  const double extinction = args["extinction"].as<double>(), radius = args["radius"].as<double>();
  checkExtinctionRadius(extinction, radius);
  reference::SphereMcSettings st;
  st.paths = paths;
  st.seed = args["seed"].as<unsigned long long>();
  const PhasePair phases = parsePhaseOptions(args).value();  // --phase has a default
  st.first = phases.first;
  st.later = phases.later;
  const auto threads = limitThreads(args["threads"].as<int>());

  const io::QueryCsv csv = io::readQueryCsv(args["csv"].as<std::string>());
  std::vector<reference::SphereMcQuery> queries;
  queries.reserve(csv.rows.size());
  for (const io::QueryRow& r : csv.rows) {
    if (glm::dot(r.S, r.v) >= 0.0f)
      throw FileError(args["csv"].as<std::string>(), "row '" + r.text + "': v must point into the sphere (v·S < 0)");
    const double tau = extinction * radius * static_cast<double>(r.density);
    if (!(tau <= reference::kMaxParticleOpticalRadius))  // paths of about tau^2 events each
      throw FileError(args["csv"].as<std::string>(), "row '" + r.text + "': density x extinction x radius = " +
                                                         std::to_string(tau) + ", more than the " +
                                                         std::to_string(static_cast<int>(reference::kMaxParticleOpticalRadius)) +
                                                         " the path tracer can follow");
    queries.push_back({glm::dvec3(r.S), glm::dvec3(r.v), glm::dvec3(r.l), tau});
  }
  const ProgressFn progress = makeTtyProgress(args.count("quiet") > 0);
  const auto est = reference::estimateSphereRadiance(queries, st, progress);
  finishTtyProgress();

  std::ostringstream out;
  out << csv.header << ",single,single_se,multiple18,multiple18_se,multiple_all,multiple_all_se\n";
  for (std::size_t i = 0; i < csv.rows.size(); ++i) {
    const auto& e = est[i];
    out << csv.rows[i].text << ',' << formatValue(e.single) << ',' << formatValue(e.singleSe) << ','
        << formatValue(e.multipleN) << ',' << formatValue(e.multipleNSe) << ','
        << formatValue(e.multipleAll) << ',' << formatValue(e.multipleAllSe) << '\n';
  }
  if (args.count("out")) {
    const std::string path = args["out"].as<std::string>();
    io::writeFileAtomically(path, out.str());
  } else {
    std::fwrite(out.str().data(), 1, out.str().size(), stdout);
  }
  return kExitOk;
}

const CommandRegistration registration("reference", "Monte Carlo reference: the homogeneous sphere, or a particle scene",
                                       runReference);

}  // namespace
}  // namespace cloudlut::cli
