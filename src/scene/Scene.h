#pragma once
// A particle scene: ellipsoidal particles plus, optionally, the camera and the light.
// The JSON schema is specified in docs/SCENE_FORMAT.md; readScene validates every field and
// throws cloudlut::FileError whose message names the file and the offending field, e.g.
// "scene.json: particles[3].radii: expected 3 positive numbers (or one positive number)".
//
// World space is right-handed with +y up (unless camera.up says otherwise); lengths are in any
// unit as long as all of them use the same one.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "core/DetailNoise.h"
#include "core/Glsl.h"

namespace cloudlut::scene {

// One particle: the unit sphere mapped to the world by x = center + R · diag(radii) · Q · p. Q
// turns the reference particle (its density noise) inside the ellipsoid before it is scaled; R
// turns the ellipsoid (docs/SCENE_FORMAT.md).
struct Particle {
  glm::vec3 center{0.0f};
  glm::vec3 radii{1.0f};                         // semi-axes along the particle's own x, y, z
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};    // R, unit quaternion (w, x, y, z)
  float density = 1.0f;                          // density scale ρ (dimensionless)
  glm::quat noiseRotation{1.0f, 0.0f, 0.0f, 0.0f};  // Q, unit quaternion (w, x, y, z)

  // World ← particle (unit sphere) linear part R · diag(radii) · Q, and its inverse.
  glm::mat3 toWorld() const;
  glm::mat3 toParticle() const;
};

// Quaternion of the Euler angles (degrees) applied about x first, then y, then z (fixed axes):
// R = Rz · Ry · Rx.
glm::quat quatFromEulerDegrees(const glm::vec3& degrees);

// The camera and light fields a scene file or the command line may set; unset fields fall
// back on the scene file, then on the defaults (see resolveView).
struct ViewSettings {
  std::optional<glm::vec3> eye, target, up;
  std::optional<float> fovDeg;                   // vertical field of view, degrees
  std::optional<glm::vec3> sunDirection;         // toward the sun (normalised on use)
  std::optional<glm::vec3> sunColor, skyColor;
  std::optional<float> skyBelow;                 // Lighting::skyBelow, the same in every channel
  // "sky": {"model": "atmosphere", ...}: the precomputed atmosphere and its parameters
  // (scene/AtmosphereJson.h) instead of the uniform sky colour.
  std::optional<bool> atmosphere;
  std::optional<glsl::AtmosphereParameters> atmosphereParameters;
};

struct Scene {
  std::vector<Particle> particles;
  ViewSettings view;
  // "detail_noise": the density's detail noise (core/DetailNoise.h); absent: none unless asked
  // for on the command line (defaultDetailNoise).
  std::optional<DetailNoise> detail;
};

// The detail noise `--detail-noise on` gives a scene without a "detail_noise" field: amplitude
// kDefaultDetailAmplitude, feature size kDefaultDetailScaleFraction times the particles' mean
// largest semi-axis (world units; 1 without particles).
inline constexpr float kDefaultDetailAmplitude = 0.6f;
inline constexpr float kDefaultDetailScaleFraction = 0.3f;
DetailNoise defaultDetailNoise(const std::vector<Particle>& particles);

// The unit direction toward a sun at `elevationDeg` above the horizon and `azimuthDeg` from −z
// (the default view direction) toward +x, degrees (docs/SCENE_FORMAT.md).
glm::vec3 sunFromElevationAzimuth(float elevationDeg, float azimuthDeg);

// Parses and validates a scene document; `source` names it in error messages.
Scene parseScene(const nlohmann::json& document, const std::string& source);

// Reads and validates a scene file (FileError when missing, not JSON, or malformed).
Scene readScene(const std::filesystem::path& path);

