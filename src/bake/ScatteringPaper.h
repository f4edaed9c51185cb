#pragma once
// Baseline: the seed paper's multiple-scattering precomputation (§4.2–4.3), faithfully.
//
// An intermediate 4D volume table L(θS, φv, θv, r) over the whole sphere of view directions
// (θv ∈ [0, π]) and radii r ∈ [0, 1] (uniform), in the light frame of each point:
//   L(1): eq. 9 by fixed-step marching (each step weighted by its exact transmittance drop);
//   for n = 2 … N:
//     J(n) at every cell by brute-force gather over the table's own directions (eq. 6), phase
//          functions evaluated per sample (P1·PM for n = 2, PM after);
//     L(n) by fixed-step marching along the view ray (eq. 5), J(n) read with 4D interpolation;
//     LM += L(n);
//   the r = 1 slice (θv ≤ π/2) is copied to the output table.
// Volume resolution: θS and φv as the output table, θv 2·(Nθv − 1) + 1 nodes over [0, π],
// Nθv radii; 2·Nθv marching steps per chord. Cost grows as the square of the table size:
// meant to be run at reduced resolution for comparisons.
#include <nlohmann/json.hpp>

#include "bake/ScatteringBaker.h"
#include "core/Progress.h"
#include "core/Table4D.h"

namespace cloudlut::bake {

// Fills every density slice of `table` (axes θS, φv, θv, log2 ρ) with orders 2 … settings.orders;
// appends one report object per slice to `slices`.
void bakePaperMultipleScattering(const ScatteringSettings& settings, Table4D& table,
                                 nlohmann::json& slices, const ProgressFn& progress,
                                 double progressBase, double progressSpan);

}  // namespace cloudlut::bake
