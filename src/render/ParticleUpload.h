#pragma once
// Upload of explicit particles (a scene's list) into the particle records (GpuParticleRecord.h),
// in a given order: back to front for a frame's draw (volume blending draws it reversed), as given
// for the light-space passes alone.
#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

#include "render/GpuParticleRecord.h"
#include "render/GpuStorage.h"
#include "scene/Scene.h"

namespace cloudlut::render {

class ParticleUpload {
 public:
  ParticleUpload(const StorageBudget& budget, ParticleBuffers& buffers) : budget_(budget), buffers_(buffers) {}

  // Record k = particles[order[k]] packed for the sun toward `sunDirection` (unit). Returns the
  // far plane that holds them all seen from `eye`:
  //   far = max(1.01 · max_k (|c_k − eye| + √3 · max radius_k), 1e-3)  (world units),
  // √3 · radius bounding the particle's box. UsageError when the records exceed one storage buffer.
  float upload(const std::vector<scene::Particle>& particles, const std::vector<std::size_t>& order,
               const glm::vec3& eye, const glm::vec3& sunDirection);

 private:
  const StorageBudget& budget_;
  ParticleBuffers& buffers_;
};

}  // namespace cloudlut::render
