#include "bake/OpticalDepthBaker.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/Defaults.h"
#include "core/Glsl.h"

namespace cloudlut::bake {

namespace {

// Two-point Gauss–Legendre abscissae on a unit panel: 1/2 ∓ 1/(2√3).
constexpr float kGaussLo = 0.2113248654f;
constexpr float kGaussHi = 0.7886751346f;
constexpr int kBisections = 4;

// First crossing of the matter threshold between t0 (density d0 below it) and t1 (d1 at or
// above it): a few bisections, then the linear interpolation of the last bracket.
float refineCrossing(const ReferenceParticle& particle, const glm::vec3& S, const glm::vec3& v,
                     float t0, float d0, float t1, float d1, float threshold) {
  for (int i = 0; i < kBisections; ++i) {
    const float tm = 0.5f * (t0 + t1);
    const float dm = particle.density(S + tm * v);
    if (dm >= threshold) { t1 = tm; d1 = dm; } else { t0 = tm; d0 = dm; }
  }
  const float w = d1 > d0 ? (threshold - d0) / (d1 - d0) : 0.5f;
  return t0 + std::clamp(w, 0.0f, 1.0f) * (t1 - t0);
}

}  // namespace

int defaultSteps(DensityModel model) {
  switch (model) {
    case DensityModel::Sphere: return 2;  // exact: the integrand is constant
    case DensityModel::Radial: return 16;  // quartic in t: 2-point Gauss panels are near exact
    case DensityModel::Noise: return 32;
    case DensityModel::Threshold: return 64;  // sharper transitions need finer panels
    case DensityModel::Pyroclastic: return 72;
  }
  return 32;
}

ChordIntegral integrateChord(const ReferenceParticle& particle, const glm::vec3& S,
                             const glm::vec3& v, int steps) {
  const float threshold = defaults::kFirstMatterThreshold;
  const float L = glsl::chordLength(S, v);
  // Points exactly on the sphere may round to just outside it: pull S in by a hair.
  const glm::vec3 s = S * (1.0f - 1e-6f);
  const float atS = particle.density(s);
  if (L < 1e-6f) return {atS, atS >= threshold ? 0.0f : 1.0f};

  const int panels = std::max(1, static_cast<int>(std::ceil(0.25f * static_cast<float>(steps) * L)));
  const float h = L / static_cast<float>(panels);
  double sum = 0.0;
  float first = atS >= threshold ? 0.0f : -1.0f;
  float tPrev = 0.0f, dPrev = atS;
  for (int p = 0; p < panels; ++p) {
    const float a = h * static_cast<float>(p);
    const float ts[2] = {a + kGaussLo * h, a + kGaussHi * h};
    for (float t : ts) {
      const float d = particle.density(s + t * v);
      sum += d;
      if (first < 0.0f && d >= threshold) first = refineCrossing(particle, s, v, tPrev, dPrev, t, d, threshold) / L;
      tPrev = t;
      dPrev = d;
    }
  }
  const float mean = static_cast<float>(sum / (2.0 * panels));
  return {std::clamp(mean, 0.0f, 1.0f), first < 0.0f ? 1.0f : std::clamp(first, 0.0f, 1.0f)};
}

std::array<Axis, 4> opticalDepthAxes(const std::array<int, 4>& d) {
  const double pi = 3.14159265358979323846;
  return {Axis{"phi_s", "rad", 0.0, 2.0 * pi, d[0], true}, Axis{"theta_s", "rad", 0.0, pi, d[1], false},
          Axis{"phi_v", "rad", 0.0, 2.0 * pi, d[2], true}, Axis{"theta_v", "rad", 0.0, 0.5 * pi, d[3], false}};
}

Table4D bakeOpticalDepth(const ReferenceParticle& particle, const OpticalDepthSettings& settings,
                         const ProgressFn& progress) {
  const auto& d = settings.dims;
  const int steps = settings.steps > 0 ? settings.steps : defaultSteps(particle.model());
  const std::array<Axis, 4> axes = opticalDepthAxes(d);
  Table4D table("optical_depth", axes,
                {{"mean_density", "mean normalised density along the chord; optical depth = value * chord length * extinction * radius * density scale"},
                 {"first_matter", "distance along the chord to the first density >= threshold, divided by the chord length"}});
  auto& params = table.parameters();
  params["density_model"] = toString(particle.model());
  params["seed"] = particle.seed();
  params["density_grid"] = particle.isGridded() ? particle.gridResolution() : 0;
  params["steps"] = steps;
  params["extinction_per_m"] = settings.extinction;
  params["radius_m"] = settings.radius;
  params["first_matter_threshold"] = defaults::kFirstMatterThreshold;

  // Entry points and frames per (φS, θS) node, directions' angles per (φv, θv) node.
  struct Frame { glm::vec3 S, x, y; };
  std::vector<Frame> frames(static_cast<std::size_t>(d[0]) * d[1]);
  for (int i1 = 0; i1 < d[1]; ++i1)
    for (int i0 = 0; i0 < d[0]; ++i0) {
      const float phi = static_cast<float>(axes[0].value(i0)), theta = static_cast<float>(axes[1].value(i1));
      frames[i1 * d[0] + i0] = {glsl::sphericalPoint(phi, theta), glsl::tangentX(phi, theta), glsl::tangentY(phi)};
    }

  const int slices = d[2] * d[3];
  std::atomic<int> done{0};
  tbb::parallel_for(tbb::blocked_range<int>(0, slices, 1), [&](const tbb::blocked_range<int>& r) {
    for (int slice = r.begin(); slice != r.end(); ++slice) {
      const int i2 = slice % d[2], i3 = slice / d[2];
      const float phiV = static_cast<float>(axes[2].value(i2)), thetaV = static_cast<float>(axes[3].value(i3));
      for (int i1 = 0; i1 < d[1]; ++i1)
        for (int i0 = 0; i0 < d[0]; ++i0) {
          const Frame& f = frames[i1 * d[0] + i0];
          const glm::vec3 v = glsl::frameDirection(f.x, f.y, f.S, phiV, thetaV);
          const ChordIntegral c = integrateChord(particle, f.S, v, steps);
          const std::size_t node = table.index(i0, i1, i2, i3);
          table.at(node, 0) = c.meanDensity;
          table.at(node, 1) = c.firstMatter;
        }
      const int n = ++done;
      if (progress && (n % 16 == 0 || n == slices))
        reportProgress(progress, "optical depth", static_cast<double>(n) / slices);
    }
  });
  return table;
}

}  // namespace cloudlut::bake
