#include "scene/Scene.h"

#include "scene/AtmosphereJson.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <set>
#include <utility>
#include <sstream>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "core/Errors.h"

namespace cloudlut::scene {

glm::mat3 Particle::toWorld() const {
  const glm::mat3 r = glm::mat3_cast(rotation);
  return glm::mat3(r[0] * radii.x, r[1] * radii.y, r[2] * radii.z) * glm::mat3_cast(noiseRotation);
}

glm::mat3 Particle::toParticle() const {
  // (R · D · Q)⁻¹ = Qᵀ · D⁻¹ · Rᵀ: row k of D⁻¹ · Rᵀ is column k of R divided by radii[k].
  const glm::mat3 rt = glm::transpose(glm::mat3_cast(rotation));
  glm::mat3 m;
  for (int c = 0; c < 3; ++c)
    m[c] = glm::vec3(rt[c].x / radii.x, rt[c].y / radii.y, rt[c].z / radii.z);
  return glm::transpose(glm::mat3_cast(noiseRotation)) * m;
}

glm::quat quatFromEulerDegrees(const glm::vec3& degrees) {
  const glm::vec3 r = glm::radians(degrees);
  const glm::quat qx = glm::angleAxis(r.x, glm::vec3(1, 0, 0));
  const glm::quat qy = glm::angleAxis(r.y, glm::vec3(0, 1, 0));
  const glm::quat qz = glm::angleAxis(r.z, glm::vec3(0, 0, 1));
  return glm::normalize(qz * qy * qx);
}

namespace {

// Field-level validation with messages of the form "<source>: <field>: <problem>".
class Validator {
 public:
  explicit Validator(std::string source) : source_(std::move(source)) {}
  const std::string& source() const { return source_; }

  [[noreturn]] void fail(const std::string& field, const std::string& problem) const {
    throw FileError(source_, field + ": " + problem);
  }

  void requireObject(const nlohmann::json& j, const std::string& field) const {
    if (!j.is_object()) fail(field, "expected a JSON object");
  }

  // Rejects keys not in `allowed` (catches typos such as "centre").
  void onlyKeys(const nlohmann::json& j, const std::string& field,
                const std::set<std::string>& allowed) const {
    for (const auto& item : j.items()) {
      if (allowed.count(item.key())) continue;
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      fail(field.empty() ? item.key() : field + "." + item.key(),
           "unknown field (expected one of: " + list + ")");
    }
  }

  float finiteNumber(const nlohmann::json& j, const std::string& field, const char* expected) const {
    if (!j.is_number()) fail(field, expected);
    const double v = j.get<double>();
    if (!std::isfinite(v) || std::abs(v) > 1e30) fail(field, expected);
    return static_cast<float>(v);
  }

  float positive(const nlohmann::json& j, const std::string& field) const {
    const float v = finiteNumber(j, field, "expected a positive number");
    if (!(v > 0.0f)) fail(field, "expected a positive number");
    return v;
  }

  glm::vec3 vec3(const nlohmann::json& j, const std::string& field) const {
    const char* expected = "expected 3 numbers";
    if (!j.is_array() || j.size() != 3) fail(field, expected);
    return {finiteNumber(j[0], field, expected), finiteNumber(j[1], field, expected),
            finiteNumber(j[2], field, expected)};
  }

  glm::vec3 color(const nlohmann::json& j, const std::string& field) const {
    const char* expected = "expected 3 non-negative numbers";
    if (!j.is_array() || j.size() != 3) fail(field, expected);
    glm::vec3 c;
    for (int k = 0; k < 3; ++k) {
      c[k] = finiteNumber(j[k], field, expected);
      if (c[k] < 0.0f) fail(field, expected);
    }
    return c;
  }

  glm::vec3 nonZeroVec3(const nlohmann::json& j, const std::string& field) const {
    const glm::vec3 v = vec3(j, field);
    if (!(glm::length(v) > 1e-12f)) fail(field, "expected 3 numbers, not all zero");
    return v;
  }

