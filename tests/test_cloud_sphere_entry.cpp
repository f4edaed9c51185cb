// cloudSphereEntry (lut_formats/glsl/cloudlut_shading.glsl), the point where a view ray enters
// the cloud-scale sphere, checked against its definition computed here from angles: on the great
// circle through the sun and the camera, at angle θS = acos((τcol − 2τsun)/τcol) from the sun
// when that point faces the camera (cos ≥ 0.02), else at the nearest angle that does. And the
// point moves continuously with τsun and with the view direction.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "core/Glsl.h"

namespace {

constexpr double kPi = 3.14159265358979323846;

// The expected point from angles, in double: the camera at angle β ∈ [0, π] from the sun on the
// circle, the point at θS clamped to [β − acos 0.02, β + acos 0.02].
glm::dvec3 expectedEntry(double tauSun, double tauColumn, const glm::dvec3& dir, const glm::dvec3& sun) {
  const double cosS = std::clamp((tauColumn - 2.0 * tauSun) / tauColumn, -1.0, 1.0);
  const glm::dvec3 toCamera = -dir;
  const glm::dvec3 t = glm::normalize(toCamera - glm::dot(toCamera, sun) * sun);
  const double beta = std::atan2(glm::dot(toCamera, t), glm::dot(toCamera, sun));
  const double limb = std::acos(0.02);
  const double angle = std::clamp(std::acos(cosS), beta - limb, beta + limb);
  return std::cos(angle) * sun + std::sin(angle) * t;
}

glm::vec3 randomUnit(std::mt19937& rng) {
  std::normal_distribution<float> n(0.0f, 1.0f);
  return glm::normalize(glm::vec3(n(rng), n(rng), n(rng)));
}

}  // namespace

TEST_CASE("cloudSphereEntry: the point of the definition, facing the camera", "[lighting][shading]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  double worst = 0.0, leastFacing = 1.0;
  for (int n = 0; n < 20000; ++n) {
    const glm::vec3 sun = randomUnit(rng), dir = randomUnit(rng);
    if (std::abs(glm::dot(sun, dir)) > 0.999f) continue;  // the circle is undefined (tested below)
    const float tauColumn = 0.1f + 40.0f * u(rng), tauSun = tauColumn * u(rng);
    const glm::vec3 S = cloudlut::glsl::cloudSphereEntry(tauSun, tauColumn, dir, sun);
    const glm::dvec3 e = expectedEntry(tauSun, tauColumn, glm::dvec3(dir), glm::dvec3(sun));
    worst = std::max(worst, glm::length(glm::dvec3(S) - e));
    leastFacing = std::min(leastFacing, static_cast<double>(glm::dot(S, -dir)));
    CHECK(std::abs(glm::length(S) - 1.0f) < 1e-4f);
  }
  INFO("worst |S - expected| " << worst << ", least S·(toward the camera) " << leastFacing);
  CHECK(worst < 2e-4);
  CHECK(leastFacing > 0.0199);
}

TEST_CASE("cloudSphereEntry: continuous in the column's split and in the view direction", "[lighting][shading]") {
  // Looking toward the sun, where the point chosen from the sun alone faces away for small τsun:
  // sweeps of τsun (camera 30° off the sun) and of the camera's angle off the sun (τsun = 0,
  // 0.5° to 179.5°), 4000 steps each. A step of the sweep moves the point by at most a few
  // hundredths; a jump across the sphere would be a step of order 1.
  const glm::vec3 sun = glm::normalize(glm::vec3(0.3f, 0.2f, 1.0f));
  const glm::vec3 side = glm::normalize(glm::cross(sun, glm::vec3(0.0f, 1.0f, 0.0f)));
  const float tauColumn = 12.0f;
  const int steps = 4000;
  auto viewOff = [&](double degrees) {
    const float off = static_cast<float>(degrees * kPi / 180.0);
    return glm::vec3(std::cos(off) * sun + std::sin(off) * side);
  };
  double largestStep = 0.0, leastFacing = 1.0;
  glm::vec3 previous = cloudlut::glsl::cloudSphereEntry(0.0f, tauColumn, viewOff(30.0), sun);
  for (int i = 1; i <= steps; ++i) {
    const float tauSun = tauColumn * static_cast<float>(i) / steps;
    const glm::vec3 S = cloudlut::glsl::cloudSphereEntry(tauSun, tauColumn, viewOff(30.0), sun);
    largestStep = std::max(largestStep, static_cast<double>(glm::length(S - previous)));
    leastFacing = std::min(leastFacing, static_cast<double>(glm::dot(S, -viewOff(30.0))));
    previous = S;
  }
  previous = cloudlut::glsl::cloudSphereEntry(0.0f, tauColumn, viewOff(0.5), sun);
  for (int i = 1; i <= steps; ++i) {
    const glm::vec3 dir = viewOff(0.5 + 179.0 * i / steps);
    const glm::vec3 S = cloudlut::glsl::cloudSphereEntry(0.0f, tauColumn, dir, sun);
    largestStep = std::max(largestStep, static_cast<double>(glm::length(S - previous)));
    leastFacing = std::min(leastFacing, static_cast<double>(glm::dot(S, -dir)));
    previous = S;
  }
  INFO("largest step " << largestStep << ", least facing " << leastFacing);
  CHECK(largestStep < 0.05);
  CHECK(leastFacing > 0.0199);
}
