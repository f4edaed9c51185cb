#pragma once
// The diffusion pass (shaders/diffusion_volume.comp.glsl, docs/LIGHTING.md "Diffusion of the
// multiply scattered light"): per frame, the multiply scattered light of the particles as the
// solution of the flux-limited diffusion equation on the nodes of a vertical column volume
// (a SunVolume built toward +y over the particles' bounds, whose optical depths give the
// extinction), lit through the sun volume. The particle shader reads the fluence and flux at
// each fragment's mean scattering point (shaders/diffusion_sampling.glsl) and takes a share of
// its multiple scattering from it (diffusionShareOfMultiple, cloudlut_shading.glsl), larger
// where the pass finds cloud beside the point across the sun (cloudBesideWeight,
// shaders/diffusion_beside.comp.glsl).
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "render/GlContext.h"
#include "render/GlFunctions.h"
#include "render/GlResources.h"
#include "render/SunVolume.h"

namespace cloudlut::render {

class DiffusionVolume {
 public:
  DiffusionVolume(const GlFunctions& gl, const GlContext& context);
  ~DiffusionVolume();
  DiffusionVolume(const DiffusionVolume&) = delete;
  DiffusionVolume& operator=(const DiffusionVolume&) = delete;

  // Solves over the nodes of `columns` (one cascade, columns toward +y) lit through `sun` (bound
  // to texture unit `sunUnit` for the solve), for a later phase function of mean cosine g: coarse
  // to fine over up to kLevels levels (each halving the nodes per side), `sweeps` red-black
  // over-relaxed Gauss-Seidel sweeps on each level (a small level's in a single
  // dispatch, the same updates in the same order), but on the finest level of several, when
  // `cycles` > 0, that many correction cycles (V-cycles over the coarser levels, D kept there)
  // in place of its sweeps (docs/LIGHTING.md "Convergence"). With
  // fadeNodes > 0 (a box over part of a wider scene, whose sides cut clouds) the shader fades
  // the field out toward the grid's horizontal sides over that many nodes (diffusion_sampling.glsl).
  // Then, on the next coarser level's nodes (the finest's when it is the only one), the weight
  // of the cloud beside each across the sun, besideOffset (world units) away (cloudBesideWeight):
  // it varies over particle radii, and the finest level's nodes would cost 8 times as much.
  // A warm start (warmCycles > 0; the caller's promise: the same columns as the last build, only
  // the sun moved): the last solve's φ and D start the finest level, and warmCycles correction
  // cycles replace the coarse-to-fine solve and its cycles (docs/LIGHTING.md "A moving sun").
  // Solved cold when there is no last solve over the same nodes, or only one level.
  void build(const SunVolume& columns, const SunVolume& sun, int sunUnit, float laterAsymmetry, int sweeps,
             int cycles, float besideOffset, float fadeNodes = 0.0f, int warmCycles = 0);
  static constexpr int kLevels = 3;
  // Binds the field to `unit`, the weights of the cloud beside to `unit` + 1, and sets
  // diffusion_sampling.glsl's uniforms; without a build
  // (or after clear()) the shader reads no field.
  void bind(const ProgramUniforms& uniforms, int unit) const;
  void clear() { built_ = false; }
  bool built() const { return built_; }
  // Whether the last build started from the solve before it (a warm start).
  bool warmStarted() const { return warmStarted_; }
  // φ (per unit sun irradiance) and J (world axes) per node, 4 floats, x fastest (the tests,
  // through Renderer::diffusionVolume).
  std::vector<float> readBack() const;
  // The finest level's solve per node, 4 floats, x fastest (the tests): σ* (the δ-Eddington-
  // scaled extinction, 1/length), q (the scaled sun beam's loss per unit length per unit sun
  // irradiance, 1/length), φ and D (length).
  std::vector<float> readSolve() const;

 private:
  const GlFunctions& gl_;
  const GlContext& context_;
  static constexpr int kStages = 9;
  GlProgram stages_[kStages];  // diffusion_volume.comp.glsl's STAGE 0 … 8
  struct Level {
    GLuint medium = 0, field = 0;  // σ* and q; φ and D
    glm::ivec3 nodes{0};
  };
  void release();
  Level levels_[kLevels];
  int levelCount_ = 0;
  // φ and J on the finest level (the particle shader's); during the cycles, scratch for the
  // residual and D handed to the coarser level
  GLuint flux_ = 0;
  // The weight of the cloud beside each node of one level (diffusion_beside.comp.glsl), for the
  // particle shader's share: the second level, or the only one.
  struct Beside {
    GlProgram program;
    GLuint texture = 0;
    int level = 0;
    float stride() const { return static_cast<float>(1 << level); }  // finest nodes per node
  };
  Beside beside_;
  glm::ivec3 nodes_{0};
  glm::mat4 worldToNode_{1.0f};
  float fadeNodes_ = 0.0f;
  bool built_ = false;
  bool solved_ = false;       // the levels hold a finished solve (clear() keeps it for a warm start)
  bool warmStarted_ = false;
};

}  // namespace cloudlut::render
