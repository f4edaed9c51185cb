#include "cli/Options.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include <tbb/global_control.h>

#include "core/Defaults.h"
#include "core/Errors.h"
#include "core/ParameterRules.h"

namespace cloudlut::cli {

namespace {

// cxxopts names the value it could not read, not its option. The shortest prefix of the arguments
// that fails the same way ends with that value ("--name value") or with "--name=value": the
// message names both. Falls back to cxxopts' own message.
std::string badValueMessage(cxxopts::Options& options, int argc, char** argv, const std::string& what) {
  for (int n = 2; n <= argc; ++n) {
    try {
      options.parse(n, argv);
    } catch (const cxxopts::exceptions::incorrect_argument_type&) {
      const std::string last = argv[n - 1];
      const std::size_t eq = last.find('=');
      if (last.rfind("--", 0) == 0 && eq != std::string::npos)
        return last.substr(0, eq) + ": '" + last.substr(eq + 1) + "' is not a valid value";
      if (n >= 3) return std::string(argv[n - 2]) + ": '" + last + "' is not a valid value";
      break;
    } catch (const cxxopts::exceptions::exception&) {
      // a prefix that cuts an option from its value; the next one holds it
    }
  }
  return what;
}

}  // namespace

bool parseOptions(cxxopts::Options& options, int argc, char** argv, cxxopts::ParseResult& out) {
  options.add_options("help")("h,help", "print this help");
  try {
    out = options.parse(argc, argv);
  } catch (const cxxopts::exceptions::incorrect_argument_type& e) {
    throw UsageError(badValueMessage(options, argc, argv, e.what()));
  } catch (const cxxopts::exceptions::exception& e) {
    throw UsageError(e.what());
  }
  if (out.count("help")) {
    std::printf("%s\n", options.help().c_str());
    return false;
  }
  if (!out.unmatched().empty()) throw UsageError("unexpected argument '" + out.unmatched().front() + "'");
  return true;
}

namespace {
int parseInt(const std::string& s, const std::string& option) {
  int v = 0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || r.ec != std::errc() || r.ptr != s.data() + s.size())
    throw UsageError("--" + option + ": '" + s + "' is not an integer");
  return v;
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const auto pos = s.find(sep, start);
    parts.push_back(s.substr(start, pos == std::string::npos ? std::string::npos : pos - start));
    if (pos == std::string::npos) break;
    start = pos + 1;
  }
  return parts;
}
}  // namespace

std::array<int, 4> parseDims(const std::string& text, const std::string& option) {
  const auto parts = split(text, ',');
  if (parts.size() != 4) throw UsageError("--" + option + ": expected four comma-separated dimensions, got '" + text + "'");
  std::array<int, 4> dims{};
  for (int i = 0; i < 4; ++i) {
    dims[i] = parseInt(parts[i], option);
    if (dims[i] < 2 || dims[i] > 65536)
      throw UsageError("--" + option + ": dimension " + std::to_string(dims[i]) + " is out of range [2, 65536]");
  }
  return dims;
}

std::vector<int> parseIntList(const std::string& text, const std::string& option) {
  std::vector<int> values;
  const auto colon = text.find(':');
  if (colon != std::string::npos) {
    const int a = parseInt(text.substr(0, colon), option), b = parseInt(text.substr(colon + 1), option);
    if (b < a) throw UsageError("--" + option + ": empty range '" + text + "'");
    for (int i = a; i <= b; ++i) values.push_back(i);
  } else {
    for (const auto& p : split(text, ',')) values.push_back(parseInt(p, option));
  }
  return values;
}

std::unique_ptr<tbb::global_control> limitThreads(int threads) {
  if (threads < 0) throw UsageError("--threads must be 0 (all cores) or positive");
  if (threads == 0) return nullptr;
  return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                               static_cast<std::size_t>(threads));
}

double requirePositive(double value, const std::string& option) {
  if (!(value > 0.0) || !std::isfinite(value))
    throw UsageError("--" + option + " must be a positive number");
  return value;
}

std::pair<float, float> parseRangeOption(const std::string& text, const std::string& option) {
  const auto fail = [&] {
    return UsageError("--" + option + ": expected lo,hi, two finite numbers with lo < hi within +-1e37, got '" + text + "'");
  };
  const auto comma = text.find(',');
  if (comma == std::string::npos) throw fail();
  double v[2] = {0, 0};
  const std::string parts[2] = {text.substr(0, comma), text.substr(comma + 1)};
  for (int k = 0; k < 2; ++k) {
    const auto r = std::from_chars(parts[k].data(), parts[k].data() + parts[k].size(), v[k]);
    if (parts[k].empty() || r.ec != std::errc() || r.ptr != parts[k].data() + parts[k].size() || !std::isfinite(v[k]) ||
        std::fabs(v[k]) > 1e37)
      throw fail();
  }
  const float lo = static_cast<float>(v[0]), hi = static_cast<float>(v[1]);
  if (!(hi > lo) || !std::isfinite(hi - lo)) throw fail();
  return {lo, hi};
}

