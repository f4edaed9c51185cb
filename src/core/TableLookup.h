#pragma once
// Evaluating the tables at arbitrary geometry, with the interpolation the renderer uses
// (quadrilinear over the nodes; see Table4D::sample). Shared by `query`, the renderer's
// tests and the accuracy tests.
#include <glm/vec3.hpp>

#include "core/Table4D.h"

namespace cloudlut {

struct OpticalDepthSample {
  float meanDensity;   // channel 0, [0, 1]
  float firstMatter;   // channel 1, fraction of the chord
  float chordLength;   // unit-sphere units
  float opticalDepth;  // τ = σ·ρ·L·meanDensity, σ = extinction·radius (dimensionless)
  float transmittance; // e^{-τ}
};

// Optical depth of the reference particle of density scale rho along the chord entering the
// unit sphere at S along v (seed §4.4: τ = ρ·T). Uses the table's extinction_per_m and
// radius_m parameters.
OpticalDepthSample lookupOpticalDepth(const Table4D& table, const glm::vec3& S,
                                      const glm::vec3& v, float rho);

// Value of a scattering table (θS, φv, θv, log2 ρ) at the geometry (S, v, l) and density rho;
// rho outside the table's range is clamped to it. For the single-scattering table this is L1,
// without the phase function.
float lookupScattering(const Table4D& table, const glm::vec3& S, const glm::vec3& v,
                       const glm::vec3& l, float rho);

// σ = extinction·radius of a table's parameters: the optical radius of a particle of ρ = 1.
float unitOpticalRadius(const Table4D& table);

}  // namespace cloudlut
