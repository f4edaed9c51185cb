#pragma once
// Procedural cloudscapes (seed §5.2): a cloud-type preset (data/presets/*.json, embedded in the
// binary) and a quality preset (the seed's Table 1) define a camera-centred clipmap grid of
// particles. The GPU generates them (Renderer::renderCloudscape); generateCloudscapeCpu is the
// reference with the same functions (scene/glsl/cloudscape_grid.glsl compiled as C++).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <nlohmann/json.hpp>

#include "core/Defaults.h"
#include "scene/Scene.h"

namespace cloudlut::scene {

// Ring dimension² × rings × layers (seed Table 1: low 104²×4×2, medium 136²×4×4, high 184²×4×6).
struct QualityPreset {
  std::string name;
  int ringDim = 104;
  int rings = 4;
  int layers = 2;
  long long maxParticles() const { return static_cast<long long>(ringDim) * ringDim * rings * layers; }
  long long cellCount() const { return static_cast<long long>(ringDim) * ringDim * rings; }
};
// "low", "medium", "high"; UsageError otherwise.
QualityPreset qualityPreset(const std::string& name);
const std::vector<std::string>& qualityPresetNames();

// A cloud type (docs/SCENE_FORMAT.md, "Cloudscape presets").
struct CloudType {
  std::string description;
  float coverage = 0.38f;        // share of the sky with clouds, [0, 1]
  float density = 1.0f;          // density scale of a full particle of reference size
  float cloudBase = 1200.0f;     // m
  float cloudTop = 2400.0f;      // m
  glm::vec2 particleSize{0.75f, 1.15f};  // particle radius / cell size, min and max
  float verticalAspect = 0.8f;   // vertical / horizontal radius (at least 0.6 × layer spacing)
  float noiseScale = 5000.0f;    // m, feature size of the coverage noise
  float cellSize = static_cast<float>(defaults::kCloudscapeCellMetres);  // m, ring-0 cell
  float jitter = 0.8f;           // random displacement, fraction of a cell
  float visibility = 40000.0f;   // m, far plane: no particle beyond it
  float fadeFraction = 0.25f;    // share of a ring over which it cross-fades with the next
  float heightProfile = 1.0f;    // column height = amount^p: p < 1 flat-topped sheets, 1 domed heaps
  float topTaper = 0.3f;         // the top particle of a column is this much smaller than the bottom one
  float edgeDensity = 0.35f;     // density at a cloud's edge relative to its core
  int seed = 1;
};

struct CloudscapeScene {
  std::string name;  // preset name or file
  CloudType cloud;
  ViewSettings view;
  std::optional<DetailNoise> detail;  // "detail_noise", as in a particle scene (world units: m)
};

// Parses a cloudscape document (`source` names it in errors: FileError "<source>: <field>: ...").
CloudscapeScene parseCloudscape(const nlohmann::json& document, const std::string& source);
// The embedded preset NAME (data/presets/NAME.json), or else the file at that path; a name that
// is neither is a UsageError naming `option` and listing the presets.
CloudscapeScene loadCloudscape(const std::string& nameOrPath, const std::string& option = "--scene");
const std::vector<std::string>& cloudscapePresetNames();
inline constexpr const char* kDefaultCloudscape = "fair_weather_cumulus";
// True when the JSON document is a cloudscape (no "particles" array).
bool isCloudscapeDocument(const nlohmann::json& document);

// Grid parameters as the shader takes them (cloudscape_grid.glsl: g0 … g4). `referenceRadius` is
// the radius R (m) of the tables' reference particle (their radius_m): a particle of world radius
// r gets ρ ∝ r₀/R (r₀ its ring-0 radius) so that it is drawn with the optical depth it models.
struct GridParameters {
  glm::vec4 g0, g1, g2, g3, g4;
};
GridParameters gridParameters(const CloudType& cloud, const QualityPreset& quality,
                              float referenceRadius = static_cast<float>(defaults::kParticleRadiusMetres));

// The far distance that is modelled: the visibility, or less when the outer ring ends sooner.
float modelledFarDistance(const CloudType& cloud, const QualityPreset& quality);

// Range of the particles' density scales ρ this cloudscape can produce for tables of reference
// radius R (for bake --for-scene): the tables' density axis should cover it. Particles whose
// level-of-detail weight times their cell's mass factor (GridParticle::fill) is below 1/16 are not
// counted: they are nearly transparent, and the renderer shades densities below the axis linearly.
glm::vec2 cloudscapeDensityRange(const CloudType& cloud, const QualityPreset& quality,
                                 float referenceRadius = static_cast<float>(defaults::kParticleRadiusMetres));

// Frustum planes (dot(n, p) + w ≥ 0 inside: left, right, bottom, top, near) of a camera.
struct Frustum {
  glm::vec4 planes[5];
};
Frustum cameraFrustum(const Camera& camera, int width, int height);

// A generated particle with its grid identity.
struct GridParticle {
  Particle particle;
  int ring = 0, cellX = 0, cellZ = 0, layer = 0;
  float weight = 1.0f;  // level-of-detail fade
  float fill = 1.0f;    // its cell's mass factor f (cloudscape_grid.glsl, cgCellCloud): 1 in ring 0
};

struct CpuGeneration {
  std::vector<GridParticle> particles;
  std::size_t validCells = 0;  // non-empty cells within the far distance
  std::size_t lit = 0;         // particles within the far distance: those the light-space passes take
};
// CPU reference of the GPU generation: the same cells (every non-empty one within the far
// distance), the same particles drawn (those in the frustum, any order), the same `lit`.
CpuGeneration generateCloudscapeCpu(const CloudType& cloud, const QualityPreset& quality, const Camera& camera,
                                    int width, int height,
                                    float referenceRadius = static_cast<float>(defaults::kParticleRadiusMetres));
// Every particle the grid generates around the eye within the modelled far distance, before any
// frustum culling (the level-of-detail weight folded into the density, as drawn).
CpuGeneration generateCloudscapeAround(const CloudType& cloud, const QualityPreset& quality, const glm::vec3& eye,
                                       float referenceRadius = static_cast<float>(defaults::kParticleRadiusMetres));

// The camera of frame `frame` on the simple path of `--frames`: forward along the horizontal
// view direction at `speed` m per frame, turning by `yawDegPerFrame`.
Camera cameraOnPath(const Camera& start, int frame, float speed, float yawDegPerFrame);

}  // namespace cloudlut::scene
