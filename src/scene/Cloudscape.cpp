#include "scene/Cloudscape.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "core/Defaults.h"
#include "core/Errors.h"
#include "scene/CloudscapeGrid.h"
#include "scene/EmbeddedPresets.h"

namespace cloudlut::scene {

namespace {

[[noreturn]] void fail(const std::string& source, const std::string& field, const std::string& problem) {
  throw FileError(source, field + ": " + problem);
}

float number(const nlohmann::json& doc, const std::string& source, const char* field, float lo, float hi,
             float fallback, bool required = false) {
  const std::string range = "expected a number in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  if (!doc.contains(field)) {
    if (required) fail(source, field, "missing (" + range + ")");
    return fallback;
  }
  const nlohmann::json& j = doc[field];
  if (!j.is_number()) fail(source, field, range);
  const double v = j.get<double>();
  if (!std::isfinite(v) || v < lo || v > hi) fail(source, field, range + ", got " + j.dump());
  return static_cast<float>(v);
}

}  // namespace

const std::vector<std::string>& qualityPresetNames() {
  static const std::vector<std::string> names{"low", "medium", "high"};
  return names;
}

QualityPreset qualityPreset(const std::string& name) {
  if (name == "low") return {"low", 104, 4, 2};
  if (name == "medium") return {"medium", 136, 4, 4};
  if (name == "high") return {"high", 184, 4, 6};
  throw UsageError("--quality: unknown quality preset '" + name + "' (low, medium, high)");
}

const std::vector<std::string>& cloudscapePresetNames() {
  static const std::vector<std::string> names{"cumulus_congestus", "fair_weather_cumulus", "overcast",
                                              "stratocumulus", "towering_cumulus_sunset"};
  return names;
}

bool isCloudscapeDocument(const nlohmann::json& document) {
  return document.is_object() && !document.contains("particles");
}

CloudscapeScene parseCloudscape(const nlohmann::json& doc, const std::string& source) {
  if (!doc.is_object()) fail(source, "(document)", "expected a JSON object");
  static const std::set<std::string> allowed{"description", "coverage", "density", "cloud_base_m", "cloud_top_m",
                                             "particle_size", "vertical_aspect", "noise_scale_m", "cell_size_m",
                                             "jitter", "visibility_m", "fade_fraction", "height_profile", "top_taper",
                                             "edge_density", "seed", "camera", "sun", "sky", "detail_noise"};
  for (const auto& item : doc.items())
    if (!allowed.count(item.key())) {
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      fail(source, item.key(), "unknown field (expected one of: " + list + ")");
    }
  CloudscapeScene scene;
  scene.name = source;
  CloudType& c = scene.cloud;
  if (doc.contains("description")) {
    if (!doc["description"].is_string()) fail(source, "description", "expected a string");
    c.description = doc["description"].get<std::string>();
  }
  c.coverage = number(doc, source, "coverage", 0.0f, 1.0f, c.coverage, true);
  c.density = number(doc, source, "density", 1e-3f, 100.0f, c.density, true);
  c.cloudBase = number(doc, source, "cloud_base_m", -1e4f, 2e4f, c.cloudBase, true);
  c.cloudTop = number(doc, source, "cloud_top_m", -1e4f, 2e4f, c.cloudTop, true);
  if (!(c.cloudTop > c.cloudBase)) fail(source, "cloud_top_m", "must be above cloud_base_m");
  if (doc.contains("particle_size")) {
    const nlohmann::json& s = doc["particle_size"];
    const char* expected = "expected [min, max], 0.05 <= min <= max <= 4 (radius / cell size)";
    if (!s.is_array() || s.size() != 2 || !s[0].is_number() || !s[1].is_number())
      fail(source, "particle_size", expected);
    c.particleSize = {s[0].get<float>(), s[1].get<float>()};
    if (!(c.particleSize.x >= 0.05f && c.particleSize.x <= c.particleSize.y && c.particleSize.y <= 4.0f))
      fail(source, "particle_size", expected);
  }
  c.verticalAspect = number(doc, source, "vertical_aspect", 0.05f, 4.0f, c.verticalAspect);
  c.noiseScale = number(doc, source, "noise_scale_m", 1.0f, 1e7f, c.noiseScale);
  c.cellSize = number(doc, source, "cell_size_m", 1.0f, 1e5f, c.cellSize);
  c.jitter = number(doc, source, "jitter", 0.0f, 1.0f, c.jitter);
  c.visibility = number(doc, source, "visibility_m", 10.0f, 1e7f, c.visibility);
  c.fadeFraction = number(doc, source, "fade_fraction", 0.01f, 0.9f, c.fadeFraction);
  c.heightProfile = number(doc, source, "height_profile", 0.05f, 4.0f, c.heightProfile);
  c.topTaper = number(doc, source, "top_taper", 0.0f, 0.9f, c.topTaper);
  c.edgeDensity = number(doc, source, "edge_density", 0.01f, 1.0f, c.edgeDensity);
  c.seed = static_cast<int>(number(doc, source, "seed", 0.0f, 1e6f, static_cast<float>(c.seed)));
  // Camera, sun and sky: the scene format's fields, validated by its parser.
  nlohmann::json view = nlohmann::json::object();
  for (const char* key : {"camera", "sun", "sky", "detail_noise"})
    if (doc.contains(key)) view[key] = doc[key];
  view["particles"] = nlohmann::json::array();
  const Scene parsed = parseScene(view, source);
  scene.view = parsed.view;
  scene.detail = parsed.detail;
  return scene;
}

