#pragma once
// The atmosphere's checks (issue 13): the tables and the sky computed from them by the shared
// GLSL (what the renderer evaluates) against the brute-force reference (src/reference/
// AtmosphereReference.h), from a camera 500 m above the ground, at the zenith, the horizon under
// the sun, toward the sun, away from it and 90° from it, for sun elevations 90°, 30°, 5° and −2°.
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "bake/AtmosphereBaker.h"
#include "reference/AtmosphereReference.h"

namespace cloudlut::bench {

inline constexpr double kCheckAltitudeMetres = 500.0;

struct AtmosphereCheck {
  std::string name;          // "zenith", "horizon", "toward sun", "away from sun", "90 deg from sun"
  double sunElevationDeg;
  glm::dvec3 view;           // unit, planet frame (+y up at the camera)
  glm::dvec3 sun;            // unit, toward the sun
};

// The 20 checks. Toward and away from the sun look at least 2° above the horizon (below it the
// ray meets the ground); the horizon looks level along the sun's azimuth; 90° from the sun looks
// level, perpendicular to the sun's azimuth.
std::vector<AtmosphereCheck> atmosphereChecks();

// The camera's position, m from the planet's centre.
glm::dvec3 checkPosition(const glsl::AtmosphereParameters& a);

// Sky radiance along the view from the tables by the shared GLSL (integrateSkySegment with
// CLOUDLUT_SKY_STEPS pieces; orders 1 = single scattering only, else all), plus the ground's
// radiance through the atmosphere when the ray meets it (all orders only), sr⁻¹.
glm::dvec3 tableSkyRadiance(const bake::AtmosphereTables& tables, const glsl::AtmosphereParameters& a,
                            const AtmosphereCheck& check, int orders);

// The largest relative difference over the channels, |x − ref| / max(ref, 1e-5 sr⁻¹).
double relativeError(const glm::dvec3& x, const glm::dvec3& ref);

}  // namespace cloudlut::bench
