#pragma once
// The optical-depth table T(φS, θS, φv, θv) of the reference particle (seed §4.1, eq. 1).
//
// For the chord of the unit sphere entering at S along v (length L = 2 cos θv):
//   channel 0, mean_density = (1/L) ∫_0^L ρ̂(S + t v) dt ∈ [0, 1]; the optical depth of a particle
//              of density scale ρ is τ = σ · ρ · L · mean_density, σ = β·R (unit-sphere units);
//   channel 1, first_matter = t₀ / L ∈ [0, 1], t₀ the first distance at which ρ̂ reaches
//              defaults::kFirstMatterThreshold (1 when it never does).
// Degenerate (grazing, L → 0) chords take their limits: the density and matter test at S.
#include <array>
#include <cstdint>

#include <glm/vec3.hpp>

#include "core/Defaults.h"
#include "core/Progress.h"
#include "core/ReferenceParticle.h"
#include "core/Table4D.h"

namespace cloudlut::bake {

struct OpticalDepthSettings {
  std::array<int, 4> dims = defaults::kOpticalDepthDims;
  // Density samples along a full diameter; a chord of length L takes about steps·L/2 of them
  // (at least 2), as composite two-point Gauss–Legendre panels. 0 = defaultSteps(model).
  int steps = 0;
  double extinction = defaults::kExtinctionPerMetre;  // β, m⁻¹ (recorded in the table's parameters)
  double radius = defaults::kParticleRadiusMetres;    // R, m
};

struct ChordIntegral {
  float meanDensity;  // dimensionless, [0, 1]
  float firstMatter;  // distance to the first matter / chord length, [0, 1]
};

// Samples per diameter that keep each model within 1e-3 mean and 5e-3 max absolute error of
// a 4096-sample integration (measured by `cloudlut bench`; docs/BENCHMARKS.md).
int defaultSteps(DensityModel model);

// Integrates the chord from S (on the unit sphere) along v with the given number of samples
// per diameter (see OpticalDepthSettings::steps).
ChordIntegral integrateChord(const ReferenceParticle& particle, const glm::vec3& S,
                             const glm::vec3& v, int steps);

// integrateChord for four chords at once (S[k], v[k]), each lane bit for bit the same.
void integrateChords4(const ReferenceParticle& particle, const glm::vec3 S[4], const glm::vec3 v[4], int steps,
                      ChordIntegral out[4]);

// The table's axes for the given dimensions: φS ∈ [0, 2π], θS ∈ [0, π], φv ∈ [0, 2π], θv ∈ [0, π/2].
std::array<Axis, 4> opticalDepthAxes(const std::array<int, 4>& dims);

// Bakes the table over every node, in parallel (oneTBB); identical output for any thread count.
Table4D bakeOpticalDepth(const ReferenceParticle& particle, const OpticalDepthSettings& settings,
                         const ProgressFn& progress = {});

}  // namespace cloudlut::bake
