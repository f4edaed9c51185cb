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
constexpr GLuint kOrderBinding = 5;
constexpr GLuint kOccludersBinding = 6;
constexpr GLuint kCoverBinding = 7;
// The tile buffer (occlusion.comp.glsl, block Tiles): ordered-int bounds (4 ints), cover total,
// centre total, cover overflow and a pad word, then 4 T² + 2 T words (counts, starts, row totals).
constexpr std::size_t kTileHeaderBytes = 32;
constexpr std::size_t kCoverTotalOffset = 16;
constexpr std::size_t kCoverOverflowOffset = 24;
constexpr std::size_t kOccluderBytes = 64;  // four vec4 (block Occluders)
constexpr int kStages = 11;

// Threads of stage `stage` (occlusion.comp.glsl): per particle, per row of the two grids, one,
// per tile of the two grids, or per tile.
std::size_t stageThreads(int stage, std::size_t count, std::size_t tilesPerSide) {
  switch (stage) {
    case 2: return 2 * tilesPerSide;
    case 3: return 1;
    case 4: return 2 * tilesPerSide * tilesPerSide;
    case 6:
    case 8: return tilesPerSide * tilesPerSide;
    default: return count;
  }
}

}  // namespace

int lightTilesFor(std::size_t count) {
  const double side = std::ceil(std::sqrt(static_cast<double>(count) / kParticlesPerLightTile));
  return static_cast<int>(std::clamp(side, static_cast<double>(kLightTiles), static_cast<double>(kMaxLightTiles)));
}

LightOcclusion::LightOcclusion(const GlFunctions& gl, const StorageBudget& budget, ParticleBuffers& buffers)
    : gl_(gl), budget_(budget), buffers_(buffers), tiles_(gl), cover_(gl), rawSunlight_(gl), order_(gl), occluders_(gl) {
  const std::string common = glslDefine("GROUP_SIZE", kGroupSize);
  stages_.reserve(kStages);
  for (int stage = 0; stage < kStages; ++stage) {
    stages_.push_back(
        linkComputeProgram(gl, {"particle_common.glsl", "occlusion.comp.glsl"}, common + glslDefine("STAGE", stage)));
    requireParticleRecordLayout(gl, stages_.back().id(), "occlusion.comp.glsl");
  }
}

std::size_t LightOcclusion::run(std::size_t count, const RenderSettings& s, float unitOpticalRadius, bool countOverflow) {
  if (!s.occlusion || count == 0) return 0;
  const std::size_t tilesPerSide = static_cast<std::size_t>(lightTilesFor(count));
  const std::size_t headerBytes = kTileHeaderBytes + 4 * (4 * tilesPerSide * tilesPerSide + 2 * tilesPerSide);
  budget_.require(static_cast<long double>(count) * kOccluderBytes, "light occlusion of " + std::to_string(count) + " particles");
  tiles_.ensure(headerBytes);
  rawSunlight_.ensure(count * sizeof(float));
  order_.ensure(count * sizeof(GLuint));
  occluders_.ensure(count * kOccluderBytes);
  // Bounds at their identities (min ← +max int, max ← −max int), counts and totals 0.
  std::vector<GLuint> header(headerBytes / 4, 0u);
  const GLint bounds[4] = {std::numeric_limits<GLint>::max(), std::numeric_limits<GLint>::max(),
                           std::numeric_limits<GLint>::min(), std::numeric_limits<GLint>::min()};
  std::memcpy(header.data(), bounds, sizeof bounds);
  tiles_.write(0, headerBytes, header.data());
  const glm::vec3 sun = glm::normalize(s.view.lighting.sunDirection);
  const glm::vec3 helper = std::abs(sun.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  const glm::vec3 u = glm::normalize(glm::cross(helper, sun)), v = glm::cross(sun, u);
  GLuint coverCapacity = 0;
  for (int stage = 0; stage < kStages; ++stage) {
    if (stage == 5) {  // the cover bins' total is known: size them (at most one storage block)
      GLuint total = 0;
      tiles_.read(kCoverTotalOffset, sizeof total, &total);
      coverCapacity = static_cast<GLuint>(std::min<std::size_t>(std::max<std::size_t>(total, 1),
                                                                budget_.maxBlockBytes() / sizeof(GLuint)));
      cover_.ensure(static_cast<std::size_t>(coverCapacity) * sizeof(GLuint));
    }
    buffers_.records.bind(ParticleBuffers::kRecordsBinding);
    tiles_.bind(kTilesBinding);
    rawSunlight_.bind(kRawSunlightBinding);
    order_.bind(kOrderBinding);
    occluders_.bind(kOccludersBinding);
    if (cover_.bytes() == 0) cover_.ensure(64);
    cover_.bind(kCoverBinding);
    const GlProgram& p = stages_[static_cast<std::size_t>(stage)];
    gl_.UseProgram(p.id());
    gl_.Uniform1ui(p.uniform("uCount"), static_cast<GLuint>(count));
    gl_.Uniform1i(p.uniform("uTiles"), static_cast<GLint>(tilesPerSide));
    gl_.Uniform3f(p.uniform("uSun"), sun.x, sun.y, sun.z);
    gl_.Uniform3f(p.uniform("uLightU"), u.x, u.y, u.z);
    gl_.Uniform3f(p.uniform("uLightV"), v.x, v.y, v.z);
    gl_.Uniform1f(p.uniform("uSigma"), unitOpticalRadius);
    gl_.Uniform1f(p.uniform("uXi"), kOcclusionXi);
    gl_.Uniform1i(p.uniform("uSmooth"), s.smoothOcclusion ? 1 : 0);
    gl_.Uniform1ui(p.uniform("uCoverCapacity"), coverCapacity);
    gl_.DispatchCompute(groupsFor(stageThreads(stage, count, tilesPerSide), kGroupSize), 1, 1);
    fullBarrier(gl_);
  }
  std::size_t overflow = 0;
  if (countOverflow) {
    GLuint dropped = 0;
    tiles_.read(kCoverOverflowOffset, sizeof dropped, &dropped);
    overflow = dropped;
  }
  checkGlError(gl_, "light-space occlusion");
  return overflow;
}

}  // namespace cloudlut::render
