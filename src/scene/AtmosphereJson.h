#pragma once
// The atmosphere's parameters (lut_formats/glsl/cloudlut_atmosphere.glsl) as JSON: the scene's
// "sky" object and the atmosphere tables' "parameters" (docs/SCENE_FORMAT.md, FORMAT.md). Every
// field is optional and defaults to defaultAtmosphere(); a non-physical value is one FileError
// naming the file and the field.
#include <string>

#include <nlohmann/json.hpp>

#include "core/Glsl.h"

namespace cloudlut::scene {

// Fields (units): bottom_radius_m, top_radius_m, rayleigh_scattering_per_m [r, g, b],
// rayleigh_scale_height_m, mie_scattering_per_m, mie_absorption_per_m, mie_scale_height_m,
// mie_g, ozone_absorption_per_m [r, g, b], ozone_bottom_m, ozone_peak_m, ozone_top_m,
// ground_albedo (a number or [r, g, b]). `where` names the file, `prefix` the object ("sky.").
glsl::AtmosphereParameters atmosphereFromJson(const nlohmann::json& j, const std::string& where,
                                              const std::string& prefix);

// The same fields, every one written.
nlohmann::json atmosphereToJson(const glsl::AtmosphereParameters& a);

// The problem with a set of parameters ("field: phrase"), or "" when they are physical:
// coefficients ≥ 0 and finite, scale heights > 0, top above the ground, g in (−1, 1), albedo in
// [0, 1], ozone bottom ≤ peak ≤ top.
std::string atmosphereProblem(const glsl::AtmosphereParameters& a);

}  // namespace cloudlut::scene
