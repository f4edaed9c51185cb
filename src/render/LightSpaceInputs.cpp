#include "render/LightSpaceInputs.h"

#include <cstring>

namespace cloudlut::render {
namespace {

// Exact equality of two grids: cascades, dims, every cascade's matrices, slice axis, sun, local
// cloud window.
bool sameGrid(const SunVolumeGrid& a, const SunVolumeGrid& b) {
  if (a.cascades != b.cascades || a.dims != b.dims || a.sliceAxis != b.sliceAxis || a.sun != b.sun ||
      a.localCloud != b.localCloud)
    return false;
  for (int c = 0; c < a.cascades && c < kSunCascadesMax; ++c)
    if (a.toGrid[c] != b.toGrid[c] || a.toWorld[c] != b.toWorld[c]) return false;
  return true;
}

}  // namespace

bool reusable(const LightSpaceInputs& built, const LightSpaceInputs& frame) {
  // GpuParticleRecord is seven vec4 of floats, no padding: the bytes are the values
  if (built.records.size() != frame.records.size() ||
      (!frame.records.empty() &&
       std::memcmp(built.records.data(), frame.records.data(), frame.records.size() * sizeof(GpuParticleRecord)) != 0))
    return false;
  if (built.sun != frame.sun || built.zenith != frame.zenith || built.diffusion != frame.diffusion) return false;
  if (frame.sun && (!sameGrid(built.sunGrid, frame.sunGrid) || built.sunChordMap != frame.sunChordMap ||
                    (frame.countsOverflow && !built.countsOverflow)))
    return false;
  if (frame.zenith && !sameGrid(built.zenithGrid, frame.zenithGrid)) return false;
  if (frame.diffusion &&
      (!sameGrid(built.diffusionGrid, frame.diffusionGrid) || built.diffusionSweeps != frame.diffusionSweeps ||
       built.diffusionCycles != frame.diffusionCycles || built.diffusionBeside != frame.diffusionBeside ||
       built.diffusionFade != frame.diffusionFade))
    return false;
  return true;
}

}  // namespace cloudlut::render
