#include "core/AngularClosure.h"

#include <algorithm>
#include <cmath>

#include "core/Glsl.h"

namespace cloudlut {

namespace {

// Four decimals: the Monte Carlo's own error is 10⁻² and more (a shorter record to read).
std::vector<double> rounded(const std::vector<float>& v) {
  std::vector<double> out;
  for (float x : v) out.push_back(std::round(static_cast<double>(x) * 1e4) / 1e4);
  return out;
}

}  // namespace

nlohmann::json angularClosureToJson(const AngularClosure& c) {
  return {{"log2_rho_first", c.log2RhoFirst}, {"log2_rho_step", c.log2RhoStep},     {"density_nodes", c.densityNodes},
          {"mu_bins", c.muBins},               {"values", rounded(c.values)}, {"relative_errors", rounded(c.relativeErrors)}, {"own_core_shadow", c.ownCoreShadow},
          {"own_core_shadow_max", c.ownCoreShadowMax}};
}

std::optional<AngularClosure> angularClosureFromJson(const nlohmann::json& record, std::string& problem) {
  const auto bad = [&](const std::string& what) {
    problem = what;
    return std::nullopt;
  };
  if (!record.is_object()) return bad("expected a JSON object");
  const auto number = [&](const char* key, double& out) {
    if (!record.contains(key) || !record[key].is_number()) return false;
    out = record[key].get<double>();
    return std::isfinite(out);
  };
  double first = 0, step = 0, nodes = 0, bins = 0;
  if (!number("log2_rho_first", first) || std::abs(first) > 64.0)
    return bad("log2_rho_first: expected a number in [-64, 64]");
  if (!number("log2_rho_step", step) || !(step > 0.0) || step > 64.0)
    return bad("log2_rho_step: expected a number in (0, 64]");
  for (const auto& [key, value] : {std::pair<const char*, double*>{"density_nodes", &nodes}, {"mu_bins", &bins}})
    if (!number(key, *value) || *value != std::floor(*value) || *value < 1 || *value > kMaxAngularClosureAxis)
      return bad(std::string(key) + ": expected a whole number from 1 to " + std::to_string(kMaxAngularClosureAxis));
  AngularClosure c;
  c.log2RhoFirst = static_cast<float>(first);
  c.log2RhoStep = static_cast<float>(step);
  c.densityNodes = static_cast<int>(nodes);
  c.muBins = static_cast<int>(bins);
  const std::size_t count = static_cast<std::size_t>(c.densityNodes) * static_cast<std::size_t>(c.muBins);
  if (!record.contains("values") || !record["values"].is_array() || record["values"].size() != count)
    return bad("values: expected density_nodes · mu_bins = " + std::to_string(count) + " numbers");
  c.values.clear();
  for (const nlohmann::json& v : record["values"]) {
    // a closure moves light between directions: a factor outside [1/4, 4] is not one
    if (!v.is_number() || !(v.get<double>() >= 0.25 && v.get<double>() <= 4.0))
      return bad("values: expected numbers in [0.25, 4]");
    c.values.push_back(v.get<float>());
  }
  if (record.contains("relative_errors")) {
    const nlohmann::json& e = record["relative_errors"];
    if (!e.is_array() || (!e.empty() && e.size() != count)) return bad("relative_errors: expected " + std::to_string(count) + " numbers");
    for (const nlohmann::json& v : e) {
      if (!v.is_number() || !(v.get<double>() >= 0.0 && v.get<double>() <= 1e6))
        return bad("relative_errors: expected numbers ≥ 0");
      c.relativeErrors.push_back(v.get<float>());
    }
  }
  if (record.contains("own_core_shadow")) {
    if (!record["own_core_shadow"].is_boolean()) return bad("own_core_shadow: expected true or false");
    c.ownCoreShadow = record["own_core_shadow"].get<bool>();
  }
  if (record.contains("own_core_shadow_max")) {
    double most = 0;
    if (!number("own_core_shadow_max", most) || !(most >= 1.0 && most <= kMaxOwnCoreShadowMax))
      return bad("own_core_shadow_max: expected a number in [1, " + std::to_string(static_cast<int>(kMaxOwnCoreShadowMax)) + "]");
    c.ownCoreShadowMax = static_cast<float>(most);
  }
  return c;
}

float angularClosureAt(const AngularClosure& c, float rho, float mu) {
  const int nodes = c.densityNodes, bins = c.muBins;
  const float n = static_cast<float>(nodes), b = static_cast<float>(bins);
  const glm::vec2 p = glsl::angularClosurePosition(rho, mu, c.log2RhoFirst, c.log2RhoStep, n, b);
  const glm::vec2 cell = glsl::angularClosureCell(p, n, b);
  const int s0 = static_cast<int>(cell.x), m0 = static_cast<int>(cell.y);
  const int s1 = std::min(s0 + 1, nodes - 1), m1 = std::min(m0 + 1, bins - 1);
  const auto at = [&](int i, int j) { return c.values[static_cast<std::size_t>(i * bins + j)]; };
  return glsl::angularClosureBlend(glm::vec4(at(s0, m0), at(s0, m1), at(s1, m0), at(s1, m1)), p, cell);
}

}  // namespace cloudlut
