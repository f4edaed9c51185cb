#pragma once
// Multiple scattering (orders 2 … N or 2 … ∞) in the homogeneous unit sphere, fast method.
//
// The light field inside a sphere lit by a distant sun is symmetric about the sun direction l,
// so the in-scattered source J(x, ω) (radiance emitted at x along ω per unit optical length)
// is stored on a 4D grid: x in the meridian plane (radius graded in optical depth from the
// surface, position zenith from l), ω on a light-frame direction grid folded by the mirror
// symmetry (DirectionGrid). A sample at any point is rotated about l into the meridian plane.
//
// One order maps J_n to J_{n+1} = M·T(J_n):
//   T: L(x, ω) = ∫_0^{d} σ e^{-σs} J(x − sω, ω) ds, Gauss–Legendre in u = 1 − e^{−σs} near x
//      (and in s beyond six mean free paths for σ < 20); the direction's zenith from l is
//      constant along the ray, so J is read at its own direction-zenith node, interpolated in
//      (depth, position zenith) with quadratic-exact four-node weights and linearly in the
//      relative azimuth — a stencil precomputed once per density and reused by every order.
//      (Linear interpolation across optically thick cells acts as extra diffusion and drains
//      dense particles; quadratic exactness keeps the discrete operator conservative to
//      ~0.2% over the whole converged sum.)
//   M: the phase convolution, one dense matrix product over the direction grid (energy
//      conserving by construction).
// The order loop stops early once an order's field total is below 1e-5 of the running sum
// (thin particles: their orders decay fast), an exact truncation up to that tolerance.
// J_2 comes straight from the sun: the once-scattered radiance P1(−l·ω')·A(x, ω') with A the
// closed-form-sun-path integral along each ray, on a direction grid refined toward the sun's
// forward peak, convolved with the later phase function.
// The table value is then LM(S, v) = ∫_0^chord σ e^{-σt} ΣJ_n(S + t v, −v) dt.
// Thin particles (σ ≤ FastResolution::thinSigma) run orders 3 … ∞ on a coarser spatial grid
// (same directions: the phase matrix's resolution sets the diffusion rate through 1 − g, so
// directions are not coarsened), J_2 interpolated onto it and their sum back before the gather;
// dense particles keep one grid (their dark side needs the position-zenith resolution).
//
// Converged (2 … ∞): orders 2 … 18 as above, then the tail X = Σ_{n>18} J_n from
// (I − K) X = K·J_18 by restarted GMRES (inner products over fixed blocks: thread-count
// independent), right-preconditioned by an isotropic coarse-space correction (K_c = R·K·P
// assembled from the stencil, solved by LU): the slow modes of dense particles are smooth,
// nearly isotropic diffusion modes that plain iteration would need thousands of orders for.
// The baker then closes the tail's amplitude on energy (ScatteringBaker.cpp).
#include <array>
#include <memory>
#include <vector>

#include <nlohmann/json.hpp>

#include "bake/ScatteringBaker.h"
#include "core/Progress.h"
#include "core/Table4D.h"

namespace cloudlut::bake {

// Internal resolution of the fast method.
struct FastResolution {
  int radial = 16;        // depth nodes (surface to centre)
  int zenith = 32;        // position-zenith nodes over [0, π]
  int dirTheta = 24;      // direction-zenith nodes over [0, π]
  int dirPhi = 13;        // direction-azimuth nodes over [0, π]
  int fineTheta = 32;     // once-scattered light: direction-zenith nodes, graded toward −l
  int finePhi = 17;
  int transportPoints = 12;  // Gauss points per ray in the transport operator
  int gatherPoints = 24;     // ... in the final gather to the table nodes
  // Transport points when σ ≥ kFarPanelMaxSigma (u panels of 2 + 2 + 6 points: the table moves
  // ≤ 3.1e-4 relative against 3 + 3 + 6; 8 points move it by p95 2–7%).
  int denseTransportPoints = 10;
  double grading = 32.0;     // depth grading a: q = α δ + (1 − α) ln(1 + aσδ) / ln(1 + aσ), δ = 1 − r
  double linearShare = 0.25; // α
  // Thin particles (σ ≤ thinSigma): orders 3 … ∞ on a coarser volume grid, thinRadial ×
  // thinZenith spatial nodes with the same directions and grading; J_2 is interpolated onto it
  // and the orders' sum back onto the grid above before the gather. Measured against one grid:
  // p95 ≤ 0.26% on the slices σ ≤ 5; from σ ≈ 13 on, 12 × 20 moves the dark side by p95 2–61%
  // (docs/BENCHMARKS.md, third pass).
  double thinSigma = 5.0;
  int thinRadial = 12;
  int thinZenith = 20;
};

// Fills the multiple-scattering values of density slice `slice` (σ = optical radius) of
// `table` (axes θS, φv, θv, log2 ρ) with orders 2 … N (N = settings.orders, or 18 when
// converged). When converged (orders <= 0), the remaining orders N+1 … ∞ go to `tailTable`
// (same axes) if given. Sets `report` to what it measured (orders, seconds, iterations).
// The steps of a slice (MultipleScattering.cpp): the first-scattering source J_2, the transport
// stencil (ScatteringOperator.h), the orders, the tail (TailSolver.h) and the gather.
class FastMultipleScattering {
 public:
  FastMultipleScattering(const ScatteringSettings& settings, const FastResolution& res = {});
  ~FastMultipleScattering();
  FastMultipleScattering(const FastMultipleScattering&) = delete;
  FastMultipleScattering& operator=(const FastMultipleScattering&) = delete;
  void bakeSlice(double sigma, int slice, Table4D& table, Table4D* tailTable, nlohmann::json& report,
                 const ProgressFn& progress, double progressBase, double progressSpan) const;

 private:
  // What every slice shares: settings, resolution, direction grids, phase matrices.
  struct Shared;
  std::unique_ptr<const Shared> shared_;
};

}  // namespace cloudlut::bake
