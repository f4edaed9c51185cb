#include "render/DiffusionVolume.h"

#include <algorithm>
#include <functional>

#include <glm/geometric.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "render/GpuStorage.h"
#include "render/ShaderSources.h"

namespace cloudlut::render {
namespace {

// the shared GLSL and the sun volume's sampling, then the pass
std::vector<std::string> filesFor(const char* pass) {
  return {"cloudlut_geometry.glsl", "cloudlut_phase.glsl",      "cloudlut_sampling.glsl",
          "cloudlut_shading.glsl",  "sun_volume.glsl",          "sun_volume_chord.glsl",
          "sun_chord_map.glsl",     "cascade_columns.glsl",     "sun_volume_sampling.glsl",
          pass};
}
constexpr unsigned kGroup = 4;  // the shader's local size per axis
// Successive over-relaxation of the red-black sweeps: 1.8 reached on the 1419-particle patch in
// 800 sweeps what plain Gauss-Seidel had not in 1600 (docs/LIGHTING.md).
constexpr float kOverRelaxation = 1.8f;
// The correction cycles (docs/LIGHTING.md "Convergence"): plain red-black Gauss-Seidel sweeps
// before and after each coarse correction (over-relaxation damps the rough error slowly; an
// over-relaxation of 1.2, or 3 sweeps in place of 2, did no better), and the sweeps that solve
// the coarsest level's correction (200 did no better than 10 on the patch).
constexpr int kCycleSweeps = 2;
constexpr float kCycleOverRelaxation = 1.0f;
constexpr int kCoarsestCorrectionSweeps = 10;
constexpr int kCoarseUnit = 2;  // texture unit of the coarser level's field (prolongation)
// STAGE 5 (a level's sweeps in one work group of kWholeGroup invocations) for any level of at
// most kOneGroupNodes nodes (the coarsest, and every level of a small scene's grid, e.g. a single
// particle's): llvmpipe runs a work group on one core, which beats a dispatch
// per half-sweep on both cores only while the half-sweep is small. And while each invocation's
// loops stay under llvmpipe's 65535 passes in all (render/VolumeResolve.h), with a margin.
constexpr int kWholeGroup = 256;  // the shader's WHOLE_GROUP
constexpr long kOneGroupNodes = 4096;
constexpr long kLoopPassBudget = 50000;
bool inOneGroup(const glm::ivec3& nodes, int sweeps) {
  const long count = static_cast<long>((nodes.x + 1) / 2) * nodes.y * nodes.z;
  const long passes = 2L * sweeps * ((count + kWholeGroup - 1) / kWholeGroup + 1);
  return static_cast<long>(nodes.x) * nodes.y * nodes.z <= kOneGroupNodes && passes < kLoopPassBudget;
}

}  // namespace

DiffusionVolume::DiffusionVolume(const GlFunctions& gl, const GlContext& context) : gl_(gl), context_(context) {
  for (int stage = 0; stage < kStages; ++stage)
    stages_[stage] = linkComputeProgram(gl, filesFor("diffusion_volume.comp.glsl"),
                                        glslDefine("STAGE", stage) + glslDefine("WHOLE_GROUP", kWholeGroup) +
                                            SunVolume::samplingDefines());
  beside_.program = linkComputeProgram(gl, filesFor("diffusion_beside.comp.glsl"), SunVolume::samplingDefines());
}

DiffusionVolume::~DiffusionVolume() { release(); }

void DiffusionVolume::release() {
  for (Level& l : levels_) {
    deleteTexture(gl_, l.medium);
    deleteTexture(gl_, l.field);
    l.nodes = glm::ivec3(0);
  }
  deleteTexture(gl_, flux_);
  deleteTexture(gl_, beside_.texture);
  levelCount_ = 0;
  solved_ = false;
}

void DiffusionVolume::build(const SunVolume& columns, const SunVolume& sun, int sunUnit, float laterAsymmetry,
                            int sweeps, int cycles, float besideOffset, float fadeNodes, int warmCycles) {
  fadeNodes_ = fadeNodes;
  const SunVolumeGrid& grid = columns.grid();
  const glm::ivec3 n = grid.dims;
  // a warm start needs the last solve's field over these nodes and a coarser level for its cycles
  const bool warm = warmCycles > 0 && solved_ && n == nodes_ && levelCount_ > 1;
  solved_ = false;
  if (n != nodes_) {
    release();
    // levels while the coarser one keeps at least 6 nodes per side
    glm::ivec3 dims = n;
    for (int l = 0; l < kLevels && (l == 0 || glm::all(glm::greaterThanEqual(dims, glm::ivec3(6)))); ++l) {
      levels_[l].nodes = dims;
      levels_[l].medium = createFloatTexture3D(gl_, context_, "the diffusion volume", dims.x, dims.y, dims.z, 2, nullptr);
      levels_[l].field = createFloatTexture3D(gl_, context_, "the diffusion volume", dims.x, dims.y, dims.z, 2, nullptr);
      levelCount_ = l + 1;
      dims = (dims + 1) / 2;
    }
    flux_ = createFloatTexture3D(gl_, context_, "the diffusion volume", n.x, n.y, n.z, 4, nullptr);
    beside_.level = std::min(levelCount_ - 1, 1);
    const glm::ivec3 b = levels_[beside_.level].nodes;
    beside_.texture = createFloatTexture3D(gl_, context_, "the diffusion volume", b.x, b.y, b.z, 1, nullptr);
    nodes_ = n;
  }
  worldToNode_ = grid.toGrid[0];
  const glm::mat4& toWorld = grid.toWorld[0];
  const glm::vec3 spacing(glm::length(glm::vec3(toWorld[0])), glm::length(glm::vec3(toWorld[1])),
                          glm::length(glm::vec3(toWorld[2])));
  const auto use = [&](int stage, int level) {
    const GlProgram& p = stages_[stage];
    gl_.UseProgram(p.id());
    const ProgramUniforms u(gl_, p.id());
    gl_.ActiveTexture(GL_TEXTURE0);
    gl_.BindTexture(GL_TEXTURE_3D, columns.texture());
    u.set("uColumnTau", 0);
    sun.bind(u, sunUnit);
    const glm::ivec3 d = levels_[level].nodes;
    gl_.Uniform3i(p.uniform("uNodes"), d.x, d.y, d.z);
    gl_.UniformMatrix4fv(p.uniform("uNodeToWorld"), 1, GL_FALSE, glm::value_ptr(toWorld));
    gl_.UniformMatrix4fv(p.uniform("uWorldToNode"), 1, GL_FALSE, glm::value_ptr(worldToNode_));
    u.set("uSpacing", spacing * static_cast<float>(1 << level));
    u.set("uLaterAsymmetry", laterAsymmetry);
    u.set("uOverRelaxation", kOverRelaxation);
    gl_.BindImageTexture(0, levels_[level].medium, 0, GL_TRUE, 0, GL_READ_WRITE, GL_RG32F);
    gl_.BindImageTexture(1, levels_[level].field, 0, GL_TRUE, 0, GL_READ_WRITE, GL_RG32F);
    return d;
  };
  const auto uniformsOf = [&](int stage) { return ProgramUniforms(gl_, stages_[stage].id()); };
  const auto dispatch = [&](const glm::ivec3& d) {
    gl_.DispatchCompute(groupsFor(d.x, kGroup), groupsFor(d.y, kGroup), groupsFor(d.z, kGroup));
    gl_.MemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  };
  use(0, 0);  // the finest level's medium and source; its field started, or kept when warm
  gl_.Uniform1i(stages_[0].uniform("uKeepField"), warm ? 1 : 0);
  dispatch(levels_[0].nodes);
  for (int l = 1; l < levelCount_; ++l) {  // the coarser ones, each from the one finer
    const glm::ivec3 d = use(3, l);
    const glm::ivec3 fine = levels_[l - 1].nodes;
    gl_.Uniform3i(stages_[3].uniform("uFineNodes"), fine.x, fine.y, fine.z);
    gl_.BindImageTexture(2, levels_[l - 1].medium, 0, GL_TRUE, 0, GL_READ_ONLY, GL_RG32F);
    dispatch(d);
  }
  // `count` red-black sweeps on level l, over-relaxed by omega, D kept on a correction's level
  const auto relax = [&](int l, int count, float omega, bool keepDiffusivity) {
    const int stage = inOneGroup(levels_[l].nodes, count) ? 5 : 1;
    const glm::ivec3 d = use(stage, l);
    uniformsOf(stage).set("uOverRelaxation", omega);
    gl_.Uniform1i(stages_[stage].uniform("uKeepDiffusivity"), keepDiffusivity ? 1 : 0);
    if (stage == 5) {
      gl_.Uniform1i(stages_[5].uniform("uSweeps"), count);
      dispatch(glm::ivec3(1));
      return;
    }
    const glm::ivec3 half((d.x + 1) / 2, d.y, d.z);  // a colour's nodes: every other one along x
    for (int i = 0; i < count; ++i)
      for (int colour = 0; colour < 2; ++colour) {
        gl_.Uniform1i(stages_[1].uniform("uColour"), colour);
        dispatch(half);
      }
  };
  // level l + 1's field, trilinear, into level l's: as its start (STAGE 4) or added (STAGE 8)
  const auto prolong = [&](int stage, int l) {
    const glm::ivec3 d = use(stage, l);
    const glm::ivec3 coarse = levels_[l + 1].nodes;
    gl_.Uniform3i(stages_[stage].uniform("uCoarseNodes"), coarse.x, coarse.y, coarse.z);
    gl_.ActiveTexture(GL_TEXTURE0 + kCoarseUnit);
    gl_.BindTexture(GL_TEXTURE_3D, levels_[l + 1].field);
    uniformsOf(stage).set("uCoarseField", kCoarseUnit);
    dispatch(d);
  };
  // The correction cycle on level l (a V-cycle): smooth, hand the residual to the coarser level,
  // correct from its solve for the error, smooth again. D is the solve's own on the finest level
  // and kept on the coarser ones, whose equation for the error is linear.
  const std::function<void(int)> cycle = [&](int l) {
    const bool correction = l > 0;
    if (l == levelCount_ - 1) {  // the coarsest: solved by sweeps
      relax(l, kCoarsestCorrectionSweeps, kOverRelaxation, correction);
      return;
    }
    relax(l, kCycleSweeps, kCycleOverRelaxation, correction);
    // the residual and D, written by STAGE 6 into flux_ (scratch until STAGE 2) and read by STAGE 7
    gl_.BindImageTexture(3, flux_, 0, GL_TRUE, 0, GL_READ_WRITE, GL_RGBA32F);
    dispatch(use(6, l));
    const glm::ivec3 d = use(7, l + 1);
    const glm::ivec3 fine = levels_[l].nodes;
    gl_.Uniform3i(stages_[7].uniform("uFineNodes"), fine.x, fine.y, fine.z);
    dispatch(d);
    cycle(l + 1);
    prolong(8, l);
    relax(l, kCycleSweeps, kCycleOverRelaxation, correction);
  };
  if (warm) {  // the last solve's field, corrected toward the new source
    for (int c = 0; c < warmCycles; ++c) cycle(0);
  } else {
    for (int l = levelCount_ - 1; l >= 0; --l) {
      if (l < levelCount_ - 1) prolong(4, l);  // start from the coarser level's solution
      if (l > 0 || cycles == 0 || levelCount_ == 1) {
        relax(l, sweeps, kOverRelaxation, false);
        continue;
      }
      for (int c = 0; c < cycles; ++c) cycle(0);
    }
  }
  const glm::ivec3 d = use(2, 0);
  gl_.BindImageTexture(3, flux_, 0, GL_TRUE, 0, GL_READ_WRITE, GL_RGBA32F);
  dispatch(d);
  {  // the weight of the cloud beside, on its level
    gl_.UseProgram(beside_.program.id());
    const ProgramUniforms u(gl_, beside_.program.id());
    sun.bind(u, sunUnit);
    const glm::ivec3 b = levels_[beside_.level].nodes;
    gl_.Uniform3i(beside_.program.uniform("uNodes"), b.x, b.y, b.z);
    gl_.UniformMatrix4fv(beside_.program.uniform("uNodeToWorld"), 1, GL_FALSE, glm::value_ptr(toWorld));
    u.set("uBesideOffset", besideOffset);
    u.set("uBesideStride", beside_.stride());
    gl_.BindImageTexture(4, beside_.texture, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32F);
    dispatch(b);
  }
  for (GLuint unit = 0; unit < 5; ++unit) gl_.BindImageTexture(unit, 0, 0, GL_TRUE, 0, GL_READ_WRITE, GL_R32F);
  checkGlError(gl_, "solving the diffusion volume");
  built_ = true;
  solved_ = true;
  warmStarted_ = warm;
}

void DiffusionVolume::bind(const ProgramUniforms& uniforms, int unit) const {
  gl_.ActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + unit));
  gl_.BindTexture(GL_TEXTURE_3D, flux_);
  uniforms.set("uDiffusionField", unit);
  uniforms.set("uDiffusionBuilt", built_ && flux_ ? 1 : 0);
  gl_.Uniform3i(uniforms.location("uDiffusionNodes"), nodes_.x, nodes_.y, nodes_.z);
  gl_.UniformMatrix4fv(uniforms.location("uDiffusionToNode"), 1, GL_FALSE, glm::value_ptr(worldToNode_));
  uniforms.set("uDiffusionFade", fadeNodes_);
  gl_.ActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + unit + 1));
  gl_.BindTexture(GL_TEXTURE_3D, beside_.texture);
  uniforms.set("uDiffusionBeside", unit + 1);
  uniforms.set("uDiffusionBesideStride", beside_.stride());
  const glm::ivec3 b = levels_[beside_.level].nodes;
  gl_.Uniform3i(uniforms.location("uDiffusionBesideNodes"), b.x, b.y, b.z);
}

std::vector<float> DiffusionVolume::readBack() const {
  std::vector<float> out(static_cast<std::size_t>(nodes_.x) * nodes_.y * nodes_.z * 4);
  if (!flux_) return out;
  gl_.BindTexture(GL_TEXTURE_3D, flux_);
  gl_.GetTexImage(GL_TEXTURE_3D, 0, GL_RGBA, GL_FLOAT, out.data());
  return out;
}

std::vector<float> DiffusionVolume::readSolve() const {
  const std::size_t count = static_cast<std::size_t>(nodes_.x) * nodes_.y * nodes_.z;
  std::vector<float> out(count * 4), pair(count * 2);
  if (levelCount_ == 0) return out;
  for (int part = 0; part < 2; ++part) {
    gl_.BindTexture(GL_TEXTURE_3D, part == 0 ? levels_[0].medium : levels_[0].field);
    gl_.GetTexImage(GL_TEXTURE_3D, 0, GL_RG, GL_FLOAT, pair.data());
    for (std::size_t i = 0; i < count; ++i) {
      out[4 * i + 2 * part] = pair[2 * i];
      out[4 * i + 2 * part + 1] = pair[2 * i + 1];
    }
  }
  return out;
}

}  // namespace cloudlut::render
