#pragma once
// The viewer's camera and sun as angles. World +y is up; yaw is measured counter-clockwise seen
// from above (turning left increases it), yaw 0 looking along −z; pitch is the elevation of the
// view direction:
//   forward = (−sin yaw · cos pitch, sin pitch, −cos yaw · cos pitch).
// The sun direction (toward the sun) from its azimuth α (about +y, from +z toward +x) and
// elevation ε: (cos ε · sin α, sin ε, cos ε · cos α).
#include <glm/vec3.hpp>

#include "scene/Scene.h"

namespace cloudlut::view {

inline constexpr float kMaxPitchDeg = 89.0f;

struct FlyCamera {
  glm::vec3 eye{0.0f};
  float yawDeg = 0.0f;
  float pitchDeg = 0.0f;  // clamped to ±kMaxPitchDeg
  float fovDeg = 45.0f;   // vertical

  // The angles of a look-at camera (its up is taken as +y).
  static FlyCamera fromCamera(const scene::Camera& camera);
  glm::vec3 forward() const;
  // Horizontal unit vector to the right of the view direction.
  glm::vec3 right() const;
  // A look-at camera one unit ahead, up +y.
  scene::Camera camera() const;

  // Turns by the angles (degrees; positive yaw turns left, positive pitch looks up).
  void turn(float yawDeg, float pitchDeg);
  // Moves in world units:
  // eye += along·forward + up·(0, 1, 0) + side·right.
  void move(float along, float up, float side);
};

struct SunAngles {
  float azimuthDeg = 0.0f;
  float elevationDeg = 45.0f;  // clamped to [−90, 90]

  static SunAngles fromDirection(const glm::vec3& towardSun);
  glm::vec3 direction() const;
  void turn(float azimuthDeg, float elevationDeg);
};

}  // namespace cloudlut::view
