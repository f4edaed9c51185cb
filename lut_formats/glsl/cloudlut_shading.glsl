// cloudlut_shading.glsl — how one particle's view ray is shaded from the table samples
// (seed §4.4), shared by the renderer's shaders and the C++ that checks them.

#ifndef CLOUDLUT_FN
#define CLOUDLUT_FN
#endif

// Optical depth of the ray (dimensionless, seed eq. 1 via the table): ρ·σ·L·mean density, with
// σ the unit optical radius (extinction·radius), L the chord in unit-sphere units.
CLOUDLUT_FN float particleOpticalDepth(float rho, float sigma, float chord, float meanDensity) {
  return rho * sigma * chord * meanDensity;
}

// Opacity 1 − e^{−τ} of a chord of optical depth τ (dimensionless), accurate for small τ too.
CLOUDLUT_FN float chordOpacity(float tau) {
  return tau < 1e-3f ? tau * (1.0f - 0.5f * tau) : 1.0f - exp(-tau);
}

// Storage of the scattering tables (seed eq. 9 for L1, §4.3 for LM). A chord's scattered
// radiance is L = ∫_0^c σ e^{−σt} J(t) dt: its opacity 1 − e^{−σc} times the mean source J̄
// along it (the e^{−σt}-weighted mean of J, sr⁻¹ per unit sun irradiance; for L1 without the
// phase function, the mean sun transmittance). The tables store J̄, which stays finite at
// grazing rays (it tends to the source at the entry point while L → 0); the single table
// stores log2 J̄, since J̄1 falls off exponentially across the terminator of a dense particle
// and the hardware's linear interpolation of log2 J̄1 follows that (geometric interpolation).
// The multiple table stores J̄M itself: it is smooth, peaked toward the sun, and geometric
// interpolation would bias its energy low (measured: −0.2% to −0.5%, against ±0.1% linear).
const float CLOUDLUT_LOG2_SOURCE_FLOOR = -64.0f;  // stored value of J̄1 = 0 (J̄1 < 5e-20)

// The single-scattering table's stored value of a mean source J̄1 ≥ 0 (dimensionless).
CLOUDLUT_FN float singleScatteringToTable(float meanSource) {
  return max(log2(max(meanSource, 1e-30f)), CLOUDLUT_LOG2_SOURCE_FLOOR);
}

// Single-scattered radiance without the phase function, per unit sun irradiance, of a chord of
// optical depth τ, from the single table's stored value: (1 − e^{−τ}) · 2^stored.
CLOUDLUT_FN float singleScatteringFromTable(float stored, float tau) {
  return stored <= CLOUDLUT_LOG2_SOURCE_FLOOR ? 0.0f : chordOpacity(tau) * exp2(stored);
}

// Multiply-scattered radiance per unit sun irradiance (sr⁻¹) of a chord of optical depth τ,
// from the multiple table's stored mean source: (1 − e^{−τ}) · J̄M.
CLOUDLUT_FN float multipleScatteringFromTable(float stored, float tau) {
  return chordOpacity(tau) * max(stored, 0.0f);
}

// At runtime (seed §4.4) τ is the particle's optical depth along the ray from the
// optical-depth table: single = P1 · singleScatteringFromTable(J̄1 at ρ·mean density, τ),
// multiple = multipleScatteringFromTable(J̄M at ρ, τ), so an empty ray carries no light and a
// ray as dense as the sphere carries the sphere's. For the tables' own homogeneous sphere of
// density ρ, τ = ρσ · 2 cos θv.

// Scale of the sky radiance for the ambient term (seed §4.4 leaves the function open): the
// ray's opacity, darkened by up to one half where the first matter lies deep along the chord
// (creases) rather than at its entry (edges). firstMatter ∈ [0, 1] is the table's channel 1.
CLOUDLUT_FN float ambientScale(float transmittance, float firstMatter) {
  return (1.0f - transmittance) * (1.0f - 0.5f * clamp(firstMatter, 0.0f, 1.0f));
}