 private:
  std::string source_;
};

Particle parseParticle(const Validator& check, const nlohmann::json& j, const std::string& field) {
  check.requireObject(j, field);
  check.onlyKeys(j, field, {"center", "radii", "quaternion", "euler_deg", "noise_quaternion", "density"});
  Particle p;
  if (!j.contains("center")) check.fail(field + ".center", "missing (expected 3 numbers)");
  p.center = check.vec3(j["center"], field + ".center");
  if (!j.contains("radii")) check.fail(field + ".radii", "missing (expected 3 positive numbers or one positive number)");
  const nlohmann::json& r = j["radii"];
  const std::string rf = field + ".radii";
  const char* rExpected = "expected 3 positive numbers (or one positive number)";
  if (r.is_number()) {
    const float v = check.finiteNumber(r, rf, rExpected);
    if (!(v > 0.0f)) check.fail(rf, rExpected);
    p.radii = glm::vec3(v);
  } else {
    if (!r.is_array() || r.size() != 3) check.fail(rf, rExpected);
    for (int k = 0; k < 3; ++k) {
      p.radii[k] = check.finiteNumber(r[k], rf, rExpected);
      if (!(p.radii[k] > 0.0f)) check.fail(rf, rExpected);
    }
  }
  if (std::max({p.radii.x, p.radii.y, p.radii.z}) > 1e6f * std::min({p.radii.x, p.radii.y, p.radii.z}))
    check.fail(rf, "radii differ by more than a factor of 10^6");
  if (j.contains("quaternion") && j.contains("euler_deg"))
    check.fail(field, "give either \"quaternion\" or \"euler_deg\", not both");
  // A unit quaternion [w, x, y, z] (normalised) from the field `key`.
  const auto quaternion = [&](const char* key) {
    const std::string qf = field + "." + key;
    const char* qExpected = "expected 4 numbers [w, x, y, z], not all zero";
    const nlohmann::json& q = j[key];
    if (!q.is_array() || q.size() != 4) check.fail(qf, qExpected);
    glm::quat value;
    value.w = check.finiteNumber(q[0], qf, qExpected);
    value.x = check.finiteNumber(q[1], qf, qExpected);
    value.y = check.finiteNumber(q[2], qf, qExpected);
    value.z = check.finiteNumber(q[3], qf, qExpected);
    if (!(glm::length(value) > 1e-6f)) check.fail(qf, qExpected);
    return glm::normalize(value);
  };
  if (j.contains("quaternion")) {
    p.rotation = quaternion("quaternion");
  } else if (j.contains("euler_deg")) {
    p.rotation = quatFromEulerDegrees(check.vec3(j["euler_deg"], field + ".euler_deg"));
  }
  if (j.contains("noise_quaternion")) p.noiseRotation = quaternion("noise_quaternion");
  if (j.contains("density")) p.density = check.positive(j["density"], field + ".density");
  return p;
}

// "detail_noise": {"amplitude": a in [0, 1], "scale": s > 0 (world units), "seed": integer in [0, 2^24)}.
DetailNoise parseDetailNoise(const Validator& check, const nlohmann::json& j) {
  check.requireObject(j, "detail_noise");
  check.onlyKeys(j, "detail_noise", {"amplitude", "scale", "seed"});
  DetailNoise d;
  d.amplitude = kDefaultDetailAmplitude;
  const char* amplitude = "expected a number in [0, 1] (0 = off)";
  if (j.contains("amplitude")) d.amplitude = check.finiteNumber(j["amplitude"], "detail_noise.amplitude", amplitude);
  if (!(d.amplitude >= 0.0f && d.amplitude <= kMaxDetailAmplitude)) check.fail("detail_noise.amplitude", amplitude);
  if (!j.contains("scale")) check.fail("detail_noise.scale", "missing (expected the feature size in world units, > 0)");
  d.scale = check.positive(j["scale"], "detail_noise.scale");
  if (j.contains("seed")) {
    const char* seed = "expected an integer in [0, 16777215]";
    const float v = check.finiteNumber(j["seed"], "detail_noise.seed", seed);
    if (!(v >= 0.0f && v < static_cast<float>(kMaxDetailSeed)) || v != std::floor(v)) check.fail("detail_noise.seed", seed);
    d.seed = static_cast<int>(v);
  }
  return d;
}

}  // namespace

DetailNoise defaultDetailNoise(const std::vector<Particle>& particles) {
  double sum = 0;
  for (const Particle& p : particles) sum += std::max({p.radii.x, p.radii.y, p.radii.z});
  DetailNoise d;
  d.amplitude = kDefaultDetailAmplitude;
  d.scale = particles.empty() ? 1.0f
                              : kDefaultDetailScaleFraction * static_cast<float>(sum / static_cast<double>(particles.size()));
  return d;
}

glm::vec3 sunFromElevationAzimuth(float elevationDeg, float azimuthDeg) {
  const float e = glm::radians(elevationDeg), a = glm::radians(azimuthDeg);
  return {std::cos(e) * std::sin(a), std::sin(e), -std::cos(e) * std::cos(a)};
}

Scene parseScene(const nlohmann::json& document, const std::string& source) {
  const Validator check(source);
  if (!document.is_object()) check.fail("(document)", "expected a JSON object with a \"particles\" array");
  check.onlyKeys(document, "", {"description", "camera", "sun", "sky", "detail_noise", "particles"});
  Scene scene;
  if (document.contains("description") && !document["description"].is_string())
    check.fail("description", "expected a string");
  if (document.contains("camera")) {
    const nlohmann::json& c = document["camera"];
    check.requireObject(c, "camera");
    check.onlyKeys(c, "camera", {"eye", "target", "up", "fov_deg"});
    if (c.contains("eye")) scene.view.eye = check.vec3(c["eye"], "camera.eye");
    if (c.contains("target")) scene.view.target = check.vec3(c["target"], "camera.target");
    if (c.contains("up")) scene.view.up = check.nonZeroVec3(c["up"], "camera.up");
    if (c.contains("fov_deg")) {
      const float fov = check.finiteNumber(c["fov_deg"], "camera.fov_deg", "expected a number of degrees in (0, 179]");
      if (!(fov > 0.0f && fov <= 179.0f)) check.fail("camera.fov_deg", "expected a number of degrees in (0, 179]");
      scene.view.fovDeg = fov;
    }
  }
  if (document.contains("sun")) {
    const nlohmann::json& s = document["sun"];
    check.requireObject(s, "sun");
    check.onlyKeys(s, "sun", {"direction", "elevation_deg", "azimuth_deg", "color"});
    if (s.contains("direction")) scene.view.sunDirection = check.nonZeroVec3(s["direction"], "sun.direction");
    if (s.contains("elevation_deg") || s.contains("azimuth_deg")) {
      if (s.contains("direction")) check.fail("sun", "give either direction or elevation_deg and azimuth_deg, not both");
      if (!s.contains("elevation_deg")) check.fail("sun.elevation_deg", "missing (azimuth_deg needs it)");
      const float e = check.finiteNumber(s["elevation_deg"], "sun.elevation_deg", "expected degrees in [-90, 90]");
      if (!(e >= -90.0f && e <= 90.0f)) check.fail("sun.elevation_deg", "expected degrees in [-90, 90]");
      const float az = s.contains("azimuth_deg")
                           ? check.finiteNumber(s["azimuth_deg"], "sun.azimuth_deg", "expected a number of degrees")
                           : 0.0f;
      scene.view.sunDirection = sunFromElevationAzimuth(e, az);
    }
    if (s.contains("color")) scene.view.sunColor = check.color(s["color"], "sun.color");
  }
  if (document.contains("sky")) {
    const nlohmann::json& s = document["sky"];
    check.requireObject(s, "sky");
    if (s.contains("model") && !(s["model"] == "atmosphere" || s["model"] == "uniform"))
      check.fail("sky.model", "expected \"atmosphere\" or \"uniform\"");
    const bool atmosphere = s.value("model", std::string("uniform")) == "atmosphere";
    if (atmosphere) {
      check.onlyKeys(s, "sky", {"model", "color", "bottom_radius_m", "top_radius_m", "rayleigh_scattering_per_m",
                                "rayleigh_scale_height_m", "mie_scattering_per_m", "mie_absorption_per_m",
                                "mie_scale_height_m", "mie_g", "ozone_absorption_per_m", "ozone_bottom_m",
                                "ozone_peak_m", "ozone_top_m", "ground_albedo"});
      scene.view.atmosphereParameters = atmosphereFromJson(s, check.source(), "sky.");
    } else {
      check.onlyKeys(s, "sky", {"model", "color"});
    }
    if (s.contains("model")) scene.view.atmosphere = atmosphere;
    if (s.contains("color")) scene.view.skyColor = check.color(s["color"], "sky.color");
  }
  if (document.contains("detail_noise")) scene.detail = parseDetailNoise(check, document["detail_noise"]);
  if (!document.contains("particles")) check.fail("particles", "missing (expected an array of particles)");
  const nlohmann::json& ps = document["particles"];
  if (!ps.is_array()) check.fail("particles", "expected an array of particles");
  constexpr std::size_t kMaxParticles = 4u << 20;
  if (ps.size() > kMaxParticles)
    check.fail("particles", "more than " + std::to_string(kMaxParticles) + " particles");
  scene.particles.reserve(ps.size());
  for (std::size_t i = 0; i < ps.size(); ++i)
    scene.particles.push_back(parseParticle(check, ps[i], "particles[" + std::to_string(i) + "]"));
  return scene;
}

Scene readScene(const std::filesystem::path& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) throw FileError(path.string(), "missing (no such scene file)");
  if (std::filesystem::is_directory(status)) throw FileError(path.string(), "is a directory, not a scene file");
  if (!std::filesystem::is_regular_file(status))
    throw FileError(path.string(), "not a regular file (a scene is a JSON file)");
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  if (!in) throw FileError(path.string(), "cannot be read");
  const nlohmann::json document = nlohmann::json::parse(text.str(), nullptr, false);
  if (document.is_discarded()) throw FileError(path.string(), "invalid JSON");
  return parseScene(document, path.string());
}

