#pragma once
// The particle renderer (seed §4.4, §5.4): each particle's bounding box is rasterised, the
// fragment shader intersects the view ray with the ellipsoid and shades it from the tables;
// particles are blended back to front, or composited exactly per pixel (volume blending).
//
// Shading of one particle along one ray (particle space, unit-sphere units; docs/ENGINE_GUIDE.md §2):
//   S, v   entry point and unit direction of the ray mapped into the particle's unit sphere;
//   l      the world sun direction mapped by the particle's inverse transform, renormalised;
//   τ      = ρ · σ · L · T̄, L = 2 cos θv the chord, T̄ the optical-depth table's mean density,
//          σ = extinction_per_m · radius_m of the optical-depth table. The particle's size in
//          the world does not enter: every particle is the reference particle of optical
//          radius σ·ρ (to make a particle of radius r optically as thick as a reference
//          particle of radius R would be, give it ρ·r/R);
//   single = P1(cos θ) · (1 − e^{−τ}) · J̄1(S, v, l, ρ·T̄): the mean source J̄1 (mean sun
//          transmittance) of the homogeneous sphere of the ray's mean density, P1 the single
//          table's "first_phase", cos θ the world-space scattering angle (dir · sun; equal to
//          v·l unless the particle is non-uniformly scaled);
//   multiple = (1 − e^{−τ}) · J̄M(S, v, l, ρ): the ray's own opacity, so that the transparent
//          fringe of a particle does not glow (single/multipleScatteringFromTable decode the tables);
//   ambient  = sky · ambientScale(e^{−τ}, d), d the distance to the first matter as a fraction
//          of the chord (table channel 1): rays that meet matter at once take the full sky
//          light, rays whose matter lies deep along the chord half of it;
//   (both functions: lut_formats/glsl/cloudlut_shading.glsl, shared with the C++ tests)
//   radiance = sunColor · sunlight · (single + multiple) + ambient, sunlight from the light-space
//          occlusion pass (seed §5.3; 1 when disabled).
//
// A frame is a sequence of passes, one per file:
//   ParticleUpload (explicit particles) or CloudscapeGeneration (GPU generation + bitonic sort)
//   → LightOcclusion → ParticlePass (alpha blending, or fragment lists) → VolumeResolve (volume
//   blending) → Upscale (when rendered at 1/downscale resolution) → read-back.
// Cloudscapes (renderCloudscape): particles generated on the GPU from a cloud type and a quality
// preset (scene/Cloudscape.h).
#include <memory>
#include <vector>

#include "io/LutIo.h"
#include "render/GlContext.h"
#include "render/RenderTypes.h"
#include "scene/Cloudscape.h"
#include "render/SunVolumeGrid.h"
#include "scene/Scene.h"

namespace cloudlut::render {

class Renderer {
 public:
  // Uses the set's "optical_depth", "single_scattering" and "multiple_scattering" tables
  // (FileError naming the directory when one is missing or unusable) and uploads them as 3D
  // textures in their file layout. The context must stay alive and current.
  Renderer(GlContext& context, const io::LutSet& luts);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // The atmosphere's tables (bake/AtmosphereBaker.h) for frames whose sky is the atmosphere
  // (scene::Lighting::atmosphere): render/SkyPass.h composites them under it. Until they are
  // given, such frames render under the uniform sky of the lighting's skyColor.
  void setAtmosphereTables(const glsl::AtmosphereParameters& atmosphere, const Table4D& transmittance,
                           const Table4D& multipleScattering, const Table4D& irradiance);

  // One frame of explicit particles. With settings.keepLighting it reuses the light-space volumes
  // of the frame before when they would be built from the same inputs (LightSpaceInputs.h;
  // stats->lightSpaceKept says so): the same image. When only the sun moved it builds the sun
  // volume again, keeps the others and starts the diffusion solve from the last one
  // (stats->lightSpaceSunOnly, stats->diffusionWarm; RenderSettings::diffusionWarmCycles).
  Image render(const std::vector<scene::Particle>& particles, const RenderSettings& settings,
               RenderStats* stats = nullptr);

  // A procedural cloudscape, generated on the GPU for the settings' camera.
  Image renderCloudscape(const scene::CloudType& cloud, const scene::QualityPreset& quality, const RenderSettings& settings,
                         RenderStats* stats = nullptr);

  // The GPU generation alone, read back (for tests against generateCloudscapeCpu).
  scene::CpuGeneration generateOnGpu(const scene::CloudType& cloud, const scene::QualityPreset& quality, const RenderSettings& settings);

  // Sunlight reaching each particle after the occlusion pass (same order as `particles`).
  std::vector<float> sunlight(const std::vector<scene::Particle>& particles, const RenderSettings& settings);

  // The sun optical-depth volume the cloud lighting builds for `particles` under `settings`
  // (docs/LIGHTING.md), over `grid` when given (e.g. a cloudscape's cascades,
  // sunVolumeGridForLayer), else over the grid a particle scene gets: the grid, the optical depth
  // toward the sun at every node (dimensionless; SunVolume::readBack's order, cascades stacked
  // along the slices) and the particle-cascade pairs skipped for their footprint, for tests and
  // tools.
  struct SunVolumeSnapshot {
    SunVolumeGrid grid;
    std::vector<float> tau;
    std::size_t footprintOverflow = 0;
  };
  SunVolumeSnapshot sunVolume(const std::vector<scene::Particle>& particles, const RenderSettings& settings,
                              const SunVolumeGrid* grid = nullptr);

  // The diffusion volume (render/DiffusionVolume.h) the cloud lighting solves for `particles`
  // under `settings`: its grid (one cascade; its node n at toWorld[0]·n), per node φ and J
  // (`field`, DiffusionVolume::readBack) and σ*, q, φ and D (`solve`, readSolve); both empty when
  // the frame would get no field (--diffusion 0, no multiple term, no particles). For tests and
  // tools.
  struct DiffusionSnapshot {
    SunVolumeGrid grid;
    std::vector<float> field, solve;
  };
  DiffusionSnapshot diffusionVolume(const std::vector<scene::Particle>& particles, const RenderSettings& settings);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Particles sorted back to front: decreasing distance from `eye` to the centre (ties keep
// their order). Returns indices into `particles`.
std::vector<std::size_t> backToFrontOrder(const std::vector<scene::Particle>& particles, const glm::vec3& eye);

}  // namespace cloudlut::render
