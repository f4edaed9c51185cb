#pragma once
// The single- and multiple-scattering tables of the homogeneous unit sphere (seed §4.2–4.3, the
// particle-space conventions of docs/ENGINE_GUIDE.md §2), 4D tables over (θS, φv, θv, log2 ρ):
//   "single_scattering"   L1(S, v) = ∫_0^chord σ e^{-σt} e^{-σ d_sun(S + t v)} dt, WITHOUT the
//                         phase function (single = P1(v·l) · L1 exactly);
//   "multiple_scattering" orders 2 … N (or 2 … ∞, "converged") of the radiance leaving the
//                         sphere at S toward the camera (direction −v), phase functions included.
// Radiance per unit sun irradiance (sr⁻¹); σ = extinction · radius · ρ in unit-sphere units.
//
// Methods:
//   Fast  (default) — ours: L1 by graded Gauss–Legendre quadrature along each chord with the
//         closed-form sun path; multiple scattering on an axially symmetric volume grid
//         (depth-graded radius, position zenith, global direction zenith/azimuth), a transport
//         operator precomputed once per density and applied per order, the phase convolution
//         as one matrix product per order, and the first scattering of sunlight evaluated from
//         closed-form sun transmittance (see MultipleScattering.h).
//   Paper — a faithful baseline of the seed's algorithm (4D intermediate volume table, J by
//         brute-force gather, L by fixed-step marching); slow, meant for comparisons.
//
// Multithreaded with oneTBB (limit the threads with tbb::global_control); the output is
// bit-identical for any number of threads.
#include <array>
#include <optional>

#include <nlohmann/json.hpp>

#include "core/Defaults.h"
#include "core/Phase.h"
#include "core/Progress.h"
#include "core/Table4D.h"

namespace cloudlut::bake {

enum class ScatteringMethod { Fast, Paper };

struct ScatteringSettings {
  std::array<int, 4> dims = defaults::kScatteringDims;  // θS, φv, θv, ρ nodes
  double sMin = defaults::kDensitySlopeMin, sMax = defaults::kDensitySlopeMax;  // log2 ρ range of the density axis
  double extinction = defaults::kExtinctionPerMetre, radius = defaults::kParticleRadiusMetres;  // β (1/m), R (m)
  Phase firstPhase = defaults::kFirstPhase, laterPhase = defaults::kLaterPhase;
  int orders = defaults::kScatteringOrders;  // highest order in the multiple table; <= 0 means converged (2 … ∞)
  ScatteringMethod method = ScatteringMethod::Fast;
  bool single = true, multiple = true;
  // Store φv over [0, π] only (axis 1 folded; dims[1] nodes over [0, π]): the homogeneous
  // sphere's light is mirror-symmetric about the plane of S and l. false: over [0, 2π] (periodic).
  bool foldPhiV = true;
  // Interpolate between the density slices linearly in ρ (axis 3 flagged linearInExp2,
  // densityAxisLinearInRho); false: linearly in log2 ρ, the layout of format versions 1–2.
  bool densityLinearInRho = true;
};

struct ScatteringResult {
  std::optional<Table4D> single, multiple;
  // Per density: energy shares (unscattered, single, multiple, total), orders used, and
  // seconds per stage; plus the method and the internal resolution.
  nlohmann::json report;
};

// Throws std::invalid_argument for settings that cannot be baked (dims < 2, bad phase, ...).
ScatteringResult bakeScattering(const ScatteringSettings& settings, const ProgressFn& progress = {});

// Node concentration ("warp", concentratedFraction in cloudlut_geometry.glsl) of a θS axis of
// n nodes about the terminator: 7 from 32 nodes on (32 nodes: 1.2° apart at the terminator,
// 20.4° at the poles; the 95th-percentile L1 interpolation error at random geometry drops from
// 22–44% to ≤ 1.7% for ρ ≥ 1), and for fewer nodes the largest concentration that keeps the
// poles' spacing within 21° (none at 9 nodes or fewer).
double sunZenithWarp(int nodes);

// Name used in parameters and reports: "fast" or "paper".
const char* toString(ScatteringMethod method);

}  // namespace cloudlut::bake
