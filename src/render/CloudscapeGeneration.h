#pragma once
// GPU generation of a procedural cloudscape (seed §5.2) into the particle records, and the
// bitonic sort of their back-to-front keys (shaders/cloudscape_generate.comp.glsl,
// shaders/bitonic_sort.comp.glsl): the cells of the camera-centred clipmap grid
// (scene/glsl/cloudscape_grid.glsl) that are non-empty and within the far distance are listed, then
// each listed cell emits its particles within the far distance as records, whatever the frustum
// (the light-space passes take them all: a particle out of view still shadows and makes up the
// clouds in view), and those in the frustum also as keys (distance from the eye to the centre,
// record index), the ones the particle pass draws. The sort orders the keys by decreasing
// distance (ties by index) for alpha blending, and for volume blending's hidden-fragment culling,
// which draws them reversed (render/HiddenFragments.h); the occlusion needs no order.
#include <cstddef>

#include "render/GlFunctions.h"
#include "render/GlResources.h"
#include "render/GpuParticleRecord.h"
#include "render/GpuStorage.h"
#include "render/RenderTypes.h"
#include "scene/Cloudscape.h"

namespace cloudlut::render {

class CloudscapeGeneration {
 public:
  CloudscapeGeneration(const GlFunctions& gl, const StorageBudget& budget, ParticleBuffers& buffers);

  struct Result {
    std::size_t count = 0;    // records written (at most the quality's particle slots): the light-space set
    std::size_t visible = 0;  // of those, the ones in the frustum: the first `visible` keys index them
    std::size_t cells = 0;    // non-empty cells within the far distance
    // World distance that holds every particle: the modelled far distance + 2 · the largest
    // radius of the outer ring + 1.
    float farPlane = 1.0f;
  };

  // Generates for the settings' camera and sun with the tables' reference radius R (m; UsageError
  // when the quality's buffers exceed the storage budget or its layers exceed kGridLayerLimit);
  // sorts the keys when `sortKeys`.
  Result run(const scene::CloudType& cloud, const scene::QualityPreset& quality, const RenderSettings& settings,
             bool sortKeys, float referenceRadius);

  // The records the first `visible` keys index (the particles drawn) as grid particles
  // (unpackGridParticle), and how many records the light-space passes take (CpuGeneration::lit).
  scene::CpuGeneration readBack(const Result& generated, const scene::CloudType& cloud,
                                const scene::QualityPreset& quality, const RenderSettings& settings) const;

  static constexpr unsigned kGroupSize = 64;  // threads per work group, generation and sort

 private:
  void sort(std::size_t count);

  const GlFunctions& gl_;
  const StorageBudget& budget_;
  ParticleBuffers& buffers_;
  GlProgram stages_[3];  // cell list, indirect arguments, particles
  GlProgram sort_;
  StorageBuffer cells_;  // binding 6: counters, indirect dispatch arguments, the cell list
};

}  // namespace cloudlut::render
