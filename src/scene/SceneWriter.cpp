#include "scene/SceneWriter.h"

#include <glm/gtc/quaternion.hpp>

namespace cloudlut::scene {

namespace {

nlohmann::json triple(const glm::vec3& v) { return nlohmann::json::array({v.x, v.y, v.z}); }
nlohmann::json quaternion(const glm::quat& q) { return nlohmann::json::array({q.w, q.x, q.y, q.z}); }
bool identity(const glm::quat& q) { return q.w == 1.0f && q.x == 0.0f && q.y == 0.0f && q.z == 0.0f; }

}  // namespace

nlohmann::json sceneDocument(const std::vector<Particle>& particles, const View& view, const std::string& description,
                             const DetailNoise& detail) {
  nlohmann::json doc = nlohmann::json::object();
  doc["description"] = description;
  doc["camera"] = {{"eye", triple(view.camera.eye)},
                   {"target", triple(view.camera.target)},
                   {"up", triple(view.camera.up)},
                   {"fov_deg", view.camera.fovDeg}};
  doc["sun"] = {{"direction", triple(view.lighting.sunDirection)}, {"color", triple(view.lighting.sunColor)}};
  doc["sky"] = {{"color", triple(view.lighting.skyColor)}};
  if (detail.enabled())
    doc["detail_noise"] = {{"amplitude", detail.amplitude}, {"scale", detail.scale}, {"seed", detail.seed}};
  nlohmann::json list = nlohmann::json::array();
  for (const Particle& p : particles) {
    nlohmann::json j = {{"center", triple(p.center)}, {"radii", triple(p.radii)}, {"density", p.density}};
    if (!identity(p.rotation)) j["quaternion"] = quaternion(p.rotation);
    if (!identity(p.noiseRotation)) j["noise_quaternion"] = quaternion(p.noiseRotation);
    list.push_back(std::move(j));
  }
  doc["particles"] = std::move(list);
  return doc;
}

std::string sceneText(const nlohmann::json& document) {
  // nlohmann writes floats with the shortest representation that reads back the same double;
  // the values are floats widened to double, so they read back exactly.
  std::string out = "{\n";
  bool first = true;
  for (const auto& item : document.items()) {
    if (item.key() == "particles") continue;
    out += (first ? "  " : ",\n  ") + nlohmann::json(item.key()).dump() + ": " + item.value().dump();
    first = false;
  }
  out += std::string(first ? "  " : ",\n  ") + "\"particles\": [";
  const nlohmann::json& list = document.at("particles");
  for (std::size_t i = 0; i < list.size(); ++i) out += (i ? ",\n    " : "\n    ") + list[i].dump();
  out += list.empty() ? "]\n}\n" : "\n  ]\n}\n";
  return out;
}

}  // namespace cloudlut::scene
