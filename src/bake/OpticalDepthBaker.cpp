#include "bake/OpticalDepthBaker.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "bake/ChordMatterProfile.h"
#include "core/Defaults.h"
#include "core/Float4.h"
#include "core/Glsl.h"

namespace cloudlut::bake {

namespace {

// Two-point Gauss–Legendre abscissae on a unit panel: 1/2 ∓ 1/(2√3).
constexpr float kGaussLo = 0.2113248654f;
constexpr float kGaussHi = 0.7886751346f;
constexpr int kBisections = 4;

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

ChordIntegral integrateChord(const ReferenceParticle& particle, const glm::vec3& S, const glm::vec3& v, int steps) {
  const glm::vec3 lanesS[4] = {S, S, S, S}, lanesV[4] = {v, v, v, v};
  ChordIntegral out[4];
  integrateChords4(particle, lanesS, lanesV, steps, out);
  return out[0];
}

// Float8 instances below run only inside integrateChords8 (-Wpsabi: Float4.h).

namespace {

// integrateChords4 for N = lanes of the float vector V (Float4, or Float8 in AVX2 code): the
// same operations per lane, so the same bits whatever the width. Always inlined into its
// instruction set's caller.
template <class V>
[[gnu::always_inline]] inline void integrateChordLanes(const ReferenceParticle& particle, const glm::vec3* S,
                                                       const glm::vec3* v, int steps, ChordIntegral* out) {
  using I = decltype(V{} < V{});
  constexpr int N = floatLanes<V>();
  // N chords side by side, each lane on its own panels (a lane past its last panel idles).
  const float threshold = defaults::kFirstMatterThreshold;
  V sx, sy, sz, vx, vy, vz, L, h;
  int panels[N];
  int maxPanels = 0;
  for (int k = 0; k < N; ++k) {
    // Points exactly on the sphere may round to just outside it: pull S in by a hair.
    const glm::vec3 s = S[k] * (1.0f - 1e-6f);
    sx[k] = s.x, sy[k] = s.y, sz[k] = s.z;
    vx[k] = v[k].x, vy[k] = v[k].y, vz[k] = v[k].z;
    L[k] = glsl::chordLength(S[k], v[k]);
    // a degenerate (grazing) chord has no panels: it takes its limits at S
    panels[k] = L[k] < 1e-6f ? 0 : std::max(1, static_cast<int>(std::ceil(0.25f * static_cast<float>(steps) * L[k])));
    h[k] = panels[k] > 0 ? L[k] / static_cast<float>(panels[k]) : 0.0f;
    maxPanels = std::max(maxPanels, panels[k]);
  }
  const V atS = particle.densityLanes(sx, sy, sz);
  double sum[N] = {};
  // The first matter: found at S, or bracketed between two samples (t0, d0 below the
  // threshold; t1, d1 at or above it) and refined below.
  bool atStart[N], bracketed[N] = {};
  V t0 = {}, d0 = atS, t1 = {}, d1 = atS;
  bool anyBracketed = false;
  for (int k = 0; k < N; ++k) atStart[k] = atS[k] >= threshold;
  for (int p = 0; p < maxPanels; ++p) {
    const V a = h * static_cast<float>(p);
    for (const float g : {kGaussLo, kGaussHi}) {
      const V t = a + g * h;
      const V d = particle.densityLanes(sx + t * vx, sy + t * vy, sz + t * vz);
      for (int k = 0; k < N; ++k) {
        if (p >= panels[k]) continue;
        sum[k] += d[k];
        if (atStart[k] || bracketed[k]) continue;
        if (d[k] >= threshold) {
          bracketed[k] = anyBracketed = true;
          t1[k] = t[k];
          d1[k] = d[k];
        } else {
          t0[k] = t[k];
          d0[k] = d[k];
        }
      }
    }
  }
  // A few bisections of every bracket (all lanes at once), then the linear interpolation of
  // the last one.
  if (anyBracketed) {
    for (int i = 0; i < kBisections; ++i) {
      const V tm = 0.5f * (t0 + t1);
      const V dm = particle.densityLanes(sx + tm * vx, sy + tm * vy, sz + tm * vz);
      const I above = dm >= threshold;
      t1 = above ? tm : t1;
      d1 = above ? dm : d1;
      t0 = above ? t0 : tm;
      d0 = above ? d0 : dm;
    }
  }
  for (int k = 0; k < N; ++k) {
    if (panels[k] == 0) {
      out[k] = {atS[k], atStart[k] ? 0.0f : 1.0f};
      continue;
    }
    float first = 1.0f;  // never reaches the threshold
    if (atStart[k]) {
      first = 0.0f;
    } else if (bracketed[k]) {
      const float w = d1[k] > d0[k] ? (threshold - d0[k]) / (d1[k] - d0[k]) : 0.5f;
      first = std::clamp((t0[k] + std::clamp(w, 0.0f, 1.0f) * (t1[k] - t0[k])) / L[k], 0.0f, 1.0f);
    }
    const float mean = static_cast<float>(sum[k] / (2.0 * panels[k]));
    out[k] = {std::clamp(mean, 0.0f, 1.0f), first};
  }
}

#if CLOUDLUT_AVX2_LANES
// Eight chords at once (AVX2; no fused multiply-add): integrateChords4's bits.
__attribute__((target("avx2"))) void integrateChords8(const ReferenceParticle& particle, const glm::vec3 S[8],
                                                      const glm::vec3 v[8], int steps, ChordIntegral out[8]) {
  integrateChordLanes<Float8>(particle, S, v, steps, out);
}
#else
// Never called: cpuHasAvx2Lanes() is false where the AVX2 paths are not compiled.
void integrateChords8(const ReferenceParticle&, const glm::vec3*, const glm::vec3*, int, ChordIntegral*) {}
#endif

}  // namespace

void integrateChords4(const ReferenceParticle& particle, const glm::vec3 S[4], const glm::vec3 v[4], int steps,
                      ChordIntegral out[4]) {
  integrateChordLanes<Float4>(particle, S, v, steps, out);
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
  params["chord_outer_third_share"] = measureChordOuterThird(particle);

  // Entry points and frames per (φS, θS) node, directions' angles per (φv, θv) node: the chord
  // of node (i0..i3) runs along glsl::opticalDepthNodeDirection, its frame cached per entry point.
  struct Frame { glm::vec3 S, x, y; };
  std::vector<Frame> frames(static_cast<std::size_t>(d[0]) * d[1]);
  for (int i1 = 0; i1 < d[1]; ++i1)
    for (int i0 = 0; i0 < d[0]; ++i0) {
      const float phi = static_cast<float>(axes[0].value(i0)), theta = static_cast<float>(axes[1].value(i1));
      frames[i1 * d[0] + i0] = {glsl::sphericalPoint(phi, theta), glsl::tangentX(phi, theta), glsl::tangentY(phi)};
    }

  // Eight chords at once where the processor has AVX2 (the same values: integrateChords8).
  const int lanes = cpuHasAvx2Lanes() ? 8 : 4;
  const int slices = d[2] * d[3];
  std::atomic<int> done{0};
  tbb::parallel_for(tbb::blocked_range<int>(0, slices, 1), [&](const tbb::blocked_range<int>& r) {
    for (int slice = r.begin(); slice != r.end(); ++slice) {
      const int i2 = slice % d[2], i3 = slice / d[2];
      const float phiV = static_cast<float>(axes[2].value(i2)), thetaV = static_cast<float>(axes[3].value(i3));
      for (int i1 = 0; i1 < d[1]; ++i1)
        for (int i0 = 0; i0 < d[0]; i0 += lanes) {  // four or eight entry points at a time
          const int n = std::min(lanes, d[0] - i0);
          glm::vec3 S[8], v[8];
          for (int k = 0; k < lanes; ++k) {
            const Frame& f = frames[i1 * d[0] + i0 + std::min(k, n - 1)];
            S[k] = f.S;
            v[k] = glsl::frameDirection(f.x, f.y, f.S, phiV, thetaV);
          }
          ChordIntegral c[8];
          if (lanes == 8)
            integrateChords8(particle, S, v, steps, c);
          else
            integrateChords4(particle, S, v, steps, c);
          for (int k = 0; k < n; ++k) {
            const std::size_t node = table.index(i0 + k, i1, i2, i3);
            table.at(node, 0) = c[k].meanDensity;
            table.at(node, 1) = c[k].firstMatter;
          }
        }
      const int n = ++done;
      if (progress && (n % 16 == 0 || n == slices))
        reportProgress(progress, "optical depth", static_cast<double>(n) / slices);
    }
  });
  return table;
}

}  // namespace cloudlut::bake
