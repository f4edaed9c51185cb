#include "io/LutSetMedium.h"

#include <fstream>

#include <nlohmann/json.hpp>

#include "core/Errors.h"
#include "core/ParameterRules.h"

namespace cloudlut::io {

Medium mediumFromLutSet(const std::filesystem::path& dir) {
  const std::string file = (dir / "manifest.json").string();
  std::ifstream in(file);
  if (!in) throw FileError(file, "cannot open the LUT set's manifest");
  nlohmann::json m;
  try {
    m = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw FileError(file, std::string("not JSON (") + e.what() + ")");
  }
  Medium medium;
  medium.source = file;
  const auto fail = [&](const std::string& field, const std::string& problem) {
    throw FileError(file, "tables.optical_depth.parameters." + field + ": " + problem);
  };
  if (!m.is_object() || !m.contains("tables") || !m["tables"].is_object() || !m["tables"].contains("optical_depth") ||
      !m["tables"]["optical_depth"].is_object() || !m["tables"]["optical_depth"].contains("parameters") ||
      !m["tables"]["optical_depth"]["parameters"].is_object())
    throw FileError(file, "tables.optical_depth.parameters: missing (expected density_model, seed, extinction_per_m, radius_m)");
  const nlohmann::json& od = m["tables"]["optical_depth"]["parameters"];
  for (const char* key : {"density_model", "seed", "extinction_per_m", "radius_m"})
    if (!od.contains(key)) fail(key, "missing");
  const nlohmann::json& modelJson = od["density_model"];
  const auto model = modelJson.is_string() ? parseDensityModel(modelJson.get<std::string>()) : std::nullopt;
  if (!model) fail("density_model", "expected one of noise, threshold, pyroclastic, radial, sphere, got " + modelJson.dump());
  medium.model = *model;
  std::string problem;
  const std::optional<std::uint64_t> seed = rules::seedFromJson(od["seed"], problem);
  if (!seed) fail("seed", problem);
  medium.seed = *seed;
  const std::optional<double> beta = rules::numberFromJson(od["extinction_per_m"], problem);
  if (!beta) fail("extinction_per_m", problem);
  if (problem = rules::extinctionProblem(*beta); !problem.empty()) fail("extinction_per_m", problem);
  const std::optional<double> radius = rules::numberFromJson(od["radius_m"], problem);
  if (!radius) fail("radius_m", problem);
  if (problem = rules::radiusProblem(*radius); !problem.empty()) fail("radius_m", problem);
  if (problem = rules::opticalRadiusProblem(*beta, *radius); !problem.empty()) fail("extinction_per_m", problem);
  medium.extinction = *beta;
  medium.radius = *radius;
  for (const char* table : {"single_scattering", "multiple_scattering"}) {
    if (!m["tables"].contains(table)) continue;
    const nlohmann::json& entry = m["tables"][table];
    if (!entry.is_object() || !entry.contains("parameters")) continue;
    const nlohmann::json& p = entry["parameters"];
    if (!p.is_object()) throw FileError(file, std::string("tables.") + table + ".parameters: expected a JSON object");
    if (p.contains("first_phase")) medium.first = phaseFromJson(p["first_phase"], file, std::string("tables.") + table + ".parameters.first_phase");
    if (p.contains("later_phase")) medium.later = phaseFromJson(p["later_phase"], file, std::string("tables.") + table + ".parameters.later_phase");
  }
  return medium;
}

}  // namespace cloudlut::io