void checkExtinctionRadius(double extinction, double radius) {
  if (const std::string p = rules::extinctionProblem(extinction); !p.empty()) throw UsageError("--extinction " + p);
  if (const std::string p = rules::radiusProblem(radius); !p.empty()) throw UsageError("--radius " + p);
  if (const std::string p = rules::opticalRadiusProblem(extinction, radius); !p.empty())
    throw UsageError("--extinction, --radius: " + p);
}

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

std::string defaultText(double value) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", value);
  return buf;
}

void addPhaseOptions(cxxopts::Options& options, bool defaultFromLuts) {
  const std::string kinds = "phase functions: cs (Cornette-Shanks), hg (Henyey-Greenstein), jd (Jendersie-d'Eon), iso";
  if (defaultFromLuts)
    options.add_options()("phase", kinds + " (default: the LUT set's, else cs with g1 " +
                                       defaultText(static_cast<double>(defaults::kFirstScatteringG)) + ", gm " +
                                       defaultText(static_cast<double>(defaults::kMultipleScatteringG)) + ")",
                          cxxopts::value<std::string>());
  else
    options.add_options()("phase", kinds, cxxopts::value<std::string>()->default_value("cs"));
  options.add_options()
    ("g1", "asymmetry g of the first scattering of sunlight (cs, hg)",
     cxxopts::value<double>()->default_value(defaultText(static_cast<double>(defaults::kFirstScatteringG))))
    ("gm", "asymmetry g of every later scattering (cs, hg)",
     cxxopts::value<double>()->default_value(defaultText(static_cast<double>(defaults::kMultipleScatteringG))))
    ("droplet-um", "droplet diameter in micrometres for jd (one phase for every order)",
     cxxopts::value<double>()->default_value(defaultText(static_cast<double>(defaults::kDropletDiameterUm))));
}

std::optional<PhasePair> parsePhaseOptions(const cxxopts::ParseResult& args) {
  const bool given = args.count("phase") > 0;
  const std::string phase = given || args["phase"].has_default() ? args["phase"].as<std::string>() : std::string();
  // --g1/--gm apply to cs and hg, --droplet-um to jd: one given for another phase is an error
  // (count() omits defaults, so only options the user typed are seen here).
  const bool gGiven = args.count("g1") > 0 || args.count("gm") > 0, dGiven = args.count("droplet-um") > 0;
  if (phase.empty()) {
    if (gGiven || dGiven)
      throw UsageError(std::string(gGiven ? "--g1/--gm" : "--droplet-um") +
                       " given without --phase (the LUT set's phase functions are used): add --phase " +
                       (gGiven ? "cs or hg" : "jd"));
    return std::nullopt;
  }
  const auto checked = [](const Phase& p, const char* option) {
    if (const std::string problem = rules::phaseProblem(p); !problem.empty())
      throw UsageError(std::string("--") + option + ": " + problem);
    return p;
  };
  if (phase == "cs" || phase == "hg") {
    if (dGiven) throw UsageError("--droplet-um applies to --phase jd only");
    const PhaseKind kind = phase == "cs" ? PhaseKind::CornetteShanks : PhaseKind::HenyeyGreenstein;
    const double g1 = args["g1"].as<double>(), gm = args["gm"].as<double>();
    return PhasePair{checked({kind, static_cast<float>(g1)}, "g1"), checked({kind, static_cast<float>(gm)}, "gm")};
  }
  if (phase == "jd") {
    if (gGiven) throw UsageError("--g1/--gm apply to --phase cs and hg only (jd takes --droplet-um)");
    const Phase jd = checked({PhaseKind::JendersieDeon, static_cast<float>(args["droplet-um"].as<double>())}, "droplet-um");
    return PhasePair{jd, jd};
  }
  if (phase == "iso") {
    if (gGiven || dGiven) throw UsageError("--phase iso takes no --g1, --gm or --droplet-um");
    return PhasePair{{PhaseKind::Isotropic, 0.0f}, {PhaseKind::Isotropic, 0.0f}};
  }
  throw UsageError("--phase: expected cs, hg, jd or iso, got '" + phase + "'");
}

}  // namespace cloudlut::cli
