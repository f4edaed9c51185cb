// `cloudlut reference sphere --csv IN`: Monte Carlo ground truth for the homogeneous unit
// sphere at the geometry of a query CSV (reference/SphereMonteCarlo.h).
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include <glm/geometric.hpp>

#include "cli/Command.h"
#include "cli/Options.h"
#include "cli/QueryCsv.h"
#include "cli/TtyProgress.h"
#include "core/Defaults.h"
#include "core/Errors.h"
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
    ("phase", "phase functions: cs (Cornette-Shanks), hg (Henyey-Greenstein), jd (Jendersie-d'Eon), iso",
     cxxopts::value<std::string>()->default_value("cs"))
    ("g1", "g of sunlight's first scattering (cs, hg)", cxxopts::value<double>()->default_value("0.9"))
    ("gm", "g of every later scattering (cs, hg)", cxxopts::value<double>()->default_value("0.7"))
    ("droplet-um", "droplet diameter in um (jd)", cxxopts::value<double>()->default_value("10"))
    ("extinction", "extinction coefficient beta, 1/m", cxxopts::value<double>()->default_value("0.07"))
    ("radius", "particle radius R, m", cxxopts::value<double>()->default_value("183.8"))
    ("quiet", "no progress bar");
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
  const double extinction = requirePositive(args["extinction"].as<double>(), "extinction");
  const double radius = requirePositive(args["radius"].as<double>(), "radius");
  reference::SphereMcSettings st;
  st.paths = paths;
  st.seed = args["seed"].as<unsigned long long>();
  const std::string phase = args["phase"].as<std::string>();
  const double g1 = args["g1"].as<double>(), gm = args["gm"].as<double>();
  if (phase == "cs" || phase == "hg") {
    if (!(g1 > -1.0 && g1 < 1.0) || !(gm > -1.0 && gm < 1.0))
      throw UsageError("--g1 and --gm must lie in (-1, 1)");
    const int kind = phase == "cs" ? 2 : 1;
    st.first = {kind, static_cast<float>(g1)};
    st.later = {kind, static_cast<float>(gm)};
  } else if (phase == "jd") {
    const double d = args["droplet-um"].as<double>();
    if (!(d >= 5.0 && d <= 50.0)) throw UsageError("--droplet-um must lie in [5, 50] (the fit's range)");
    st.first = st.later = {3, static_cast<float>(d)};
  } else if (phase == "iso") {
    st.first = st.later = {0, 0.0f};
  } else {
    throw UsageError("--phase must be cs, hg, jd or iso");
  }
  const auto threads = limitThreads(args["threads"].as<int>());

  const QueryCsv csv = readQueryCsv(args["csv"].as<std::string>());
  std::vector<reference::SphereMcQuery> queries;
  queries.reserve(csv.rows.size());
  for (const QueryRow& r : csv.rows) {
    if (glm::dot(r.S, r.v) >= 0.0f)
      throw FileError(args["csv"].as<std::string>(), "row '" + r.text + "': v must point into the sphere (v·S < 0)");
    queries.push_back({glm::dvec3(r.S), glm::dvec3(r.v), glm::dvec3(r.l),
                       extinction * radius * static_cast<double>(r.density)});
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
    std::ofstream f(path, std::ios::binary);
    if (!f) throw FileError(path, "cannot open for writing");
    f << out.str();
    if (!f) throw FileError(path, "write failed");
  } else {
    std::fwrite(out.str().data(), 1, out.str().size(), stdout);
  }
  return kExitOk;
}

const CommandRegistration registration("reference", "Monte Carlo reference: the homogeneous sphere, or a particle scene",
                                       runReference);

}  // namespace
}  // namespace cloudlut::cli
