#pragma once
// The rules every physical parameter obeys, wherever it is read: a command-line option
// (cli/Options, cli/SceneOptions), a LUT set's manifest (io/LutSetMedium), a table's JSON
// description (core/TableLookup, io/TableDescription). Each rule returns the problem as a
// phrase ("must be a positive number at most 10"), empty when the value is acceptable; the
// caller names the option or the file and field. One definition, so a value the command line
// refuses is refused in a file too.
#include <cstdint>
#include <optional>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "core/Phase.h"

namespace cloudlut::rules {

// β, m⁻¹: real clouds lie near 0.01 … 0.5; the ceiling keeps β·R within kMaxUnitOpticalRadius
// for any radius a scene uses and keeps every product finite.
inline constexpr double kMaxExtinctionPerMetre = 10.0;
// R, m: a particle larger than 100 km is no cumulus cell.
inline constexpr double kMaxRadiusMetres = 1e5;
// β·R, the optical radius of a particle of density scale 1 (dimensionless). The default is
// 12.87; a path tracer needs about τ² scattering events per path in a particle of optical
// radius τ, so 1000 (78 times the default) bounds the work of `reference scene`.
inline constexpr double kMaxUnitOpticalRadius = 1000.0;

// The problem with β (1/m), or "".
std::string extinctionProblem(double extinctionPerMetre);
// The problem with R (m), or "".
std::string radiusProblem(double radiusMetres);
// The problem with the product β·R (dimensionless), or "".
std::string opticalRadiusProblem(double extinctionPerMetre, double radiusMetres);
// The problem with an optical-depth table's chord_outer_third_share (dimensionless; the share
// of a chord's optical depth in each outer third of its matter, bake/ChordMatterProfile.h), or
// "": in [0, ½] (½: all of it in the outer thirds; 1/3: laid evenly).
std::string chordOuterThirdProblem(double share);
// The problem with a phase function's parameter for its kind, or "": g in (−1, 1) for
// Henyey–Greenstein and Cornette–Shanks, d in [5, 50] µm for Jendersie–d'Eon (its fit's range),
// anything finite for the isotropic phase.
std::string phaseProblem(const Phase& phase);

// A phase read from JSON {"kind": integer, "param": number} under the rules above; the problem
// in `problem` (and nothing returned) otherwise. Wrong types are problems, never exceptions.
std::optional<Phase> phaseFromJsonChecked(const nlohmann::json& j, std::string& problem);
// A number read from JSON; "expected a number" when it is of another type or not finite.
std::optional<double> numberFromJson(const nlohmann::json& j, std::string& problem);
// A seed read from JSON: an unsigned integer (0 … 2⁶⁴ − 1); not −1, not 1.5, not a string.
std::optional<std::uint64_t> seedFromJson(const nlohmann::json& j, std::string& problem);

}  // namespace cloudlut::rules
