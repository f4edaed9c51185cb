#pragma once
// How the reference particle's matter lies along its chords, between each chord's first matter
// and its last (the optical-depth table's channel 1 and core/LastMatter.h): the share of it in
// the outer thirds of that span, which the renderer's volumes use to lay a chord's optical depth
// along a column (chordMatterShare, cloudlut_shading.glsl; docs/LIGHTING.md "Sunlight per
// shading point"). Recorded in the optical-depth table as `chord_outer_third_share`.
#include "core/ReferenceParticle.h"

namespace cloudlut::bake {

// The share a (dimensionless, [0, ½]) of a chord's optical depth that lies in each outer third
// of the span from its first matter to its last, over the chords of the unit sphere: the matter
// of every chord's two outer thirds, halved, summed, over the matter of every chord (so each
// chord weighs by its optical depth). The chords: 16 directions (a Fibonacci sphere), each with
// a 24 × 24 grid of parallel chords over the unit disc across it (chords uniform in area),
// sampled by the midpoint rule at 256 points per diameter; a chord's matter runs from the first
// sample whose density reaches defaults::kFirstMatterThreshold to the last one. Even matter
// (a homogeneous sphere) gives 1/3; the metaball fall-off (1 − r²)² gives 0.265.
// Deterministic (a fixed summation order, whatever the threads).
double measureChordOuterThird(const ReferenceParticle& particle);

}  // namespace cloudlut::bake
