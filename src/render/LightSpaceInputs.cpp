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

// The records byte for byte, or (sunWordsAside) but for toParticle[0].w and toParticle[2].w.
bool sameRecords(const std::vector<GpuParticleRecord>& a, const std::vector<GpuParticleRecord>& b,
                 bool sunWordsAside) {
  if (a.size() != b.size()) return false;
  // GpuParticleRecord is seven vec4 of floats, no padding: the bytes are the values
  if (!sunWordsAside) return a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(GpuParticleRecord)) == 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    GpuParticleRecord x = a[i], y = b[i];
    x.toParticle[0][3] = y.toParticle[0][3] = 0.0f;
    x.toParticle[2][3] = y.toParticle[2][3] = 0.0f;
    if (std::memcmp(&x, &y, sizeof x) != 0) return false;
  }
  return true;
}

bool sameDiffusion(const LightSpaceInputs& built, const LightSpaceInputs& frame) {
  return sameGrid(built.diffusionGrid, frame.diffusionGrid) && built.diffusionSweeps == frame.diffusionSweeps &&
         built.diffusionCycles == frame.diffusionCycles && built.diffusionBeside == frame.diffusionBeside &&
         built.diffusionFade == frame.diffusionFade;
}

}  // namespace

SunIndependentReuse reusableUnderMovedSun(const LightSpaceInputs& built, const LightSpaceInputs& frame) {
  SunIndependentReuse reuse;
  if (!sameRecords(built.records, frame.records, true)) return reuse;
  reuse.zenith = built.zenith && frame.zenith && sameGrid(built.zenithGrid, frame.zenithGrid);
  reuse.diffusionColumns = built.diffusion && frame.diffusion && sameDiffusion(built, frame);
  reuse.diffusionWarmStart = reuse.diffusionColumns && built.sun && frame.sun && built.sunGrid.sun != frame.sunGrid.sun;
  return reuse;
}

bool reusable(const LightSpaceInputs& built, const LightSpaceInputs& frame) {
  if (!sameRecords(built.records, frame.records, false)) return false;
  if (built.sun != frame.sun || built.zenith != frame.zenith || built.diffusion != frame.diffusion) return false;
  if (frame.sun && (!sameGrid(built.sunGrid, frame.sunGrid) || built.sunChordMap != frame.sunChordMap ||
                    (frame.countsOverflow && !built.countsOverflow)))
    return false;
  if (frame.zenith && !sameGrid(built.zenithGrid, frame.zenithGrid)) return false;
  if (frame.diffusion && !sameDiffusion(built, frame)) return false;
  return true;
}

}  // namespace cloudlut::render
