#pragma once
// The grid of the sun optical-depth volume (shaders/sun_volume.glsl): columns along the sun,
// slices along one world axis, up to kSunCascadesMax nested cascades. Pure math, no GL: the
// renderer uploads the maps, the tests integrate the particles along the same columns.
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace cloudlut::render {

inline constexpr int kSunCascadesMax = 3;

struct SunVolumeGrid {
  int cascades = 1;
  glm::ivec3 dims{1};                    // columns Nu, Nv and slices Nw of every cascade
  glm::mat4 toGrid[kSunCascadesMax];     // world point → (u, v, w), node (i, j, k) at integers
  glm::mat4 toWorld[kSunCascadesMax];    // the inverse
  int sliceAxis = 1;                     // world axis of the slices (0 x, 1 y, 2 z)
  glm::vec3 sun{0.0f, 1.0f, 0.0f};       // unit, toward the sun, as the columns run
  float localCloud = 0.0f;               // window along the columns that holds one cloud (world
                                         // units: the clouds' depth; localCloudColumn)
};

// One cascade around an explicit particle scene: world bounds [lo, hi] (every particle's
// bounding sphere), slices along the world axis most aligned with the sun, columns `spacing`
// apart (world units) and slices `spacing · |l_axis|` apart, so that a step between slices is
// `spacing` long along the sun. At most maxColumns² columns and maxSlices + 1 slices: the
// spacing grows when the bounds need more.
SunVolumeGrid sunVolumeGridForBounds(const glm::vec3& lo, const glm::vec3& hi, const glm::vec3& sun, float spacing,
                                     int maxColumns = 256, int maxSlices = 128);

// Nested cascades around a camera for a cloud layer y ∈ [yLo, yHi] (world units): slices along
// y (`slices` + 1 of them, shared by the cascades), `columns`² columns per cascade, centred on the
// column through the eye. Cascade c's columns are spacing0 · ratio^c apart across the sun's beam:
// along the sun's azimuth they are that over |l_y| apart on the layer (a low sun's shadows are
// long, not wide). A sun within minElevation of the horizon is raised to it for the columns (the
// layer's shear stays finite).
SunVolumeGrid sunVolumeGridForLayer(const glm::vec3& eye, float yLo, float yHi, const glm::vec3& sun, float spacing0,
                                    int cascades, int columns = 256, int slices = 32, float ratio = 3.0f,
                                    float minElevation = 0.05f);

}  // namespace cloudlut::render