struct Camera {
  glm::vec3 eye{0.0f, 0.0f, 5.0f};
  glm::vec3 target{0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float fovDeg = 45.0f;
};

struct Lighting {
  glm::vec3 sunDirection{0.0f, 1.0f, 0.0f};  // unit, toward the sun
  glm::vec3 sunColor{1.0f};                  // sun irradiance per channel
  glm::vec3 skyColor{0.05f, 0.08f, 0.15f};   // sky radiance per channel (ambient and background)
  // Radiance of the sky below the horizon (directions with y < 0: what the ground returns) per
  // channel, as a fraction of skyColor: 1 is the uniform sky (the default), less a sky from above
  // (--sky-below; the atmosphere sets the ground albedo, render/SkyPass.h). The cloud lighting's
  // ambient and the path tracer take it; the background is skyColor.
  glm::vec3 skyBelow{1.0f};
  // The sky model: a uniform sky of skyColor, or the atmosphere (then the sun colour is the
  // sunlight above the atmosphere and skyColor is not used; render/SkyPass.h).
  bool atmosphere = false;
  glsl::AtmosphereParameters atmosphereParameters = glsl::defaultAtmosphere();
};

struct View {
  Camera camera;
  Lighting lighting;
};

// The most particles one render takes. The particle method (`cloudlut render`): 2^20, what one
// storage block of llvmpipe (128 MiB) holds of the 112-byte GPU records (1 198 372), rounded down
// to a power of two; its passes grow about as N (1e6 particles: occlusion ≈ 5 s at 640×360,
// docs/BENCHMARKS.md). The ray marcher (`--method raymarch`) tests every particle at every pixel
// (time ∝ pixels · N): 2^18.
inline constexpr std::size_t kMaxRenderParticles = std::size_t(1) << 20;
inline constexpr std::size_t kMaxRayMarchParticles = std::size_t(1) << 18;
// UsageError naming `source` when `count` exceeds `limit` (kMaxRenderParticles or
// kMaxRayMarchParticles; `method` names it in the message).
void checkRenderParticleCount(std::size_t count, const std::string& source, std::size_t limit = kMaxRenderParticles,
                              const std::string& method = "particles");

// The largest eye–target distance, and distance of the eye and the target from the origin, m: the renderers
// work in float (a 24-bit mantissa leaves 60 m steps at 1e9 m).
inline constexpr double kMaxSceneDistance = 1e9;

// Defaults ← scene file ← command line, field by field. Without an eye or target the camera
// frames the particles' bounding sphere (target at its centre, eye above and behind it, on
// +z). Throws UsageError for an unusable combination (eye = target relative to their magnitude,
// eye or target farther than kMaxSceneDistance from the origin or from each other, up parallel to the view direction, zero
// sun direction); the checks run in double, so no overflow is mistaken for one of them.
View resolveView(const Scene& scene, const ViewSettings& commandLine);

// The pinhole camera of an image: ray directions and the matching OpenGL matrices.
// Pixel (x, y) counts from the top-left corner; its centre is (x + 0.5, y + 0.5).
class CameraFrame {
 public:
  CameraFrame(const Camera& camera, int width, int height);
  const glm::vec3& eye() const { return eye_; }
  glm::vec3 forward() const { return forward_; }
  // Unit direction of the ray through the image point (px, py) in pixel units.
  glm::vec3 rayDirection(float px, float py) const;
  // The world point p in the camera's frame: x right, y up, z along the view (world units).
  glm::vec3 toCamera(const glm::vec3& p) const;
  // The image point (pixel units, as rayDirection takes them) of the camera-frame direction
  // (tx, ty, 1): rayDirection's inverse for a point at tx = x/z, ty = y/z.
  glm::vec2 imagePoint(float tx, float ty) const;
  int width() const { return width_; }
  int height() const { return height_; }
  glm::mat4 viewMatrix() const;
  glm::mat4 projectionMatrix(float nearPlane, float farPlane) const;

 private:
  glm::vec3 eye_, forward_, right_, up_;
  float tanHalfFov_, aspect_;
  int width_, height_;
};

}  // namespace cloudlut::scene
