#include "render/GpuParticleRecord.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>

#include "render/ShaderSources.h"
#include "scene/CloudscapeGrid.h"

namespace cloudlut::render {

GpuParticleRecord packParticle(const scene::Particle& p, const glm::vec3& sunDirection) {
  const glm::mat3 w = p.toWorld(), inv = p.toParticle();
  GpuParticleRecord r{};
  r.centerDensity[0] = p.center.x;
  r.centerDensity[1] = p.center.y;
  r.centerDensity[2] = p.center.z;
  r.centerDensity[3] = p.density;
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < 3; ++i) {
      r.toWorld[c][i] = w[c][i];
      r.toParticle[c][i] = inv[c][i];
    }
  r.toParticle[0][3] = glm::length(inv * sunDirection);
  r.toParticle[1][3] = 1.0001f * std::max({p.radii.x, p.radii.y, p.radii.z});
  r.toParticle[2][3] = 1.0f;  // sunlight until the occlusion pass
  return r;
}

scene::GridParticle unpackGridParticle(const GpuParticleRecord& r, const scene::GridParameters& grid,
                                       const glm::vec3& eye) {
  scene::GridParticle gp;
  gp.particle.center = {r.centerDensity[0], r.centerDensity[1], r.centerDensity[2]};
  gp.particle.density = r.centerDensity[3];
  // A generated record maps by M = diag(radii) · Q (cloudscape_generate.comp.glsl): row k of M
  // is radii[k] times row k of Q.
  glm::mat3 m;
  for (int c = 0; c < 3; ++c) m[c] = glm::vec3(r.toWorld[c][0], r.toWorld[c][1], r.toWorld[c][2]);
  const glm::mat3 mt = glm::transpose(m);
  gp.particle.radii = {glm::length(mt[0]), glm::length(mt[1]), glm::length(mt[2])};
  gp.particle.noiseRotation = glm::normalize(glm::quat_cast(
      glm::transpose(glm::mat3(mt[0] / gp.particle.radii.x, mt[1] / gp.particle.radii.y, mt[2] / gp.particle.radii.z))));
  const int id = static_cast<int>(r.toWorld[0][3]);
  gp.ring = id / kGridLayerLimit;
  gp.layer = id % kGridLayerLimit;
  gp.cellX = static_cast<int>(r.toWorld[1][3]);
  gp.cellZ = static_cast<int>(r.toWorld[2][3]);
  const glm::vec2 camXZ(eye.x, eye.z);
  const glm::vec2 delta = glm::abs(scene::grid::cgCellCentre(gp.ring, gp.cellX, gp.cellZ, grid.g0) - camXZ);
  gp.weight = scene::grid::cgRingWeight(gp.ring, std::max(delta.x, delta.y), grid.g0, grid.g3);
  gp.fill = scene::grid::cgCellCloud(gp.ring, gp.cellX, gp.cellZ, grid.g0, grid.g1, grid.g2, grid.g3, grid.g4).y;
  return gp;
}

std::string particleRecordDefines() {
  return glslDefine("GRID_LAYER_LIMIT", kGridLayerLimit) +
         glslDefine("PARTICLE_RECORD_TEXELS", static_cast<int>(sizeof(GpuParticleRecord) / 16));
}

void requireParticleRecordLayout(const GlFunctions& gl, GLuint program, const std::string& what) {
  const auto property = [&](const char* variable, GLenum prop) {
    const GLuint index = gl.GetProgramResourceIndex(program, GL_BUFFER_VARIABLE, variable);
    if (index == GL_INVALID_INDEX) return GLint{-1};
    GLint value = -1;
    gl.GetProgramResourceiv(program, GL_BUFFER_VARIABLE, index, 1, &prop, 1, nullptr, &value);
    return value;
  };
  const GLint stride = property("particles[0].centerDensity", GL_TOP_LEVEL_ARRAY_STRIDE);
  const GLint offset = property("particles[0].toWorld[0]", GL_OFFSET);
  // A variable the program does not use may be inactive (-1): only what is present is checked.
  if ((stride >= 0 && stride != static_cast<GLint>(sizeof(GpuParticleRecord))) ||
      (offset >= 0 && offset != static_cast<GLint>(offsetof(GpuParticleRecord, toWorld))))
    throw GlError(what + ": the GLSL particle record (stride " + std::to_string(stride) + ", toWorld at " +
                  std::to_string(offset) + ") differs from GpuParticleRecord (" +
                  std::to_string(sizeof(GpuParticleRecord)) + ", " +
                  std::to_string(offsetof(GpuParticleRecord, toWorld)) + ")");
}

std::vector<GpuParticleRecord> ParticleBuffers::readRecords(std::size_t count) const {
  std::vector<GpuParticleRecord> out(count);
  if (count > 0) records.read(0, count * sizeof(GpuParticleRecord), out.data());
  return out;
}

std::vector<std::uint32_t> ParticleBuffers::readKeyIndices(std::size_t count) const {
  std::vector<std::uint32_t> keys(2 * count), out(count);
  if (count > 0) sortKeys.read(0, count * kSortKeyBytes, keys.data());
  for (std::size_t i = 0; i < count; ++i) out[i] = keys[2 * i + 1];
  return out;
}

}  // namespace cloudlut::render
