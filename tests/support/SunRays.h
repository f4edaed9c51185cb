#pragma once
// The optical depth toward the sun integrated from the particles' density on the CPU, and the
// renderer the light-space tests build their volumes with. The integration samples the reference
// particle's density itself, so it shares nothing with the renderer but the particles.
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <glm/geometric.hpp>

#include "bake/OpticalDepthBaker.h"
#include "core/Medium.h"
#include "core/ReferenceParticle.h"
#include "io/LutIo.h"
#include "render/GlContext.h"
#include "render/Renderer.h"
#include "scene/Scene.h"
#include "RenderLuts.h"
#include "TempDir.h"

namespace cloudlut::test {

// Optical depth (dimensionless) along x + t·sun, t ≥ 0, through the particles: Σ ∫ ρ σ
// ρ̂(M⁻¹(y − c)) |M⁻¹ dy|, midpoint rule, `stepsPerRadius` steps per least radius (world units).
inline double integratedSunDepth(const std::vector<scene::Particle>& particles, const ReferenceParticle& ref,
                                 double sigma, const glm::vec3& x, const glm::vec3& sun, int stepsPerRadius = 256) {
  double tau = 0;
  for (const scene::Particle& p : particles) {
    const glm::mat3 inv = p.toParticle();
    const float reach = std::max({p.radii.x, p.radii.y, p.radii.z});
    // the part of the ray within reach of the centre
    const glm::vec3 oc = x - p.center;
    const float b = glm::dot(oc, sun), c = glm::dot(oc, oc) - reach * reach;
    const float disc = b * b - c;
    if (disc <= 0) continue;
    const float t0 = std::max(0.0f, -b - std::sqrt(disc)), t1 = -b + std::sqrt(disc);
    if (t1 <= t0) continue;
    const float ds = std::min({p.radii.x, p.radii.y, p.radii.z}) / static_cast<float>(stepsPerRadius);
    const int n = static_cast<int>(std::ceil((t1 - t0) / ds));
    const double step = static_cast<double>(t1 - t0) / n, unitStep = glm::length(inv * sun) * step;
    double sum = 0;
    for (int i = 0; i < n; ++i) {
      const glm::vec3 y = inv * (x + sun * static_cast<float>(t0 + (i + 0.5) * step) - p.center);
      sum += ref.density(y);
    }
    tau += p.density * sigma * sum * unitStep;
  }
  return tau;
}

// A renderer on the reference particle's optical-depth table (64×32×64×32) and synthetic
// scattering tables, which the light-space volumes do not read.
struct SunVolumeRig {
  TempDir tmp;
  const Medium medium;
  const ReferenceParticle ref{medium.model, medium.seed};
  io::LutSet luts;
  std::unique_ptr<render::GlContext> context;
  std::unique_ptr<render::Renderer> renderer;

  SunVolumeRig() {
    bake::OpticalDepthSettings ods;
    ods.dims = {64, 32, 64, 32};
    const Table4D od = bake::bakeOpticalDepth(ref, ods);
    const Table4D l1 = syntheticSingle(), lm = syntheticMultiple();
    writeLutSet(tmp / "luts", {&od, &l1, &lm});
    luts = io::readLutSet(tmp / "luts");
    context = render::createHeadlessContext();
    renderer = std::make_unique<render::Renderer>(*context, luts);
  }
};

}  // namespace cloudlut::test
