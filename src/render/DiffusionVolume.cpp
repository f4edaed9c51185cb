#include "render/DiffusionVolume.h"

#include <glm/geometric.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "render/GpuStorage.h"
#include "render/ShaderSources.h"

namespace cloudlut::render {
namespace {

const std::vector<std::string> kFiles = {"cloudlut_geometry.glsl", "cloudlut_phase.glsl", "cloudlut_sampling.glsl",
                                         "cloudlut_shading.glsl", "sun_volume.glsl", "sun_volume_chord.glsl",
                                         "sun_chord_map.glsl", "cascade_columns.glsl", "sun_volume_sampling.glsl",
                                         "diffusion_volume.comp.glsl"};
constexpr unsigned kGroup = 4;  // the shader's local size per axis
// Successive over-relaxation of the red-black sweeps: 1.8 reached on the 1419-particle patch in
// 800 sweeps what plain Gauss-Seidel had not in 1600 (docs/LIGHTING.md).
constexpr float kOverRelaxation = 1.8f;

void deleteTexture(const GlFunctions& gl, GLuint& t) {
  if (t) gl.DeleteTextures(1, &t);
  t = 0;
}

}  // namespace

DiffusionVolume::DiffusionVolume(const GlFunctions& gl, const GlContext& context) : gl_(gl), context_(context) {
  for (int stage = 0; stage < 3; ++stage)
    stages_[stage] = linkComputeProgram(gl, kFiles, glslDefine("STAGE", stage) + SunVolume::samplingDefines());
}

DiffusionVolume::~DiffusionVolume() {
  for (GLuint* t : {&medium_, &field_, &flux_}) deleteTexture(gl_, *t);
}

void DiffusionVolume::build(const SunVolume& columns, const SunVolume& sun, int sunUnit, float laterAsymmetry,
                            int iterations) {
  const SunVolumeGrid& grid = columns.grid();
  const glm::ivec3 n = grid.dims;
  if (n != nodes_) {
    for (GLuint* t : {&medium_, &field_, &flux_}) deleteTexture(gl_, *t);
    medium_ = createFloatTexture3D(gl_, context_, "the diffusion volume", n.x, n.y, n.z, 2, nullptr);
    field_ = createFloatTexture3D(gl_, context_, "the diffusion volume", n.x, n.y, n.z, 2, nullptr);
    flux_ = createFloatTexture3D(gl_, context_, "the diffusion volume", n.x, n.y, n.z, 4, nullptr);
    nodes_ = n;
  }
  worldToNode_ = grid.toGrid[0];
  const glm::mat4& toWorld = grid.toWorld[0];
  const glm::vec3 spacing(glm::length(glm::vec3(toWorld[0])), glm::length(glm::vec3(toWorld[1])),
                          glm::length(glm::vec3(toWorld[2])));
  const GLuint groups[3] = {groupsFor(n.x, kGroup), groupsFor(n.y, kGroup), groupsFor(n.z, kGroup)};
  const auto use = [&](int stage) {
    const GlProgram& p = stages_[stage];
    gl_.UseProgram(p.id());
    const ProgramUniforms u(gl_, p.id());
    gl_.ActiveTexture(GL_TEXTURE0);
    gl_.BindTexture(GL_TEXTURE_3D, columns.texture());
    u.set("uColumnTau", 0);
    sun.bind(u, sunUnit);
    gl_.Uniform3i(p.uniform("uNodes"), n.x, n.y, n.z);
    gl_.UniformMatrix4fv(p.uniform("uNodeToWorld"), 1, GL_FALSE, glm::value_ptr(toWorld));
    gl_.UniformMatrix4fv(p.uniform("uWorldToNode"), 1, GL_FALSE, glm::value_ptr(worldToNode_));
    u.set("uSpacing", spacing);
    u.set("uVerticalAxis", 2);
    u.set("uLaterAsymmetry", laterAsymmetry);
  };
  const auto dispatch = [&] {
    gl_.DispatchCompute(groups[0], groups[1], groups[2]);
    gl_.MemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  };
  gl_.BindImageTexture(0, medium_, 0, GL_TRUE, 0, GL_READ_WRITE, GL_RG32F);
  use(0);
  gl_.BindImageTexture(1, field_, 0, GL_TRUE, 0, GL_READ_WRITE, GL_RG32F);
  dispatch();
  use(1);
  gl_.Uniform1f(stages_[1].uniform("uOverRelaxation"), kOverRelaxation);
  gl_.BindImageTexture(1, field_, 0, GL_TRUE, 0, GL_READ_WRITE, GL_RG32F);
  for (int i = 0; i < iterations; ++i)
    for (int colour = 0; colour < 2; ++colour) {
      gl_.Uniform1i(stages_[1].uniform("uColour"), colour);
      dispatch();
    }
  use(2);
  gl_.BindImageTexture(1, field_, 0, GL_TRUE, 0, GL_READ_WRITE, GL_RG32F);
  gl_.BindImageTexture(3, flux_, 0, GL_TRUE, 0, GL_READ_WRITE, GL_RGBA32F);
  dispatch();
  for (GLuint unit = 0; unit < 4; ++unit) gl_.BindImageTexture(unit, 0, 0, GL_TRUE, 0, GL_READ_WRITE, GL_R32F);
  checkGlError(gl_, "solving the diffusion volume");
  built_ = true;
}

void DiffusionVolume::bind(const ProgramUniforms& uniforms, int unit) const {
  gl_.ActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + unit));
  gl_.BindTexture(GL_TEXTURE_3D, flux_);
  uniforms.set("uDiffusionField", unit);
  uniforms.set("uDiffusionBuilt", built_ && flux_ ? 1 : 0);
  gl_.Uniform3i(uniforms.location("uDiffusionNodes"), nodes_.x, nodes_.y, nodes_.z);
  gl_.UniformMatrix4fv(uniforms.location("uDiffusionToNode"), 1, GL_FALSE, glm::value_ptr(worldToNode_));
}

std::vector<float> DiffusionVolume::readBack() const {
  std::vector<float> out(static_cast<std::size_t>(nodes_.x) * nodes_.y * nodes_.z * 4);
  if (!flux_) return out;
  gl_.BindTexture(GL_TEXTURE_3D, flux_);
  gl_.GetTexImage(GL_TEXTURE_3D, 0, GL_RGBA, GL_FLOAT, out.data());
  return out;
}

}  // namespace cloudlut::render
