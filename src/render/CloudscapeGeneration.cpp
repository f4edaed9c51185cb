#include "render/CloudscapeGeneration.h"

#include <algorithm>
#include <cstring>
#include <string>

#include <glm/gtc/type_ptr.hpp>

#include "core/Errors.h"
#include "render/ShaderSources.h"
#include "scene/CloudscapeGrid.h"

namespace cloudlut::render {

namespace {

constexpr GLuint kCellsBinding = 6;
// The cell-list buffer (cloudscape_generate.comp.glsl, block Generation): four counters, the
// indirect dispatch arguments (uvec4 at byte 16), the count of keys (the particles in the frustum,
// at byte 32, padded to 48), then per listed cell an ivec4 (its index, ring and layers) and a vec4
// (its cloud: amount, mass factor).
constexpr std::size_t kCellsHeaderBytes = 48;
constexpr std::size_t kCellBytes = 32;
constexpr std::size_t kIndirectOffset = 16;

}  // namespace

CloudscapeGeneration::CloudscapeGeneration(const GlFunctions& gl, const StorageBudget& budget, ParticleBuffers& buffers)
    : gl_(gl), budget_(budget), buffers_(buffers), cells_(gl) {
  const std::string common = glslDefine("GROUP_SIZE", kGroupSize) + particleRecordDefines();
  for (int stage = 0; stage < 3; ++stage) {
    stages_[stage] = linkComputeProgram(gl, {"cloudscape_grid.glsl", "particle_common.glsl", "cloudscape_generate.comp.glsl"},
                                        common + glslDefine("STAGE", stage));
    requireParticleRecordLayout(gl, stages_[stage].id(), "cloudscape_generate.comp.glsl");
  }
  sort_ = linkComputeProgram(gl, {"bitonic_sort.comp.glsl"}, glslDefine("GROUP_SIZE", kGroupSize));
}

CloudscapeGeneration::Result CloudscapeGeneration::run(const scene::CloudType& cloud, const scene::QualityPreset& q,
                                                       const RenderSettings& s, bool sortKeys,
                                                       float referenceRadius) {
  if (q.layers > kGridLayerLimit || q.rings > kGridRingLimit)
    throw UsageError("quality '" + q.name + "': " + std::to_string(q.rings) + " rings of " + std::to_string(q.layers) +
                     " layers; the particle records tell at most " + std::to_string(kGridLayerLimit) +
                     " layers and " + std::to_string(kGridRingLimit) + " rings apart");
  const scene::GridParameters g = scene::gridParameters(cloud, q, referenceRadius);
  const std::size_t capacity = static_cast<std::size_t>(q.maxParticles());
  std::size_t pow2 = 1;
  while (pow2 < capacity) pow2 <<= 1;
  const std::string what = "quality '" + q.name + "' (" + std::to_string(q.ringDim) + "^2 x " +
                           std::to_string(q.rings) + " x " + std::to_string(q.layers) + " = " +
                           std::to_string(capacity) + " particle slots)";
  const std::size_t cellBytes = kCellsHeaderBytes + kCellBytes * static_cast<std::size_t>(q.cellCount());
  budget_.require(static_cast<long double>(capacity) * sizeof(GpuParticleRecord), what);
  budget_.require(static_cast<long double>(pow2) * ParticleBuffers::kSortKeyBytes, what + " sort keys");
  budget_.require(static_cast<long double>(cellBytes), what + " cell list");
  buffers_.records.ensure(capacity * sizeof(GpuParticleRecord));
  buffers_.sortKeys.ensure(pow2 * ParticleBuffers::kSortKeyBytes);
  cells_.ensure(cellBytes);

  // Reset the counters (cells, particles, capacity, overflow) and the indirect arguments; pad the
  // keys with distance -1 (sorts last).
  const GLuint header[12] = {0, 0, static_cast<GLuint>(capacity), 0, 0, 1, 1, 0, 0, 0, 0, 0};
  cells_.write(0, sizeof header, header);
  const float minusOne = -1.0f;
  GLuint pad[2] = {0, 0xffffffffu};
  std::memcpy(&pad[0], &minusOne, sizeof minusOne);
  gl_.BindBuffer(GL_SHADER_STORAGE_BUFFER, buffers_.sortKeys.id());
  gl_.ClearBufferData(GL_SHADER_STORAGE_BUFFER, GL_RG32UI, GL_RG_INTEGER, GL_UNSIGNED_INT, pad);

  buffers_.records.bind(ParticleBuffers::kRecordsBinding);
  buffers_.sortKeys.bind(ParticleBuffers::kSortKeysBinding);
  cells_.bind(kCellsBinding);
  const scene::Frustum fr = scene::cameraFrustum(s.view.camera, s.width, s.height);
  const glm::vec3 eye = s.view.camera.eye;
  const glm::vec3 sun = glm::normalize(s.view.lighting.sunDirection);
  for (int stage = 0; stage < 3; ++stage) {
    const GlProgram& p = stages_[stage];
    gl_.UseProgram(p.id());
    gl_.Uniform4fv(p.uniform("uG0"), 1, glm::value_ptr(g.g0));
    gl_.Uniform4fv(p.uniform("uG1"), 1, glm::value_ptr(g.g1));
    gl_.Uniform4fv(p.uniform("uG2"), 1, glm::value_ptr(g.g2));
    gl_.Uniform4fv(p.uniform("uG3"), 1, glm::value_ptr(g.g3));
    gl_.Uniform4fv(p.uniform("uG4"), 1, glm::value_ptr(g.g4));
    gl_.Uniform3f(p.uniform("uEye"), eye.x, eye.y, eye.z);
    gl_.Uniform3f(p.uniform("uSun"), sun.x, sun.y, sun.z);
    gl_.Uniform4fv(p.uniform("uPlanes"), 5, glm::value_ptr(fr.planes[0]));
    if (stage == 0) {
      gl_.DispatchCompute(groupsFor(static_cast<std::size_t>(q.cellCount()), kGroupSize), 1, 1);
    } else if (stage == 1) {
      gl_.DispatchCompute(1, 1, 1);
    } else {
      gl_.BindBuffer(GL_DISPATCH_INDIRECT_BUFFER, cells_.id());
      gl_.DispatchComputeIndirect(static_cast<GLintptr>(kIndirectOffset));
      gl_.BindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
    }
    fullBarrier(gl_);
  }
  GLuint counts[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  cells_.read(0, sizeof counts, counts);
  checkGlError(gl_, "generating the cloudscape");
  Result out;
  out.cells = counts[0];
  out.count = std::min<std::size_t>(counts[1], capacity);
  out.visible = std::min<std::size_t>(counts[8], out.count);
  const glm::vec2 maxR = scene::grid::cgMaxRadii(q.rings - 1, g.g0, g.g1, g.g2);
  out.farPlane = g.g3.y + 2.0f * std::max(maxR.x, maxR.y) + 1.0f;
  if (sortKeys && out.visible > 1) sort(out.visible);
  return out;
}

// Bitonic sort of the keys padded to n = 2^k: passes (k, j) for k = 2, 4, …, n and j = k/2, …, 1.
void CloudscapeGeneration::sort(std::size_t count) {
  std::size_t n = 1;
  while (n < count) n <<= 1;
  gl_.UseProgram(sort_.id());
  gl_.Uniform1ui(sort_.uniform("uCount"), static_cast<GLuint>(n));
  const GLint uK = sort_.uniform("uK"), uJ = sort_.uniform("uJ");
  for (std::size_t k = 2; k <= n; k <<= 1)
    for (std::size_t j = k >> 1; j > 0; j >>= 1) {
      gl_.Uniform1ui(uK, static_cast<GLuint>(k));
      gl_.Uniform1ui(uJ, static_cast<GLuint>(j));
      gl_.DispatchCompute(groupsFor(n, kGroupSize), 1, 1);
      gl_.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
  fullBarrier(gl_);
}

scene::CpuGeneration CloudscapeGeneration::readBack(const Result& generated, const scene::CloudType& cloud,
                                                    const scene::QualityPreset& quality,
                                                    const RenderSettings& settings) const {
  const scene::GridParameters g = scene::gridParameters(cloud, quality);
  scene::CpuGeneration out;
  out.validCells = generated.cells;
  out.lit = generated.count;
  const std::vector<GpuParticleRecord> records = buffers_.readRecords(generated.count);
  for (const std::uint32_t index : buffers_.readKeyIndices(generated.visible))
    out.particles.push_back(unpackGridParticle(records.at(index), g, settings.view.camera.eye));
  checkGlError(gl_, "reading the particles back");
  return out;
}

}  // namespace cloudlut::render
