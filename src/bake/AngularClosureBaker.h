#pragma once
// The angular closure of an isolated particle's multiple scattering (docs/LIGHTING.md, "The
// particle's own term, closed per exit direction").
//
// The runtime's own term of a particle reads the multiple table, the homogeneous sphere's, at the
// view chord's mean density ρ·T̄ (seed §4.4). Over all view directions that model sends out about
// the power the reference particle scatters (within 1–5%), but not in the right directions: its
// dense core reflects like a sphere of its mean density, too much back toward the sun and too
// little forward (at ρ = 4, +25% of the power leaving toward the sun, −16% leaving sideways).
//
// The closure K(ρ, μ) is, per density node ρ and exit-direction bin μ = ω_out · l, the ratio of
//   the power of orders 2 … N leaving the reference particle, from forward Monte Carlo through
//   its own density (delta tracking; first and later phase functions of the tables), to
//   the power the own-term model sends out: ∫ dω ∫ dA (1 − e^{−τ}) J̄M(S, v, l, ρT̄) · C over the
//   view directions v with −v · l in the bin and the chords of the disc facing v, C the own core
//   shadow at the chord's mean scattering point (ownCoreShadow, cloudlut_shading.glsl; 1 with
//   AngularClosureSettings::ownCoreShadow false).
// Both per unit sun irradiance on the unit sphere (powers in unit-sphere area units), averaged
// over a fixed set of sun directions in the particle's frame. The renderer multiplies the own
// term by K at the particle's density and its exit direction (−v · l).
#include <cstdint>
#include <optional>
#include <vector>

#include "core/AngularClosure.h"
#include "core/Phase.h"
#include "core/Progress.h"
#include "core/ReferenceParticle.h"
#include "core/Table4D.h"

namespace cloudlut::bake {

struct AngularClosureSettings {
  float log2RhoFirst = -2.0f;       // first density node, log2 ρ
  float log2RhoStep = 1.0f;         // node spacing, octaves
  int densityNodes = 6;             // ρ = 1/4 … 8
  int muBins = 8;                   // uniform bins of μ = ω_out · l over [−1, 1]
  int sunDirections = 6;            // Fibonacci directions in the particle's frame
  long long photonsPerDirection = 16000;  // standard errors 1–3% per bin
  int viewDirections = 300;         // Fibonacci view directions of the model's integral
  int discSide = 32;                // chords per side of the disc facing each view direction
  bool ownCoreShadow = true;        // the model's own term darkened by its core shadow (ownCoreShadow);
                                    // false: the closure of the term without it (sets baked before it)
  float ownCoreShadowMax = 1.2f;    // the most it may brighten the term (ownCoreShadow's bound; a
                                    // sweep of 1 … 1.5 in docs/LIGHTING.md)
  std::uint64_t seed = 1;
};


// Densest particle the Monte Carlo follows: optical radius σ·ρ of a density node (a photon makes
// about (σρ)² steps; the default table's densest node, ρ = 8, is 103). Denser nodes are left
// out, and the closure's last node holds for them.
inline constexpr double kMaxClosureOpticalRadius = 256.0;

// K for the multiple table `multiple` (its orders: 2 … N, or every order when "converged") and the
// reference particle of the optical-depth table `opticalDepth`, over the settings' density nodes
// up to kMaxClosureOpticalRadius; nullopt when even the first node is denser. Deterministic for
// a seed, whatever the thread count. Throws std::invalid_argument on settings out of range.
std::optional<AngularClosure> computeAngularClosure(const Table4D& opticalDepth, const Table4D& multiple,
                                     const ReferenceParticle& particle, const Phase& first, const Phase& later,
                                     const AngularClosureSettings& settings = {}, const ProgressFn& progress = {});


// Computes the closure of `multiple` and records it in its parameters under "angular_closure";
// records nothing (K = 1) when computeAngularClosure finds no node it can follow.
void attachAngularClosure(Table4D& multiple, const Table4D& opticalDepth, const ReferenceParticle& particle,
                          const Phase& first, const Phase& later, const AngularClosureSettings& settings = {},
                          const ProgressFn& progress = {});

}  // namespace cloudlut::bake
