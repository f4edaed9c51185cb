#pragma once
// A recorded flight: the camera and the sun direction of each frame the viewer showed, with the
// time it was shown. `cloudlut view --record FILE` writes one; `cloudlut render --path FILE`
// renders it frame by frame. The JSON schema is in docs/SCENE_FORMAT.md ("Camera paths");
// parseCameraPath validates every field and throws cloudlut::FileError naming the source and
// the field, e.g. "flight.json: frames[2].eye: expected 3 numbers".
#include <filesystem>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "scene/Scene.h"

namespace cloudlut::scene {

inline constexpr const char* kCameraPathFormat = "cloudlut camera path";
inline constexpr int kCameraPathVersion = 1;

struct CameraPathFrame {
  double seconds = 0.0;  // time since the recording started, non-decreasing along the path
  Camera camera;
  glm::vec3 sunDirection{0.0f, 1.0f, 0.0f};  // toward the sun, unit
};

struct CameraPath {
  std::vector<CameraPathFrame> frames;
};

// The document of a path (the inverse of parseCameraPath).
nlohmann::json cameraPathToJson(const CameraPath& path);

// The document as text, one frame a line.
std::string cameraPathText(const CameraPath& path);

// Parses and validates a path document; `source` names it in error messages. A path holds at
// least one frame; every camera must be usable (eye ≠ target, up not parallel to the view
// direction, 0 < fov < 180) and every sun direction non-zero.
CameraPath parseCameraPath(const nlohmann::json& document, const std::string& source);

// Reads and validates a path file (FileError when missing, not JSON, or malformed).
CameraPath readCameraPath(const std::filesystem::path& path);

}  // namespace cloudlut::scene
