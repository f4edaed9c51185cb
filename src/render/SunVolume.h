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
// The sun volume also keeps the chords it splatted (the chord map, shaders/sun_chord_map.glsl),
// which the particle shader reads to take each particle's own ramp back out.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include <glm/vec4.hpp>

#include "render/GlContext.h"
#include "render/GlFunctions.h"
#include "render/GlResources.h"
#include "render/GpuParticleRecord.h"
#include "render/GpuStorage.h"
#include "render/SplatTable.h"
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
  // optical-depth table, laid as it says (SplatTable). UsageError when the grid needs
  // more storage than this OpenGL allows. With keepChords it fills the chord map too (the sun
  // volume; the zenith volume has no use for it), if the budget holds every chord of the
  // frame (chordMapComplete; otherwise the particle shader computes them). Returns the
  // particle-cascade pairs skipped for a footprint over kSunFootprintMax when `countOverflow`
  // (0 otherwise).
  std::size_t build(const SunVolumeGrid& grid, std::size_t count, const SplatTable& table, bool countOverflow,
                    bool keepChords = false);

  // Binds the volume texture to `unit` and sets the sampling uniforms of
  // sun_volume_sampling.glsl (uSunTau, uSunCascades, uSunDims, uSunToGrid[], uSunToWorld[],
  // uSunColumns, uSunLocalCloud, uSunChordOuterThird) on the program in use; `prefix` names another set of them (the zenith volume's
  // "uZenith", zenith_volume_sampling.glsl), whose missing uniforms are left alone.
  void bind(const ProgramUniforms& uniforms, int unit, const std::string& prefix = "uSun") const;
  // Binds the chord map's two buffers as buffer textures (shaders/sun_chord_map.glsl,
  // uSunChordFootprintTexels and uSunChordTexels) to texture units `unit` and `unit` + 1 of the
  // program in use, for the particle shader.
  void bindChordMap(const ProgramUniforms& uniforms, int unit) const;
  // The last build kept every chord it splatted: shaders compiled with samplingDefines(true) may read them.
  bool chordMapComplete() const { return mapped_; }

  // The volume read back: τ per node, cascade after cascade (each Nu × Nv × Nw, u fastest).
  std::vector<float> readBack() const;
  // The chords (footprint columns) the last build's chord map needed (0 without one).
  std::size_t chordsNeeded() const { return chordsNeeded_; }
  const SunVolumeGrid& grid() const { return grid_; }
  // The volume's R32F 3D texture (0 before the first build).
  GLuint texture() const { return texture_; }

  // The #defines a shader that samples the volume needs (SUN_CASCADES_MAX; SUN_CHORD_MAP, 1 for
  // a particle shader that reads the chord map, sun_volume_sampling.glsl).
  static std::string samplingDefines(bool chordMap = false);
  static constexpr unsigned kGroupSize = 64;  // threads (particles or columns) per work group

 private:
  // Sizes the chord map for `count` particles: STAGE 2 (run(2)) counts the chords it needs. False
  // when the budget cannot hold them; else sized and both of its buffers bound for the splat.
  bool sizeChordMap(std::size_t count, const std::function<void(int)>& run);
  const GlFunctions& gl_;
  const GlContext& context_;
  const StorageBudget& budget_;
  ParticleBuffers& buffers_;
  bool mapped_ = false;   // the last build filled the chord map
  GlProgram stages_[3];   // splat, integration, the chord map's count (sun_volume_build.comp.glsl)
  StorageBuffer deltas_;  // binding 5: overflow counter, then Nw + 1 fixed-point slots per column
  StorageBuffer footprints_;  // binding 9: per particle and cascade, where its chords are (sun_chord_map.glsl)
  StorageBuffer chords_;      // binding 10: counters, then one vec4 per footprint column
  std::size_t chordsNeeded_ = 0;
  BufferTexels footprintTexels_;  // over footprints_, RGBA32I (the particle shader's reads)
  BufferTexels chordTexels_;      // over chords_, RGBA32F
  GLuint texture_ = 0;
  glm::ivec3 textureDims_{0};
  SunVolumeGrid grid_;
  float chordOuterThird_ = 1.0f / 3.0f;  // the last build's (SplatTable), for the sampling shaders
};

}  // namespace cloudlut::render
