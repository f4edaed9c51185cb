#pragma once
// Light-space occlusion (seed §5.3; shaders/occlusion.comp.glsl): the sunlight that reaches each
// particle through the others, written into the records' sunlight slot (toParticle[2].w).
//   1. the particles' bounds seen from the sun (light-space axes u, v ⟂ l);
//   2. a T² grid over those bounds, T = lightTilesFor(N): about kParticlesPerLightTile particle
//      centres per tile whatever N. Two bins per tile, filled by counting, a prefix sum and a
//      scatter on the GPU: the particles whose centre it holds, and those that, widened by half a
//      tile, cover it; each bin sorted (deterministic sums). The particles are then taken in the
//      order of their centre bins, copied so that a tile's particles lie together in memory: each
//      particle tests a bounded number of others, read from nearby memory, and the pass grows
//      about as N (not N², as a fixed grid does, nor with cache misses as linked lists do);
//   3. per particle, the ray from its centre toward the sun against every other particle of the
//      cover bin of the tile holding the centre: sunlight = exp(−ξ Σ τ), τ = ρ σ · (chord through
//      the homogeneous ellipsoid, unit-sphere units), σ the tables' unit optical radius,
//      ξ = kOcclusionXi;
//   4. optionally (smoothing), a density-weighted mean of the sunlight over the particles of the
//      same cover bin within twice the particle's reach, weights ρ · (1 − distance / (2 · reach)).
#include <cstddef>
#include <vector>

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
  // units per unit density. Returns the cover-bin entries dropped for want of room (more than one
  // storage block holds; 0 normally).
  std::size_t run(std::size_t count, const RenderSettings& settings, float unitOpticalRadius, bool countOverflow);

  static constexpr unsigned kGroupSize = 64;  // threads (particles) per work group

 private:
  const GlFunctions& gl_;
  const StorageBudget& budget_;
  ParticleBuffers& buffers_;
  std::vector<GlProgram> stages_;  // occlusion.comp.glsl, STAGE 0 … 10
  StorageBuffer tiles_;        // binding 3: bounds, totals, per-tile counts, starts, row totals
  StorageBuffer cover_;        // binding 7: the cover bins (binned positions)
  StorageBuffer rawSunlight_;  // binding 4: sunlight before smoothing, per binned position
  StorageBuffer order_;        // binding 5: binned position → particle index
  StorageBuffer occluders_;    // binding 6: the particles in binned order (centre, ρ, inverse, reach)
};

}  // namespace cloudlut::render
