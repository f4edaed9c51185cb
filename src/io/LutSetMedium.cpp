#include "io/LutSetMedium.h"

#include <fstream>

#include <nlohmann/json.hpp>

#include "core/Errors.h"

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
  try {
    const nlohmann::json& od = m.at("tables").at("optical_depth").at("parameters");
    const auto model = parseDensityModel(od.at("density_model").get<std::string>());
    if (!model) throw FileError(file, "optical_depth: unknown density_model");
    medium.model = *model;
    medium.seed = od.at("seed").get<std::uint64_t>();
    medium.extinction = od.at("extinction_per_m").get<double>();
    medium.radius = od.at("radius_m").get<double>();
  } catch (const nlohmann::json::exception&) {
    throw FileError(file, "tables.optical_depth.parameters: expected density_model, seed, extinction_per_m, radius_m");
  }
  if (!(medium.extinction > 0) || !(medium.radius > 0))
    throw FileError(file, "optical_depth: extinction and radius must be positive");
  for (const char* table : {"single_scattering", "multiple_scattering"}) {
    if (!m["tables"].contains(table)) continue;
    const nlohmann::json& p = m["tables"][table].value("parameters", nlohmann::json::object());
    if (p.contains("first_phase")) medium.first = phaseFromJson(p["first_phase"], file, std::string(table) + ".first_phase");
    if (p.contains("later_phase")) medium.later = phaseFromJson(p["later_phase"], file, std::string(table) + ".later_phase");
  }
  return medium;
}

}  // namespace cloudlut::io
