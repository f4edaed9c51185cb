#include "core/Phase.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "core/Errors.h"
#include "core/Glsl.h"
#include "core/ParameterRules.h"

namespace cloudlut {

static_assert(glslKind(PhaseKind::Isotropic) == glsl::CLOUDLUT_PHASE_ISOTROPIC);
static_assert(glslKind(PhaseKind::HenyeyGreenstein) == glsl::CLOUDLUT_PHASE_HENYEY_GREENSTEIN);
static_assert(glslKind(PhaseKind::CornetteShanks) == glsl::CLOUDLUT_PHASE_CORNETTE_SHANKS);
static_assert(glslKind(PhaseKind::JendersieDeon) == glsl::CLOUDLUT_PHASE_JENDERSIE_DEON);

std::optional<PhaseKind> phaseKindFromInt(int k) {
  if (k < glslKind(PhaseKind::Isotropic) || k > glslKind(PhaseKind::JendersieDeon)) return std::nullopt;
  return static_cast<PhaseKind>(k);
}

const char* phaseKindName(PhaseKind kind) {
  switch (kind) {
    case PhaseKind::HenyeyGreenstein: return "henyey_greenstein";
    case PhaseKind::CornetteShanks: return "cornette_shanks";
    case PhaseKind::JendersieDeon: return "jendersie_deon";
    case PhaseKind::Isotropic: break;
  }
  return "isotropic";
}

std::string describePhase(const Phase& p) {
  char buf[64];
  if (p.kind == PhaseKind::HenyeyGreenstein || p.kind == PhaseKind::CornetteShanks)
    std::snprintf(buf, sizeof buf, "%s g=%g", p.kind == PhaseKind::HenyeyGreenstein ? "hg" : "cs",
                  static_cast<double>(p.param));
  else if (p.kind == PhaseKind::JendersieDeon)
    std::snprintf(buf, sizeof buf, "jd d=%g um", static_cast<double>(p.param));
  else
    std::snprintf(buf, sizeof buf, "iso");
  return buf;
}

float phaseValue(const Phase& phase, float mu) { return glsl::phaseFunction(glslKind(phase.kind), mu, phase.param); }

// ∫ μ P(μ) dω = 2π ∫_{-1}^{1} μ P(μ) dμ, midpoint rule in θ on 4096 steps (the forward peaks of
// the cloud phase functions are a degree wide).
float phaseMeanCosine(const Phase& phase) {
  constexpr int kSteps = 4096;
  constexpr double kPi = 3.14159265358979323846;
  double sum = 0.0;
  for (int i = 0; i < kSteps; ++i) {
    const double theta = (i + 0.5) * kPi / kSteps;
    const double mu = std::cos(theta);
    sum += mu * phaseValue(phase, static_cast<float>(mu)) * std::sin(theta);
  }
  return std::clamp(static_cast<float>(2.0 * kPi * sum * kPi / kSteps), 0.0f, 0.99f);
}

nlohmann::json phaseToJson(const Phase& p) {
  return {{"kind", glslKind(p.kind)}, {"param", p.param}, {"name", phaseKindName(p.kind)}};
}

Phase phaseFromJson(const nlohmann::json& j, const std::string& file, const std::string& field) {
  std::string problem;
  const std::optional<Phase> phase = rules::phaseFromJsonChecked(j, problem);
  if (!phase) throw FileError(file, field + ": " + problem);
  return *phase;
}

Phase recordedPhase(const nlohmann::json& parameters, const char* key, const Phase& fallback) {
  const nlohmann::json phase = parameters.value(key, nlohmann::json::object());
  const int kind = phase.value("kind", glslKind(fallback.kind));
  return {phaseKindFromInt(kind).value_or(PhaseKind::Isotropic), phase.value("param", fallback.param)};
}

}  // namespace cloudlut
