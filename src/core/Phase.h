#pragma once
// The phase function of a medium: a kind and one parameter, selected exactly as phaseFunction()
// of lut_formats/glsl/cloudlut_phase.glsl selects it (PhaseKind value k is the GLSL's kind k, and
// the number the tables' JSON stores). The one description every layer uses: the bakers, the
// Monte Carlo references, the ray marcher and the command line.
#include <optional>
#include <string>

#include <nlohmann/json_fwd.hpp>

namespace cloudlut {

// Numbered as the CLOUDLUT_PHASE_* constants of cloudlut_phase.glsl (checked in Phase.cpp).
enum class PhaseKind : int { Isotropic = 0, HenyeyGreenstein = 1, CornetteShanks = 2, JendersieDeon = 3 };

struct Phase {
  PhaseKind kind = PhaseKind::Isotropic;
  // g (mean cosine parameter, dimensionless) for Henyey–Greenstein and Cornette–Shanks; the
  // droplet diameter d in µm for Jendersie–d'Eon; unused for the isotropic phase.
  float param = 0.0f;
  friend bool operator==(const Phase&, const Phase&) = default;
};

// The kind as the GLSL's phaseFunction() and the table JSON number it.
constexpr int glslKind(PhaseKind kind) { return static_cast<int>(kind); }
// The kind numbered `k`; nothing for a number no kind has.
std::optional<PhaseKind> phaseKindFromInt(int k);

// The table JSON's "name": "isotropic", "henyey_greenstein", "cornette_shanks", "jendersie_deon".
const char* phaseKindName(PhaseKind kind);
// For messages: "cs g=0.7", "hg g=0.9", "jd d=10 um", "iso".
std::string describePhase(const Phase& phase);

// p(μ) in sr⁻¹, μ = cos θ of the scattering angle: phaseFunction(kind, μ, param) of
// cloudlut_phase.glsl (seed eq. 7 for Cornette–Shanks).
float phaseValue(const Phase& phase, float mu);

// The phase function's mean cosine g = ∫ μ P(μ) dω (dimensionless; P normalised over the sphere),
// clamped to [0, 0.99]: the asymmetry the two-stream terms of the shading take
// (diffuseTransmittance, cloudlut_shading.glsl).
float phaseMeanCosine(const Phase& phase);

// The table JSON form {"kind": integer, "param": number, "name": string} (lut_formats/FORMAT.md,
// the scattering tables' first_phase / later_phase).
nlohmann::json phaseToJson(const Phase& phase);
// The way back; FileError(file, "<field>: ...") when `j` is not {"kind": integer, "param":
// number} of a known kind whose parameter obeys core/ParameterRules.h (rules::phaseProblem).
Phase phaseFromJson(const nlohmann::json& j, const std::string& file, const std::string& field);
// The phase a table's parameters record under `key` ("first_phase"), read leniently as the
// shaders' phaseFunction() would take it: a missing object, kind or param takes `fallback`'s; a
// kind no phase has is isotropic. nlohmann::json::type_error when kind or param is not a number.
Phase recordedPhase(const nlohmann::json& parameters, const char* key, const Phase& fallback);

}  // namespace cloudlut
