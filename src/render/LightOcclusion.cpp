#include "render/LightOcclusion.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "render/ShaderSources.h"

namespace cloudlut::render {

namespace {

constexpr GLuint kTilesBinding = 3;
constexpr GLuint kRawSunlightBinding = 4;
constexpr GLuint kNodesBinding = 7;
// The tile buffer (occlusion.comp.glsl, block Tiles): ordered-int bounds (4 ints), node count,
// capacity, overflow and a pad word, then one list head per tile; the (particle, next) nodes are
// a buffer of their own (block TileNodes).
constexpr std::size_t kTileCountersBytes = 32;
constexpr std::size_t kTileNodeBytes = 8;
constexpr std::size_t kNodeOverflowOffset = 24;  // word 6 (after the node count and capacity)
// Tile-list nodes per particle reserved (a particle covers a few tiles), and the least pool.
constexpr std::size_t kNodesPerParticle = 16;
constexpr std::size_t kMinNodes = std::size_t{1} << 18;

}  // namespace

int lightTilesFor(std::size_t count) {
  const double side = std::ceil(std::sqrt(static_cast<double>(count) / kParticlesPerLightTile));
  return static_cast<int>(std::clamp(side, static_cast<double>(kLightTiles), static_cast<double>(kMaxLightTiles)));
}

LightOcclusion::LightOcclusion(const GlFunctions& gl, const StorageBudget& budget, ParticleBuffers& buffers)
    : gl_(gl), budget_(budget), buffers_(buffers), tiles_(gl), nodes_(gl), rawSunlight_(gl) {
  const std::string common = glslDefine("GROUP_SIZE", kGroupSize);
  for (int stage = 0; stage < 4; ++stage) {
    stages_[stage] =
        linkComputeProgram(gl, {"particle_common.glsl", "occlusion.comp.glsl"}, common + glslDefine("STAGE", stage));
    requireParticleRecordLayout(gl, stages_[stage].id(), "occlusion.comp.glsl");
  }
}

std::size_t LightOcclusion::run(std::size_t count, const RenderSettings& s, float unitOpticalRadius, bool countOverflow) {
  if (!s.occlusion || count == 0) return 0;
  const int tilesPerSide = lightTilesFor(count);
  const std::size_t headerBytes =
      kTileCountersBytes + 4 * static_cast<std::size_t>(tilesPerSide) * static_cast<std::size_t>(tilesPerSide);
  const std::size_t nodeCapacity = std::min<std::size_t>(std::max<std::size_t>(count * kNodesPerParticle, kMinNodes),
                                                         budget_.maxBlockBytes() / kTileNodeBytes);
  tiles_.ensure(headerBytes);
  nodes_.ensure(nodeCapacity * kTileNodeBytes);
  rawSunlight_.ensure(count * sizeof(float));
  // Bounds at their identities (min ← +max int, max ← −max int), empty counters, empty lists.
  std::vector<GLuint> header(headerBytes / 4, 0xffffffffu);
  const GLint bounds[4] = {std::numeric_limits<GLint>::max(), std::numeric_limits<GLint>::max(),
                           std::numeric_limits<GLint>::min(), std::numeric_limits<GLint>::min()};
  std::memcpy(header.data(), bounds, sizeof bounds);
  header[4] = 0;
  header[5] = static_cast<GLuint>(nodeCapacity);
  header[6] = 0;
  header[7] = 0;
  tiles_.write(0, headerBytes, header.data());
  buffers_.records.bind(ParticleBuffers::kRecordsBinding);
  tiles_.bind(kTilesBinding);
  nodes_.bind(kNodesBinding);
  rawSunlight_.bind(kRawSunlightBinding);
  const glm::vec3 sun = glm::normalize(s.view.lighting.sunDirection);
  const glm::vec3 helper = std::abs(sun.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  const glm::vec3 u = glm::normalize(glm::cross(helper, sun)), v = glm::cross(sun, u);
  for (const GlProgram& p : stages_) {
    gl_.UseProgram(p.id());
    gl_.Uniform1ui(p.uniform("uCount"), static_cast<GLuint>(count));
    gl_.Uniform1i(p.uniform("uTiles"), tilesPerSide);
    gl_.Uniform3f(p.uniform("uSun"), sun.x, sun.y, sun.z);
    gl_.Uniform3f(p.uniform("uLightU"), u.x, u.y, u.z);
    gl_.Uniform3f(p.uniform("uLightV"), v.x, v.y, v.z);
    gl_.Uniform1f(p.uniform("uSigma"), unitOpticalRadius);
    gl_.Uniform1f(p.uniform("uXi"), kOcclusionXi);
    gl_.Uniform1i(p.uniform("uSmooth"), s.smoothOcclusion ? 1 : 0);
    gl_.DispatchCompute(groupsFor(count, kGroupSize), 1, 1);
    fullBarrier(gl_);
  }
  std::size_t overflow = 0;
  if (countOverflow) {
    GLuint dropped = 0;
    tiles_.read(kNodeOverflowOffset, sizeof dropped, &dropped);
    overflow = dropped;
  }
  checkGlError(gl_, "light-space occlusion");
  return overflow;
}

}  // namespace cloudlut::render
