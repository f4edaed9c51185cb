#pragma once
// Evaluating the tables at arbitrary geometry, with the interpolation the renderer uses
// (quadrilinear over the nodes; see Table4D::sample). Shared by `query`, the renderer's
// tests and the accuracy tests.
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

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

// Channel names of the scattering tables (cloudlut_shading.glsl): the single table stores log2
// of the mean source along the chord, the multiple table the mean source itself.
inline constexpr const char* kSingleScatteringChannel = "log2_mean_source";
inline constexpr const char* kMultipleScatteringChannel = "mean_source";

// How a scattering table stores its values, from its channel name.
enum class ScatteringStorage { Log2MeanSource, MeanSource };

// The storage of a scattering table; throws std::runtime_error naming the table unless it is a
// scattering table of this cloudlut version (older versions stored radiance: re-bake them).
ScatteringStorage scatteringStorage(const Table4D& table);

// The axes record of a scattering table for scatteringAxes() (cloudlut_geometry.glsl):
// (log2 ρ at the first and last density node, θS warp, layout flags: CLOUDLUT_LAYOUT_FOLDED_PHI_V
// if axis 1 is folded + CLOUDLUT_LAYOUT_LINEAR_IN_RHO if axis 3 is interpolated linearly in 2^s).
// The renderer passes the same vector to its shaders.
glm::vec4 scatteringAxesRecord(const Table4D& table);

// The stored value (channel 0) of a scattering table (θS, φv, θv, log2 ρ) at the
// geometry (S, v, l) and density rho; rho outside the table's range is clamped to it.
float sampleScattering(const Table4D& table, const glm::vec3& S, const glm::vec3& v,
                       const glm::vec3& l, float rho);

// Radiance per unit sun irradiance (sr⁻¹) of the tables' homogeneous sphere of density rho
// along the chord entering at S along v: scatteringFromStored(storage, sampleScattering(...), ρσ·chord).
// For the single-scattering table this is L1, without the phase function.
float lookupScattering(const Table4D& table, const glm::vec3& S, const glm::vec3& v,
                       const glm::vec3& l, float rho);

// Radiance (sr⁻¹ per unit sun irradiance) of a chord of optical depth tau from a scattering
// table's stored value, decoded as its storage says (single/multipleScatteringFromTable).
float scatteringFromStored(ScatteringStorage storage, float stored, float tau);

// σ = extinction·radius of a table's parameters: the optical radius of a particle of ρ = 1.
float unitOpticalRadius(const Table4D& table);

// The optical-depth table's chord_outer_third_share (dimensionless; bake/ChordMatterProfile.h):
// the share of a chord's optical depth in each outer third of its matter, as the renderer's
// volumes lay it (chordMatterShare). 1/3, matter laid evenly, for a table that records none
// (baked before it was measured). Throws std::invalid_argument ("chord_outer_third_share …")
// when it is not a number in [0, 0.5] (rules::chordOuterThirdProblem).
float chordOuterThird(const Table4D& opticalDepth);

}  // namespace cloudlut
