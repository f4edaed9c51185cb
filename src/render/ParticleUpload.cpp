#include "render/ParticleUpload.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include <glm/geometric.hpp>

#include "core/Errors.h"

namespace cloudlut::render {

float ParticleUpload::upload(const std::vector<scene::Particle>& particles, const glm::vec3& eye,
                             const glm::vec3& sunDirection) {
  const std::size_t maxParticles = budget_.maxBlockBytes() / sizeof(GpuParticleRecord);
  if (particles.size() > maxParticles)
    throw UsageError(std::to_string(particles.size()) + " particles exceed this OpenGL's shader storage limit of " +
                     std::to_string(maxParticles) + " particles per render");
  records_.assign(particles.size(), GpuParticleRecord{});
  float farthest = 0.0f;
  for (std::size_t k = 0; k < particles.size(); ++k) {
    const scene::Particle& p = particles[k];
    records_[k] = packParticle(p, sunDirection);
    const float reach = std::sqrt(3.0f) * std::max({p.radii.x, p.radii.y, p.radii.z});
    farthest = std::max(farthest, glm::length(p.center - eye) + reach);
  }
  buffers_.records.assign(records_.empty() ? nullptr : records_.data(),
                          std::max<std::size_t>(records_.size(), 1) * sizeof(GpuParticleRecord));
  return std::max(farthest * 1.01f, 1e-3f);
}

void ParticleUpload::uploadDrawOrder(const std::vector<std::size_t>& order) {
  std::vector<std::uint32_t> keys(2 * std::max<std::size_t>(order.size(), 1), 0u);
  for (std::size_t k = 0; k < order.size(); ++k) keys[2 * k + 1] = static_cast<std::uint32_t>(order[k]);
  buffers_.sortKeys.assign(keys.data(), keys.size() * sizeof(std::uint32_t));
}

}  // namespace cloudlut::render
