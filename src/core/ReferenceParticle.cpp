#include "core/ReferenceParticle.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <tbb/parallel_for.h>

#include <glm/geometric.hpp>

#include "core/Noise.h"

namespace cloudlut {

std::optional<DensityModel> parseDensityModel(std::string_view name) {
  if (name == "noise") return DensityModel::Noise;
  if (name == "threshold") return DensityModel::Threshold;
  if (name == "pyroclastic") return DensityModel::Pyroclastic;
  if (name == "radial") return DensityModel::Radial;
  if (name == "sphere") return DensityModel::Sphere;
  return std::nullopt;
}

std::string toString(DensityModel model) {
  switch (model) {
    case DensityModel::Noise: return "noise";
    case DensityModel::Threshold: return "threshold";
    case DensityModel::Pyroclastic: return "pyroclastic";
    case DensityModel::Radial: return "radial";
    case DensityModel::Sphere: return "sphere";
  }
  return "unknown";
}

namespace {

float smoothstep(float e0, float e1, float x) {
  const float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

// The procedural density the grid samples, ρ̂ ∈ [0, 1].
float proceduralDensity(DensityModel model, const GradientNoise& noise, const glm::vec3& p) {
  const float r2 = glm::dot(p, p);
  if (r2 > 1.0f) return 0.0f;
  const float r = std::sqrt(r2);
  const float falloff = ReferenceParticle::radialFalloff(r2);
  switch (model) {
    case DensityModel::Noise: {
      // fall-off times a noise around 1: dense core, ragged holes and a soft edge
      const float n = 0.5f + 0.5f * noise.fbm(p * 2.5f, 3);
      return std::clamp(2.0f * falloff * (0.25f + 1.5f * n) - 0.15f, 0.0f, 1.0f);
    }
    case DensityModel::Threshold: {
      const float n = 0.5f + 0.5f * noise.fbm(p * 3.0f, 3);
      return smoothstep(0.42f, 0.58f, n + 0.35f * falloff - 0.1f) * smoothstep(1.0f, 0.85f, r);
    }
    case DensityModel::Pyroclastic: {
      const glm::vec3 dir = r > 1e-6f ? p / r : glm::vec3(0.0f, 0.0f, 1.0f);
      const float turbulence = std::fabs(noise.fbm(dir * 2.0f, 4));
      const float radius = 0.62f + 0.55f * turbulence;
      return std::clamp((std::min(radius, 0.97f) - r) / 0.06f, 0.0f, 1.0f);
    }
    default: return 0.0f;
  }
}

}  // namespace

ReferenceParticle::ReferenceParticle(DensityModel model, std::uint64_t seed, int gridResolution)
    : model_(model), seed_(seed), res_(gridResolution) {
  if (model == DensityModel::Sphere || model == DensityModel::Radial) return;
  if (res_ < 4 || res_ > 1024) throw std::invalid_argument("density grid resolution out of range");
  const GradientNoise noise(seed);
  const std::size_t n = static_cast<std::size_t>(res_);
  grid_.resize(n * n * n);
  const float h = 2.0f / static_cast<float>(res_ - 1);
  tbb::parallel_for(std::size_t{0}, n, [&](std::size_t k) {
    for (std::size_t j = 0; j < n; ++j)
      for (std::size_t i = 0; i < n; ++i) {
        const glm::vec3 p(-1.0f + h * static_cast<float>(i), -1.0f + h * static_cast<float>(j),
                          -1.0f + h * static_cast<float>(k));
        grid_[(k * n + j) * n + i] = proceduralDensity(model_, noise, p);
      }
  });
}

}  // namespace cloudlut
