#pragma once
// Upload of explicit particles (a scene's list) into the particle records (GpuParticleRecord.h),
// in the list's order, and of the order a frame draws them in (back to front for alpha blending and
// for volume blending's hidden-fragment culling, which draws it reversed) as the sort keys the
// particle pass follows (ParticleBuffers::sortKeys). The records do not depend on the camera, so
// the light-space volumes built from them (LightSpaceInputs.h) hold while it moves.
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

  // Record k = particles[k] packed for the sun toward `sunDirection` (unit). Returns the far plane
  // that holds them all seen from `eye`:
  //   far = max(1.01 · max_k (|c_k − eye| + √3 · max radius_k), 1e-3)  (world units),
  // √3 · radius bounding the particle's box. UsageError when the records exceed one storage buffer.
  float upload(const std::vector<scene::Particle>& particles, const glm::vec3& eye, const glm::vec3& sunDirection);
  // Sort key k = (0, order[k]): the particle pass draws record order[k] k-th (useOrder).
  void uploadDrawOrder(const std::vector<std::size_t>& order);
  // The records of the last upload, in order.
  const std::vector<GpuParticleRecord>& records() const { return records_; }

 private:
  const StorageBudget& budget_;
  ParticleBuffers& buffers_;
  std::vector<GpuParticleRecord> records_;
};

}  // namespace cloudlut::render