void checkRenderParticleCount(std::size_t count, const std::string& source, std::size_t limit,
                              const std::string& method) {
  if (count > limit)
    throw UsageError(source + ": " + std::to_string(count) + " particles, more than the " + std::to_string(limit) +
                     " one render of --method " + method + " takes; split the scene");
}

View resolveView(const Scene& scene, const ViewSettings& commandLine) {
  const auto pick = [](const auto& cli, const auto& file, const auto& fallback) {
    return cli ? *cli : file ? *file : fallback;
  };
  View view;
  const ViewSettings& f = scene.view;
  view.camera.fovDeg = pick(commandLine.fovDeg, f.fovDeg, view.camera.fovDeg);
  if (!(view.camera.fovDeg > 0.0f && view.camera.fovDeg <= 179.0f))
    throw UsageError("--fov: expected degrees in (0, 179]");
  view.camera.up = pick(commandLine.up, f.up, view.camera.up);

  // Default framing: the bounding sphere of the particles.
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const Particle& p : scene.particles) {
    const float r = std::max({p.radii.x, p.radii.y, p.radii.z});
    lo = glm::min(lo, p.center - glm::vec3(r));
    hi = glm::max(hi, p.center + glm::vec3(r));
  }
  glm::vec3 centre(0.0f);
  float radius = 1.0f;
  if (!scene.particles.empty()) {
    centre = 0.5f * (lo + hi);
    radius = std::max(0.5f * glm::length(hi - lo), 1e-6f);
  }
  view.camera.target = pick(commandLine.target, f.target, centre);
  const float distance = 1.1f * radius / std::sin(0.5f * glm::radians(view.camera.fovDeg));
  view.camera.eye = pick(commandLine.eye, f.eye,
                         view.camera.target + distance * glm::normalize(glm::vec3(0.0f, 0.35f, 1.0f)));
  // In double: a float length overflows near 1e19 and underflows near 1e-19.
  const glm::dvec3 eye(view.camera.eye), target(view.camera.target), up(view.camera.up);
  for (const auto& [point, name] : {std::pair{eye, "eye"}, std::pair{target, "target (the particles' centre unless given)"}})
    if (!(glm::length(point) <= kMaxSceneDistance)) {
      char message[256];
      std::snprintf(message, sizeof message,
                    "camera: the %s lies %.3g m from the origin, more than %.0e m (the float range the renderers work "
                    "in; camera.eye/camera.target or --eye/--target)",
                    name, glm::length(point), kMaxSceneDistance);
      throw UsageError(message);
    }
  const double separation = glm::length(target - eye);
  if (!(separation <= kMaxSceneDistance)) {
    char message[224];
    std::snprintf(message, sizeof message,
                  "camera: eye and target are %.3g m apart, more than %.0e m (the float range the renderers work in; "
                  "camera.eye/camera.target or --eye/--target)",
                  separation, kMaxSceneDistance);
    throw UsageError(message);
  }
  const double scale = std::max(glm::length(eye), glm::length(target));
  if (!(separation > 1e-6 * scale) || !(separation > 1e-18))
    throw UsageError("camera: eye and target coincide (camera.eye/camera.target or --eye/--target)");
  const glm::dvec3 forward = (target - eye) / separation;
  if (!(glm::length(glm::cross(forward, glm::normalize(up))) > 1e-4))
    throw UsageError("camera: up is parallel to the view direction (camera.up or --up)");

  const glm::vec3 sun = pick(commandLine.sunDirection, f.sunDirection, glm::vec3(0.4f, 0.8f, 0.45f));
  if (!(glm::length(sun) > 1e-12f)) throw UsageError("--sun: the direction toward the sun must not be zero");
  view.lighting.sunDirection = glm::normalize(sun);
  view.lighting.sunColor = pick(commandLine.sunColor, f.sunColor, view.lighting.sunColor);
  view.lighting.skyColor = pick(commandLine.skyColor, f.skyColor, view.lighting.skyColor);
  view.lighting.skyBelow = glm::vec3(pick(commandLine.skyBelow, f.skyBelow, 1.0f));
  view.lighting.atmosphere = pick(commandLine.atmosphere, f.atmosphere, false);
  view.lighting.atmosphereParameters =
      pick(commandLine.atmosphereParameters, f.atmosphereParameters, glsl::defaultAtmosphere());
  if (view.lighting.atmosphere && !(eye.y >= 0.0))
    throw UsageError("camera: the eye lies underground (y < 0) under the atmosphere's sky (camera.eye or --eye)");
  return view;
}