CloudscapeScene loadCloudscape(const std::string& nameOrPath, const std::string& option) {
  const auto& names = cloudscapePresetNames();
  if (std::find(names.begin(), names.end(), nameOrPath) != names.end()) {
    const std::string file = nameOrPath + ".json";
    const char* text = nullptr;
    for (const auto& f : embedded::kEmbeddedFiles)
      if (file == f.name) text = f.text;
    if (!text) throw std::logic_error("preset " + file + " was not embedded in this build");
    const nlohmann::json doc = nlohmann::json::parse(text);
    CloudscapeScene s = parseCloudscape(doc, "preset " + nameOrPath);
    s.name = nameOrPath;
    return s;
  }
  std::error_code ec;
  if (!std::filesystem::is_regular_file(nameOrPath, ec)) {
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    throw UsageError(option + ": '" + nameOrPath + "' is neither a cloudscape preset (" + list + ") nor a file");
  }
  std::ifstream in(nameOrPath, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  const nlohmann::json doc = nlohmann::json::parse(text.str(), nullptr, false);
  if (doc.is_discarded()) throw FileError(nameOrPath, "invalid JSON");
  return parseCloudscape(doc, nameOrPath);
}

GridParameters gridParameters(const CloudType& c, const QualityPreset& q, float referenceRadius) {
  GridParameters p;
  p.g0 = {c.cellSize, static_cast<float>(q.ringDim), static_cast<float>(q.rings), static_cast<float>(q.layers)};
  p.g1 = {c.coverage, c.density, c.cloudBase, c.cloudTop};
  p.g2 = {c.particleSize.x, c.particleSize.y, c.verticalAspect, c.noiseScale};
  p.g3 = {c.jitter, modelledFarDistance(c, q), static_cast<float>(c.seed), c.fadeFraction};
  p.g4 = {referenceRadius, c.heightProfile, c.topTaper, c.edgeDensity};
  return p;
}

float modelledFarDistance(const CloudType& c, const QualityPreset& q) {
  // The outer ring is complete up to (ringDim/2 − 1) of its cells from the camera.
  const float outer = (0.5f * static_cast<float>(q.ringDim) - 1.0f) * c.cellSize * std::exp2(static_cast<float>(q.rings - 1));
  return std::min(c.visibility, outer);
}

glm::vec2 cloudscapeDensityRange(const CloudType& c, const QualityPreset& q, float referenceRadius) {
  // ρ = density · ramp(amount) · f · cell₀ · rel / R · weight (cloudscape_grid.glsl, cgParticle) with
  // rel = size · taper · mix(0.7, 1, amount), the same in every ring (mass conservation), and the
  // cell's mass factor f ≤ 1 / (ramp · mix(0.7, 1, amount)) (cgCellCloud): at most a full core's ρ.
  // The lower end holds for f · weight ≥ 1/16.
  (void)q;
  const float relMin = c.particleSize.x * (1.0f - c.topTaper) * 0.7f;
  const float relMax = c.particleSize.y;
  const float R = referenceRadius;
  return {c.density * c.edgeDensity * c.cellSize * relMin / R / 16.0f, c.density * c.cellSize * relMax / R};
}

Frustum cameraFrustum(const Camera& camera, int width, int height) {
  const CameraFrame frame(camera, width, height);
  const glm::vec3 eye = frame.eye(), f = frame.forward();
  // Corner rays: the four side planes pass through the eye and two adjacent corners.
  const glm::vec3 tl = frame.rayDirection(0, 0), tr = frame.rayDirection(static_cast<float>(width), 0);
  const glm::vec3 bl = frame.rayDirection(0, static_cast<float>(height));
  const glm::vec3 br = frame.rayDirection(static_cast<float>(width), static_cast<float>(height));
  auto plane = [&](const glm::vec3& a, const glm::vec3& b) {
    glm::vec3 n = glm::normalize(glm::cross(a, b));
    if (glm::dot(n, f) < 0.0f) n = -n;
    return glm::vec4(n, -glm::dot(n, eye));
  };
  Frustum fr;
  fr.planes[0] = plane(tl, bl);
  fr.planes[1] = plane(tr, br);
  fr.planes[2] = plane(bl, br);
  fr.planes[3] = plane(tl, tr);
  fr.planes[4] = glm::vec4(f, -glm::dot(f, eye));
  return fr;
}

namespace {

// The grid's particles around `eye` within the far distance; with a frustum, only the particles in
// it (the cells listed are every non-empty one within the far distance, as on the GPU, and `lit`
// counts every particle within it, the light-space passes' set).
CpuGeneration generate(const CloudType& cloud, const QualityPreset& q, const glm::vec3& eye, const Frustum* fr,
                       float referenceRadius) {
  const GridParameters g = gridParameters(cloud, q, referenceRadius);
  const glm::vec2 camXZ(eye.x, eye.z);
  // No frustum: planes every point is inside (0 · p + 1 ≥ 0).
  Frustum all;
  for (glm::vec4& p : all.planes) p = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  const Frustum& f = fr ? *fr : all;
  CpuGeneration out;
  for (int ring = 0; ring < q.rings; ++ring) {
    const glm::ivec2 origin = grid::cgRingOrigin(camXZ, ring, g.g0);
    for (int j = 0; j < q.ringDim; ++j)
      for (int i = 0; i < q.ringDim; ++i) {
        const int ix = origin.x + i, iz = origin.y + j;
        const glm::vec2 centre = grid::cgCellCentre(ring, ix, iz, g.g0);
        const glm::vec2 delta = glm::abs(centre - camXZ);
        const float w = grid::cgRingWeight(ring, std::max(delta.x, delta.y), g.g0, g.g3);
        if (!(w > 0.0f)) continue;
        const glm::vec4 b = grid::cgCellBound(ring, ix, iz, g.g0, g.g1, g.g2, g.g3);
        if (!grid::cgWithinFar(glm::vec3(b), b.w, eye, g.g3.y)) continue;
        const glm::vec2 cellCloud = grid::cgCellCloud(ring, ix, iz, g.g0, g.g1, g.g2, g.g3, g.g4);
        const int layers = grid::cgLayerCount(cellCloud.x, g.g0, g.g4);
        if (layers < 1) continue;
        ++out.validCells;
        for (int k = 0; k < layers; ++k) {
          const grid::CgParticle p =
              grid::cgParticle(ring, ix, iz, k, cellCloud.x, cellCloud.y, w, g.g0, g.g1, g.g2, g.g3, g.g4);
          const float reach = std::max(p.radii.x, p.radii.y);
          if (!grid::cgWithinFar(p.centre, 0.0f, eye, g.g3.y)) continue;
          ++out.lit;
          if (!grid::cgVisible(p.centre, reach, eye, g.g3.y, f.planes[0], f.planes[1], f.planes[2], f.planes[3],
                               f.planes[4]))
            continue;
          GridParticle gp;
          gp.particle.center = p.centre;
          gp.particle.radii = p.radii;
          gp.particle.noiseRotation = glm::quat(p.noise.w, p.noise.x, p.noise.y, p.noise.z);
          gp.particle.density = p.density;
          gp.ring = ring;
          gp.cellX = ix;
          gp.cellZ = iz;
          gp.layer = k;
          gp.weight = p.weight;
          gp.fill = cellCloud.y;
          out.particles.push_back(gp);
        }
      }
  }
  return out;
}

}  // namespace

CpuGeneration generateCloudscapeCpu(const CloudType& cloud, const QualityPreset& q, const Camera& camera,
                                    int width, int height, float referenceRadius) {
  const Frustum fr = cameraFrustum(camera, width, height);
  return generate(cloud, q, camera.eye, &fr, referenceRadius);
}

CpuGeneration generateCloudscapeAround(const CloudType& cloud, const QualityPreset& q, const glm::vec3& eye,
                                       float referenceRadius) {
  return generate(cloud, q, eye, nullptr, referenceRadius);
}

Camera cameraOnPath(const Camera& start, int frame, float speed, float yawDegPerFrame) {
  Camera c = start;
  const glm::vec3 dir = start.target - start.eye;
  glm::vec3 flat(dir.x, 0.0f, dir.z);
  if (glm::length(flat) < 1e-6f) flat = glm::vec3(0.0f, 0.0f, -1.0f);
  flat = glm::normalize(flat);
  const float f = static_cast<float>(frame);
  c.eye = start.eye + flat * (speed * f);
  const glm::quat yaw = glm::angleAxis(glm::radians(yawDegPerFrame * f), glm::vec3(0.0f, 1.0f, 0.0f));
  c.target = c.eye + yaw * dir;
  return c;
}

}  // namespace cloudlut::scene
