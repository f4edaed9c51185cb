#include "view/FlyCamera.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

namespace cloudlut::view {

FlyCamera FlyCamera::fromCamera(const scene::Camera& camera) {
  FlyCamera c;
  c.eye = camera.eye;
  c.fovDeg = camera.fovDeg;
  const glm::vec3 f = glm::normalize(camera.target - camera.eye);
  c.yawDeg = glm::degrees(std::atan2(-f.x, -f.z));
  c.pitchDeg = std::clamp(glm::degrees(std::asin(std::clamp(f.y, -1.0f, 1.0f))), -kMaxPitchDeg, kMaxPitchDeg);
  return c;
}

glm::vec3 FlyCamera::forward() const {
  const float yaw = glm::radians(yawDeg), pitch = glm::radians(pitchDeg);
  return {-std::sin(yaw) * std::cos(pitch), std::sin(pitch), -std::cos(yaw) * std::cos(pitch)};
}

glm::vec3 FlyCamera::right() const {
  const float yaw = glm::radians(yawDeg);
  return {std::cos(yaw), 0.0f, -std::sin(yaw)};
}

scene::Camera FlyCamera::camera() const {
  scene::Camera c;
  c.eye = eye;
  c.target = eye + forward();
  c.up = glm::vec3(0.0f, 1.0f, 0.0f);
  c.fovDeg = fovDeg;
  return c;
}

void FlyCamera::turn(float yaw, float pitch) {
  yawDeg = std::remainder(yawDeg + yaw, 360.0f);
  pitchDeg = std::clamp(pitchDeg + pitch, -kMaxPitchDeg, kMaxPitchDeg);
}

void FlyCamera::move(float along, float up, float side) {
  eye += along * forward() + glm::vec3(0.0f, up, 0.0f) + side * right();
}

SunAngles SunAngles::fromDirection(const glm::vec3& towardSun) {
  const glm::vec3 d = glm::normalize(towardSun);
  SunAngles s;
  s.elevationDeg = glm::degrees(std::asin(std::clamp(d.y, -1.0f, 1.0f)));
  s.azimuthDeg = glm::degrees(std::atan2(d.x, d.z));
  return s;
}

glm::vec3 SunAngles::direction() const {
  const float a = glm::radians(azimuthDeg), e = glm::radians(elevationDeg);
  return {std::cos(e) * std::sin(a), std::sin(e), std::cos(e) * std::cos(a)};
}

void SunAngles::turn(float azimuth, float elevation) {
  azimuthDeg = std::remainder(azimuthDeg + azimuth, 360.0f);
  elevationDeg = std::clamp(elevationDeg + elevation, -90.0f, 90.0f);
}

}  // namespace cloudlut::view
