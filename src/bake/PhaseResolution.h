#pragma once
// How well a grid of directions resolves a phase function's forward peak.
//
// A grid that carries the phase convolution sees the phase function only through its
// integrals against the grid's interpolation functions: the fast method's phase matrix is
// M_ij = ∫ P(ω_i·ω') hat_j(ω') dω' with hat_j the bilinear hat of node j (DirectionGrid.h).
// Model used here, in one dimension, the scattering angle θ from the forward direction: nodes
// θ_0 = 0 < θ_1 < … < θ_K = π with linear hats; the grid's phase has the mass
// m_k = ∫ P hat_k dΩ at cos θ_k, so its transport asymmetry is
//   g_grid = Σ_k m_k cos θ_k / Σ_k m_k = ∫ P · Icos dΩ / ∫ P dΩ,
// Icos the piecewise-linear interpolant of cos θ on the nodes. The exact asymmetry is
// g = ∫ P μ dΩ / ∫ P dΩ; both by the same fine quadrature, graded toward the forward peak.
// The expected error is
//   ε = |g_grid − g| / (1 − g),
// the relative error in 1 − g, the factor that sets the transport mean free path
// 1/(σ(1 − g)) and so how light diffuses through a dense particle. Light scattered by θ
// inside the first cell is shared between the nodes at 0 and θ_1 in proportion θ/θ_1: its
// angular spread becomes ≈ θ·θ_1/2 instead of θ²/2, so a forward peak narrower than a cell
// is broadened to the cell's size — the error grows with the peak's weight and sharpness.
// Smooth phase functions have ε = O(θ_1²) (≈ g θ_1² / (12 (1 − g)) for a uniform grid);
// an isotropic one has ε = 0 on any grid symmetric about π/2. At a 2D grid's coarsest
// spacing the estimate is ~25% above the error the fast method's phase matrix actually makes
// on that grid (tests/test_phase_resolution.cpp): a conservative expectation.
#include <string>
#include <vector>

#include "bake/ScatteringBaker.h"

namespace cloudlut::bake {

struct PhaseResolutionEstimate {
  double asymmetry = 0;      // exact g = ∫ P μ dΩ / ∫ P dΩ (dimensionless)
  double gridAsymmetry = 0;  // g_grid of the cell-integrated phase (dimensionless)
  double relativeError = 0;  // ε = |g_grid − g| / (1 − g) (dimensionless; 0.01 = 1%)
  double peakValue = 0;      // P(μ = 1), sr⁻¹
  double peakHalfWidth = 0;  // radians: the smallest θ with P(cos θ) ≤ P(1)/2; π if none (no peak)
};

// The estimate for a uniform grid of angular spacing `spacing` (radians, in (0, π]): nodes
// θ_k = kπ/K with K = ceil(π / spacing), so the spacing actually used is π/K ≤ `spacing`.
PhaseResolutionEstimate estimatePhaseResolution(const Phase& phase, double spacing);

// The estimate for explicit nodes in the scattering angle (radians, ascending, first 0, last π).
PhaseResolutionEstimate estimatePhaseResolution(const Phase& phase, const std::vector<double>& nodes);

// The largest uniform spacing π/K (radians) whose estimate is at most `tolerance`
// (dimensionless), searched over K up to 8192; returns π/8192 if even that is not enough.
double spacingForError(const Phase& phase, double tolerance);

// Peak half-width alone (radians), as in PhaseResolutionEstimate::peakHalfWidth.
double phasePeakHalfWidth(const Phase& phase);

// One phase function on one grid of a bake: what the warning reports.
struct PhaseResolutionCheck {
  std::string grid;       // which grid, e.g. "the fast method's 24x13 direction grid"
  std::string which;      // "first" (first scattering of sunlight) or "later" (every later order)
  Phase phase;
  double spacing = 0;     // radians: the spacing the estimate used (the grid's coarsest)
  PhaseResolutionEstimate estimate;
  double neededSpacing = 0;  // radians: the largest spacing whose ε is within the tolerance
  std::string advice;     // the resolution that gets there, in the grid's own terms
};

// The phase-function grids a scattering bake with `settings` uses, each estimated; returns the
// ones whose ε exceeds `tolerance` (dimensionless; empty: nothing to warn about).
// Fast method: the later phase on the internal direction grid (FastResolution dirTheta ×
// dirPhi nodes over [0, π]²; spacing = the coarser of π/(dirTheta − 1) and π/(dirPhi − 1),
// the azimuth spacing being the arc length on the light frame's equator); the first phase on
// the once-scattered grid graded toward the sun (nodes π (j/(fineTheta − 1))² in scattering
// angle). Paper method: both phases on its volume's direction grid (θv spacing
// π/(2(Nθv − 1)), φv spacing 2π/(Nφv − 1); coarser of the two). Nothing to check when no
// multiple-scattering table is baked (L1 is stored without the phase function) or for an
// isotropic phase function.
//
// Default tolerance 2%: the defaults (cs g = 0.7 on the 24×13 grid) estimate 1.8%, and a grid
// that brings them to 1% (dirPhi 13 → 18, +17% bake time) moved the multiple-scattering energy
// shares by at most 0.001 (0.2% of the share): the estimate in 1 − g overstates what reaches
// the table, so 2% flags a phase function well beyond the defaults (jd 10 µm: 2.7%).
inline constexpr double kPhaseResolutionTolerance = 0.02;
std::vector<PhaseResolutionCheck> checkPhaseResolution(const ScatteringSettings& settings,
                                                       double tolerance = kPhaseResolutionTolerance);

// The checks of checkPhaseResolution(settings, kPhaseResolutionTolerance) as one warning line
// for `program` ("cloudlut bake"): per grid, the phase, its asymmetry, peak and half-width, the
// grid's spacing, the expected error in 1 − g and the resolution that brings it under the
// tolerance. Empty when there is nothing to warn about.
std::string phaseResolutionWarning(const ScatteringSettings& settings, const std::string& program);

}  // namespace cloudlut::bake
