#include "scene/CameraPath.h"

#include <cmath>
#include <fstream>
#include <set>

#include <glm/geometric.hpp>

#include "core/Errors.h"

namespace cloudlut::scene {
namespace {

nlohmann::json toJson(const glm::vec3& v) { return nlohmann::json::array({v.x, v.y, v.z}); }

// Field checks with messages "<source>: <field>: <problem>".
struct PathFields {
  const std::string& source;

  [[noreturn]] void fail(const std::string& field, const std::string& problem) const {
    throw FileError(source, field + ": " + problem);
  }
  double number(const nlohmann::json& j, const std::string& field, const char* expected) const {
    if (!j.is_number()) fail(field, expected);
    const double v = j.get<double>();
    if (!std::isfinite(v) || std::abs(v) > 1e30) fail(field, expected);
    return v;
  }
  glm::vec3 vec3(const nlohmann::json& object, const std::string& key, const std::string& field) const {
    const char* expected = "expected 3 numbers";
    if (!object.contains(key)) fail(field, "missing (expected 3 numbers)");
    const nlohmann::json& j = object[key];
    if (!j.is_array() || j.size() != 3) fail(field, expected);
    return {static_cast<float>(number(j[0], field, expected)), static_cast<float>(number(j[1], field, expected)),
            static_cast<float>(number(j[2], field, expected))};
  }
};

CameraPathFrame parseFrame(const PathFields& check, const nlohmann::json& j, const std::string& field) {
  if (!j.is_object()) check.fail(field, "expected a JSON object");
  static const std::set<std::string> allowed = {"seconds", "eye", "target", "up", "fov_deg", "sun"};
  for (const auto& item : j.items())
    if (!allowed.count(item.key()))
      check.fail(field + "." + item.key(), "unknown field (expected one of: eye, fov_deg, seconds, sun, target, up)");
  CameraPathFrame f;
  if (!j.contains("seconds")) check.fail(field + ".seconds", "missing (expected a non-negative number)");
  f.seconds = check.number(j["seconds"], field + ".seconds", "expected a non-negative number");
  if (f.seconds < 0.0) check.fail(field + ".seconds", "expected a non-negative number");
  f.camera.eye = check.vec3(j, "eye", field + ".eye");
  f.camera.target = check.vec3(j, "target", field + ".target");
  f.camera.up = check.vec3(j, "up", field + ".up");
  if (!j.contains("fov_deg")) check.fail(field + ".fov_deg", "missing (expected degrees in (0, 180))");
  f.camera.fovDeg = static_cast<float>(check.number(j["fov_deg"], field + ".fov_deg", "expected degrees in (0, 180)"));
  if (!(f.camera.fovDeg > 0.0f && f.camera.fovDeg < 180.0f)) check.fail(field + ".fov_deg", "expected degrees in (0, 180)");
  f.sunDirection = check.vec3(j, "sun", field + ".sun");
  const glm::vec3 forward = f.camera.target - f.camera.eye;
  if (!(glm::length(forward) > 1e-6f)) check.fail(field + ".target", "equals the eye");
  if (!(glm::length(glm::cross(forward, f.camera.up)) > 1e-6f * glm::length(forward)))
    check.fail(field + ".up", "zero or parallel to the view direction");
  if (!(glm::length(f.sunDirection) > 1e-12f)) check.fail(field + ".sun", "expected 3 numbers, not all zero");
  f.sunDirection = glm::normalize(f.sunDirection);
  return f;
}

}  // namespace

nlohmann::json cameraPathToJson(const CameraPath& path) {
  nlohmann::json frames = nlohmann::json::array();
  for (const CameraPathFrame& f : path.frames)
    frames.push_back({{"seconds", f.seconds},
                      {"eye", toJson(f.camera.eye)},
                      {"target", toJson(f.camera.target)},
                      {"up", toJson(f.camera.up)},
                      {"fov_deg", f.camera.fovDeg},
                      {"sun", toJson(f.sunDirection)}});
  nlohmann::json document = {{"format", kCameraPathFormat}, {"version", kCameraPathVersion}};
  document["frames"] = std::move(frames);
  return document;
}

std::string cameraPathText(const CameraPath& path) {
  const nlohmann::json document = cameraPathToJson(path);
  std::string text = "{\"format\": " + document["format"].dump() + ", \"version\": " + document["version"].dump() +
                     ",\n \"frames\": [";
  const nlohmann::json& frames = document["frames"];
  for (std::size_t i = 0; i < frames.size(); ++i) text += (i ? ",\n  " : "\n  ") + frames[i].dump();
  return text + "\n ]\n}\n";
}

CameraPath parseCameraPath(const nlohmann::json& document, const std::string& source) {
  const PathFields check{source};
  if (!document.is_object()) check.fail("(document)", "expected a JSON object");
  for (const auto& item : document.items())
    if (item.key() != "format" && item.key() != "version" && item.key() != "frames")
      check.fail(item.key(), "unknown field (expected one of: format, frames, version)");
  if (!document.contains("format") || document["format"] != kCameraPathFormat)
    check.fail("format", std::string("expected \"") + kCameraPathFormat + "\"");
  if (!document.contains("version") || !document["version"].is_number_integer() ||
      document["version"].get<long long>() != kCameraPathVersion)
    check.fail("version", "expected " + std::to_string(kCameraPathVersion));
  if (!document.contains("frames") || !document["frames"].is_array() || document["frames"].empty())
    check.fail("frames", "expected an array of at least one frame");
  CameraPath path;
  const nlohmann::json& frames = document["frames"];
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const std::string field = "frames[" + std::to_string(i) + "]";
    path.frames.push_back(parseFrame(check, frames[i], field));
    if (i > 0 && path.frames[i].seconds < path.frames[i - 1].seconds)
      check.fail(field + ".seconds", "earlier than the frame before it");
  }
  return path;
}

CameraPath readCameraPath(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw FileError(path.string(), "cannot open the camera path");
  nlohmann::json document;
  try {
    document = nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& e) {
    throw FileError(path.string(), std::string("not valid JSON: ") + e.what());
  }
  return parseCameraPath(document, path.string());
}

}  // namespace cloudlut::scene
