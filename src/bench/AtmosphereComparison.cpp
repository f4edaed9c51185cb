#include "bench/AtmosphereComparison.h"

#include <algorithm>
#include <cmath>

namespace cloudlut::bench {
namespace {

glm::dvec3 elevated(double azimuthCos, double azimuthSin, double elevationDeg) {
  const double e = elevationDeg * 3.14159265358979323846 / 180.0;
  return {std::cos(e) * azimuthCos, std::sin(e), std::cos(e) * azimuthSin};
}

}  // namespace

std::vector<AtmosphereCheck> atmosphereChecks() {
  std::vector<AtmosphereCheck> checks;
  for (const double e : {90.0, 30.0, 5.0, -2.0}) {
    const glm::dvec3 sun = elevated(1.0, 0.0, e);
    const double viewElevation = std::max(e, 2.0);
    checks.push_back({"zenith", e, {0.0, 1.0, 0.0}, sun});
    checks.push_back({"horizon", e, elevated(1.0, 0.0, 0.0), sun});
    checks.push_back({"toward sun", e, elevated(1.0, 0.0, viewElevation), sun});
    checks.push_back({"away from sun", e, elevated(-1.0, 0.0, viewElevation), sun});
    checks.push_back({"90 deg from sun", e, elevated(0.0, 1.0, 0.0), sun});
  }
  return checks;
}

glm::dvec3 checkPosition(const glsl::AtmosphereParameters& a) {
  return {0.0, double(a.bottomRadius) + kCheckAltitudeMetres, 0.0};
}

glm::dvec3 tableSkyRadiance(const bake::AtmosphereTables& tables, const glsl::AtmosphereParameters& a,
                            const AtmosphereCheck& check, int orders) {
  const glsl::AtmosphereTexture transmittance = bake::atmosphereTexture(tables.transmittance);
  const glsl::AtmosphereTexture multiple = bake::atmosphereTexture(tables.multipleScattering);
  const glsl::AtmosphereTexture irradiance = bake::atmosphereTexture(tables.irradiance);
  const float r = static_cast<float>(checkPosition(a).y);
  const float mu = static_cast<float>(check.view.y), muS = static_cast<float>(check.sun.y);
  const float nu = static_cast<float>(glm::dot(check.view, check.sun));
  const float tMax = glsl::distanceToAtmosphereEnd(a, r, mu);
  const glsl::SkySegment s = glsl::integrateSkySegment(a, transmittance, multiple, r, mu, muS, nu, tMax,
                                                       glsl::CLOUDLUT_SKY_STEPS, orders == 1 ? 0.0f : 1.0f);
  glm::vec3 L = s.radiance;
  if (orders != 1 && glsl::rayHitsGround(a, r, mu)) {
    const float muSg = (r * muS + tMax * nu) / a.bottomRadius;
    L += s.transmittance * glsl::groundRadiance(a, transmittance, irradiance, muSg, 1.0f);
  }
  return glm::dvec3(L);
}

// Below kRadianceFloor (sr⁻¹ per unit irradiance, about 1e-4 of the daytime sky) differences count
// against the floor: the sky opposite a sun below the horizon is nearly black.
constexpr double kRadianceFloor = 1e-5;

double relativeError(const glm::dvec3& x, const glm::dvec3& ref) {
  double worst = 0.0;
  for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(x[c] - ref[c]) / std::max(std::abs(ref[c]), kRadianceFloor));
  return worst;
}

}  // namespace cloudlut::bench
