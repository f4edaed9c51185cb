#pragma once
// Light-space occlusion (seed §5.3; shaders/occlusion.comp.glsl): the sunlight that reaches each
// particle through the others, written into the records' sunlight slot (toParticle[2].w).
//   1. the particles' bounds seen from the sun (light-space axes u, v ⟂ l);
//   2. each particle, widened by half a tile, is listed in every tile of a T² grid over those
//      bounds that it covers, T = lightTilesFor(N): about kParticlesPerLightTile particle centres
//      per tile whatever N, so each particle tests a bounded number of others and the pass grows
//      about as N (not N², as a fixed grid does);
//   3. per particle, the ray from its centre toward the sun against every other particle of the
//      tile holding the centre: sunlight = exp(−ξ Σ τ), τ = ρ σ · (chord through the homogeneous
//      ellipsoid, unit-sphere units), σ the tables' unit optical radius, ξ = kOcclusionXi;
//   4. optionally (smoothing), a density-weighted mean of the sunlight over the particles of the
//      same tile within twice the particle's reach, weights ρ · (1 − distance / (2 · reach)).
#include <cstddef>

#include "render/GlFunctions.h"
#include "render/GlResources.h"
#include "render/GpuParticleRecord.h"
#include "render/GpuStorage.h"
#include "render/RenderTypes.h"

namespace cloudlut::render {

// Tiles per side of the light-space grid for `count` particles:
// clamp(⌈√(count / kParticlesPerLightTile)⌉, kLightTiles, kMaxLightTiles).
inline constexpr double kParticlesPerLightTile = 4.0;
inline constexpr int kMaxLightTiles = 1024;
int lightTilesFor(std::size_t count);

class LightOcclusion {
 public:
  LightOcclusion(const GlFunctions& gl, const StorageBudget& budget, ParticleBuffers& buffers);

  // Over the first `count` records, for the settings' sun and smoothing choice; σ in unit-sphere
  // units per unit density. Returns the tile-list nodes dropped for want of room (0 normally).
  std::size_t run(std::size_t count, const RenderSettings& settings, float unitOpticalRadius, bool countOverflow);

  static constexpr unsigned kGroupSize = 64;  // threads (particles) per work group

 private:
  const GlFunctions& gl_;
  const StorageBudget& budget_;
  ParticleBuffers& buffers_;
  GlProgram stages_[4];
  StorageBuffer tiles_;        // binding 3: bounds, node counters, tile heads
  StorageBuffer nodes_;        // binding 7: tile-list nodes
  StorageBuffer rawSunlight_;  // binding 4: stage 3's result before smoothing
};

}  // namespace cloudlut::render
