#pragma once
// Random view rays into the unit sphere, as a distant camera sees them: shared by the
// resolution choice of `bake --for-scene` and the table-layout bench.
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace cloudlut {

// A unit direction v entering the unit sphere at the surface point S (unit), cosine-weighted
// about the inward normal −S: cos θ = sqrt(u1) from the normal, azimuth 2π·u2 (u1, u2 uniform
// in [0, 1)). Pdf cos θ / π over the inward hemisphere.
inline glm::dvec3 cosineWeightedInward(const glm::dvec3& S, double u1, double u2) {
  const glm::dvec3 n = -S, a = std::abs(n.x) < 0.7 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 t = glm::normalize(glm::cross(n, a)), b = glm::cross(n, t);
  const double q = std::sqrt(u1), p = 6.283185307179586 * u2;
  return glm::normalize(std::sqrt(1.0 - q * q) * n + q * (std::cos(p) * t + std::sin(p) * b));
}

}  // namespace cloudlut
