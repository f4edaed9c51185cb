#include "scene/AtmosphereJson.h"

#include <cmath>

#include "core/Errors.h"

namespace cloudlut::scene {
namespace {

bool finite3(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool nonNegative3(const glm::vec3& v) { return finite3(v) && v.x >= 0.0f && v.y >= 0.0f && v.z >= 0.0f; }

float readNumber(const nlohmann::json& j, const char* key, const std::string& where, const std::string& prefix) {
  const nlohmann::json& v = j.at(key);
  if (!v.is_number() || !std::isfinite(v.get<double>()))
    throw FileError(where, prefix + key + ": expected a number, got " + v.dump());
  return v.get<float>();
}

glm::vec3 readColour(const nlohmann::json& j, const char* key, const std::string& where, const std::string& prefix,
                     bool numberAllowed) {
  const nlohmann::json& v = j.at(key);
  if (numberAllowed && v.is_number()) return glm::vec3(readNumber(j, key, where, prefix));
  if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() || !v[2].is_number())
    throw FileError(where, prefix + key + ": expected [r, g, b] numbers, got " + v.dump());
  return glm::vec3(v[0].get<float>(), v[1].get<float>(), v[2].get<float>());
}

}  // namespace

std::string atmosphereProblem(const glsl::AtmosphereParameters& a) {
  const auto positive = [](float x) { return std::isfinite(x) && x > 0.0f; };
  const auto nonNegative = [](float x) { return std::isfinite(x) && x >= 0.0f; };
  if (!positive(a.bottomRadius) || a.bottomRadius > 1e9f) return "bottom_radius_m: must be a positive number of metres (at most 1e9)";
  if (!positive(a.topRadius) || !(a.topRadius > a.bottomRadius) || a.topRadius > 2.0f * a.bottomRadius)
    return "top_radius_m: must lie above the ground (bottom_radius_m) and below twice its radius";
  if (!nonNegative3(a.rayleighScattering)) return "rayleigh_scattering_per_m: must be non-negative";
  if (!positive(a.rayleighScaleHeight)) return "rayleigh_scale_height_m: must be positive";
  if (!nonNegative(a.mieScattering)) return "mie_scattering_per_m: must be non-negative";
  if (!nonNegative(a.mieAbsorption)) return "mie_absorption_per_m: must be non-negative";
  if (!positive(a.mieScaleHeight)) return "mie_scale_height_m: must be positive";
  if (!(std::isfinite(a.mieG) && a.mieG > -1.0f && a.mieG < 1.0f)) return "mie_g: must lie in (-1, 1)";
  if (!nonNegative3(a.ozoneAbsorption)) return "ozone_absorption_per_m: must be non-negative";
  if (!(nonNegative(a.ozoneBottom) && a.ozoneBottom <= a.ozonePeak && a.ozonePeak <= a.ozoneTop && std::isfinite(a.ozoneTop)))
    return "ozone_bottom_m, ozone_peak_m, ozone_top_m: must be non-negative and in that order";
  if (!nonNegative3(a.groundAlbedo) || a.groundAlbedo.x > 1.0f || a.groundAlbedo.y > 1.0f || a.groundAlbedo.z > 1.0f)
    return "ground_albedo: must lie in [0, 1]";
  return {};
}

glsl::AtmosphereParameters atmosphereFromJson(const nlohmann::json& j, const std::string& where,
                                              const std::string& prefix) {
  glsl::AtmosphereParameters a = glsl::defaultAtmosphere();
  if (!j.is_object()) throw FileError(where, prefix + ": expected an object");
  const auto number = [&](const char* key, float& out) {
    if (j.contains(key)) out = readNumber(j, key, where, prefix);
  };
  const auto colour = [&](const char* key, glm::vec3& out, bool numberAllowed) {
    if (j.contains(key)) out = readColour(j, key, where, prefix, numberAllowed);
  };
  number("bottom_radius_m", a.bottomRadius);
  number("top_radius_m", a.topRadius);
  colour("rayleigh_scattering_per_m", a.rayleighScattering, false);
  number("rayleigh_scale_height_m", a.rayleighScaleHeight);
  number("mie_scattering_per_m", a.mieScattering);
  number("mie_absorption_per_m", a.mieAbsorption);
  number("mie_scale_height_m", a.mieScaleHeight);
  number("mie_g", a.mieG);
  colour("ozone_absorption_per_m", a.ozoneAbsorption, false);
  number("ozone_bottom_m", a.ozoneBottom);
  number("ozone_peak_m", a.ozonePeak);
  number("ozone_top_m", a.ozoneTop);
  colour("ground_albedo", a.groundAlbedo, true);
  if (const std::string problem = atmosphereProblem(a); !problem.empty()) throw FileError(where, prefix + problem);
  return a;
}

nlohmann::json atmosphereToJson(const glsl::AtmosphereParameters& a) {
  const auto rgb = [](const glm::vec3& v) { return nlohmann::json::array({v.x, v.y, v.z}); };
  return {{"bottom_radius_m", a.bottomRadius},
          {"top_radius_m", a.topRadius},
          {"rayleigh_scattering_per_m", rgb(a.rayleighScattering)},
          {"rayleigh_scale_height_m", a.rayleighScaleHeight},
          {"mie_scattering_per_m", a.mieScattering},
          {"mie_absorption_per_m", a.mieAbsorption},
          {"mie_scale_height_m", a.mieScaleHeight},
          {"mie_g", a.mieG},
          {"ozone_absorption_per_m", rgb(a.ozoneAbsorption)},
          {"ozone_bottom_m", a.ozoneBottom},
          {"ozone_peak_m", a.ozonePeak},
          {"ozone_top_m", a.ozoneTop},
          {"ground_albedo", rgb(a.groundAlbedo)}};
}

}  // namespace cloudlut::scene
