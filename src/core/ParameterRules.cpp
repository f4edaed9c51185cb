// The physical parameter rules: plain range checks, and the JSON readers that apply them.
#include "core/ParameterRules.h"

#include <cmath>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "core/Defaults.h"

namespace cloudlut::rules {

namespace {

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

}  // namespace

std::string extinctionProblem(double beta) {
  if (!std::isfinite(beta) || !(beta > 0.0) || beta > kMaxExtinctionPerMetre)
    return "must be a positive number of 1/m, at most " + number(kMaxExtinctionPerMetre) + " (got " + number(beta) + ")";
  return {};
}

std::string radiusProblem(double radius) {
  if (!std::isfinite(radius) || !(radius > 0.0) || radius > kMaxRadiusMetres)
    return "must be a positive number of metres, at most " + number(kMaxRadiusMetres) + " (got " + number(radius) + ")";
  return {};
}

std::string chordOuterThirdProblem(double share) {
  if (!std::isfinite(share) || !(share >= 0.0) || share > 0.5)
    return "must be a number in [0, 0.5] (got " + number(share) + ")";
  return {};
}

std::string opticalRadiusProblem(double beta, double radius) {
  const double tau = beta * radius;
  if (!std::isfinite(tau) || !(tau > 0.0) || tau > kMaxUnitOpticalRadius)
    return "extinction x radius (the optical radius of a particle of density 1) must lie in (0, " +
           number(kMaxUnitOpticalRadius) + "] (got " + number(tau) + ")";
  return {};
}

std::string phaseProblem(const Phase& phase) {
  const double p = static_cast<double>(phase.param);
  switch (phase.kind) {
    case PhaseKind::HenyeyGreenstein:
    case PhaseKind::CornetteShanks:
      if (!(std::fabs(p) < 1.0)) return "g must lie strictly between -1 and 1 (got " + number(p) + ")";
      return {};
    case PhaseKind::JendersieDeon:
      if (!(p >= static_cast<double>(defaults::kDropletDiameterMinUm) &&
            p <= static_cast<double>(defaults::kDropletDiameterMaxUm)))
        return "the droplet diameter must lie in [5, 50] um, the range of the Jendersie-d'Eon fit (got " + number(p) + ")";
      return {};
    case PhaseKind::Isotropic:
      if (!std::isfinite(p)) return "param must be a finite number";
      return {};
  }
  return "unknown phase kind";
}

std::optional<double> numberFromJson(const nlohmann::json& j, std::string& problem) {
  if (!j.is_number()) {
    problem = std::string("expected a number, got ") + j.type_name();
    return std::nullopt;
  }
  const double v = j.get<double>();
  if (!std::isfinite(v)) {
    problem = "expected a finite number";
    return std::nullopt;
  }
  return v;
}

std::optional<std::uint64_t> seedFromJson(const nlohmann::json& j, std::string& problem) {
  if (!j.is_number_unsigned()) {
    problem = j.is_number() ? "expected a non-negative integer (got " + j.dump() + ")"
                            : std::string("expected a non-negative integer, got ") + j.type_name();
    return std::nullopt;
  }
  return j.get<std::uint64_t>();
}

std::optional<Phase> phaseFromJsonChecked(const nlohmann::json& j, std::string& problem) {
  if (!j.is_object() || !j.contains("kind") || !j["kind"].is_number_integer() || !j.contains("param") ||
      !j["param"].is_number()) {
    problem = "expected {\"kind\": integer, \"param\": number}";
    return std::nullopt;
  }
  const nlohmann::json& kindJson = j["kind"];
  const bool small = kindJson.is_number_unsigned() ? kindJson.get<std::uint64_t>() <= 1000u
                                                   : kindJson.get<long long>() >= -1000 && kindJson.get<long long>() <= 1000;
  const std::optional<PhaseKind> kind = small ? phaseKindFromInt(kindJson.get<int>()) : std::nullopt;
  if (!kind) {
    problem = "unknown phase kind " + kindJson.dump() + " (0 isotropic, 1 Henyey-Greenstein, 2 Cornette-Shanks, "
              "3 Jendersie-d'Eon)";
    return std::nullopt;
  }
  const double param = j["param"].get<double>();
  const Phase phase{*kind, static_cast<float>(param)};
  problem = std::isfinite(param) && std::fabs(param) < 1e30 ? phaseProblem(phase) : "param must be a finite number";
  if (!problem.empty()) return std::nullopt;
  return phase;
}

}  // namespace cloudlut::rules
