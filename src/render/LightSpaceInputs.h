#pragma once
// What a frame's light-space volumes are built from: the sun optical-depth volume, the zenith
// volume and the diffusion volume (render/Renderer.cpp, illuminate). None of them depends on the
// camera, only on the particle records (in the list's order, whatever the draw order: the sun
// volume's chord map is indexed by record; ParticleUpload.h), the grids (around the camera only
// for a scene too wide for one grid), the solve's parameters and whether the build counts what it
// leaves out. A frame whose inputs equal the last build's reuses the volumes
// (RenderSettings::keepLighting): still clouds under a still sun are not lit again while the
// camera moves. The reuse is exact: the same inputs build the same volumes bit for bit.
#include <cstddef>
#include <vector>

#include "render/GpuParticleRecord.h"
#include "render/SunVolumeGrid.h"

namespace cloudlut::render {

struct LightSpaceInputs {
  std::vector<GpuParticleRecord> records;  // as uploaded (ParticleUpload::records)
  bool sun = false, zenith = false, diffusion = false;  // the volumes built
  SunVolumeGrid sunGrid, zenithGrid, diffusionGrid;  // compared only for the volumes built
  bool sunChordMap = false;     // the sun volume keeps its chords (RenderSettings::sunChordMap)
  bool countsOverflow = false;  // the sun volume's build counted the footprints it skipped
  int diffusionSweeps = 0, diffusionCycles = 0;
  float diffusionBeside = 0.0f, diffusionFade = 0.0f;  // world units, nodes
};

// True when `frame` can reuse volumes built from `built`: every volume the frame needs was built
// from equal inputs (records byte for byte, grids and parameters exactly), and the build counted
// the skipped footprints if the frame wants them counted.
bool reusable(const LightSpaceInputs& built, const LightSpaceInputs& frame);

// A frame that cannot reuse everything (not reusable) because the sun moved: the volumes that do
// not depend on the sun and stand as built. The particles must be the built ones in everything but
// the two words of a record that follow the sun (toParticle[0].w, the extinction scale toward it,
// and toParticle[2].w, the sunlight; GpuParticleRecord.h), and the volume's grid and parameters
// the built ones'.
struct SunIndependentReuse {
  bool zenith = false;            // the zenith volume: exact
  bool diffusionColumns = false;  // the diffusion's column volume: exact
  // the diffusion's columns kept and the sun moved: the solve may start from the last one
  // (DiffusionVolume::build, warm start); with the sun where it was (another change, e.g. the
  // chord map), the solve is the whole one, and the frame the one built from nothing
  bool diffusionWarmStart = false;
};
SunIndependentReuse reusableUnderMovedSun(const LightSpaceInputs& built, const LightSpaceInputs& frame);

}  // namespace cloudlut::render