CameraFrame::CameraFrame(const Camera& camera, int width, int height)
    : eye_(camera.eye),
      forward_(glm::normalize(camera.target - camera.eye)),
      right_(glm::normalize(glm::cross(forward_, camera.up))),
      up_(glm::cross(right_, forward_)),
      tanHalfFov_(std::tan(0.5f * glm::radians(camera.fovDeg))),
      aspect_(static_cast<float>(width) / static_cast<float>(height)),
      width_(width),
      height_(height) {}

glm::vec3 CameraFrame::rayDirection(float px, float py) const {
  const float x = (2.0f * px / static_cast<float>(width_) - 1.0f) * tanHalfFov_ * aspect_;
  const float y = (1.0f - 2.0f * py / static_cast<float>(height_)) * tanHalfFov_;
  return glm::normalize(forward_ + x * right_ + y * up_);
}

glm::vec3 CameraFrame::toCamera(const glm::vec3& p) const {
  const glm::vec3 q = p - eye_;
  return {glm::dot(q, right_), glm::dot(q, up_), glm::dot(q, forward_)};
}

glm::vec2 CameraFrame::imagePoint(float tx, float ty) const {
  return {(tx / (tanHalfFov_ * aspect_) + 1.0f) * 0.5f * static_cast<float>(width_),
          (1.0f - ty / tanHalfFov_) * 0.5f * static_cast<float>(height_)};
}

glm::mat4 CameraFrame::viewMatrix() const { return glm::lookAt(eye_, eye_ + forward_, up_); }

glm::mat4 CameraFrame::projectionMatrix(float nearPlane, float farPlane) const {
  return glm::perspective(2.0f * std::atan(tanHalfFov_), aspect_, nearPlane, farPlane);
}

}  // namespace cloudlut::scene
