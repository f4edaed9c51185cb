#pragma once
// The sun optical-depth volume pass (shaders/sun_volume.glsl, sun_volume_build.comp.glsl): per
// frame, the optical depth toward the sun of the particles in front of any point, on a grid of
// sun-parallel columns (SunVolumeGrid), filled from the particle records with the
// optical-depth table's chords (seed §4.1) — the same mean densities the shading uses. The
// particle pass samples it where each fragment's light is scattered (sunlight per shading point
// instead of the seed's per particle, §5.3) and along the column through that point (the cloud
// around it, for multiple scattering); a ground can sample it for the clouds' shadow. The renderer
// builds it a second time with vertical columns (the zenith volume): the optical depth of the cloud
// above and below every point, for the ambient under a sky from above (docs/LIGHTING.md).
#include <cstddef>
#include <string>
#include <vector>

#include <glm/vec4.hpp>

#include "render/GlContext.h"
#include "render/GlFunctions.h"
#include "render/GlResources.h"
#include "render/GpuParticleRecord.h"
#include "render/GpuStorage.h"
#include "render/SunVolumeGrid.h"

namespace cloudlut::render {

// Largest footprint, in columns, one particle may cover in one cascade; a particle above it is
// left to the coarser cascades and counted (footprintOverflow).
inline constexpr int kSunFootprintMax = 64 * 64;
// Fixed-point scale of the deltas (integer units per unit of optical depth per slice): the
// splat adds integers, so the volume does not depend on the order the GPU runs the particles.
inline constexpr float kSunFixedScale = 4096.0f;

class SunVolume {
 public:
  SunVolume(const GlFunctions& gl, const GlContext& context, const StorageBudget& budget, ParticleBuffers& buffers);
  ~SunVolume();
  SunVolume(const SunVolume&) = delete;
  SunVolume& operator=(const SunVolume&) = delete;

  // Fills the volume of `grid` from the first `count` particle records, their chords from the
  // optical-depth texture (its dims; σ the unit optical radius). UsageError when the grid needs
  // more storage than this OpenGL allows. Returns the particle-cascade pairs skipped for a
  // footprint over kSunFootprintMax when `countOverflow` (0 otherwise).
  std::size_t build(const SunVolumeGrid& grid, std::size_t count, GLuint opticalDepthTexture,
                    const glm::vec4& opticalDepthDims, float sigma, bool countOverflow);

  // Binds the volume texture to `unit` and sets the sampling uniforms of
  // sun_volume_sampling.glsl (uSunTau, uSunCascades, uSunDims, uSunToGrid[], uSunToWorld[],
  // uSunColumns) on the program in use; `prefix` names another set of them (the zenith volume's
  // "uZenith", zenith_volume_sampling.glsl), whose missing uniforms are left alone.
  void bind(const ProgramUniforms& uniforms, int unit, const std::string& prefix = "uSun") const;

  // The volume read back: τ per node, cascade after cascade (each Nu × Nv × Nw, u fastest).
  std::vector<float> readBack() const;
  const SunVolumeGrid& grid() const { return grid_; }

  // The #defines a shader that samples the volume needs (SUN_CASCADES_MAX).
  static std::string samplingDefines();
  static constexpr unsigned kGroupSize = 64;  // threads (particles or columns) per work group

 private:
  const GlFunctions& gl_;
  const GlContext& context_;
  const StorageBudget& budget_;
  ParticleBuffers& buffers_;
  GlProgram stages_[2];
  StorageBuffer deltas_;  // binding 5: overflow counter, then Nw + 1 fixed-point slots per column
  GLuint texture_ = 0;
  glm::ivec3 textureDims_{0};
  SunVolumeGrid grid_;
};

}  // namespace cloudlut::render
