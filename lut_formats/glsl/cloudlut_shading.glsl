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

// Share of the homogeneous sphere's multiple scattering LM(ρ) carried by a ray of the
// inhomogeneous particle: the ray's opacity 1 − e^{−τ} over the opacity of the same chord
// through the homogeneous sphere of density ρ, 1 − e^{−τh}. It is 1 on a ray as dense as the
// sphere, tends to τ/τh (the mean density) when both are thin, and 0 on an empty ray — where
// the seed's unscaled LM(ρ) would light up the transparent fringe of a particle. Dimensionless.
CLOUDLUT_FN float multipleScatteringShare(float tau, float tauHomogeneous) {
  float opacityHomogeneous = 1.0f - exp(-tauHomogeneous);
  if (opacityHomogeneous < 1e-6f) return tauHomogeneous > 0.0f ? clamp(tau / tauHomogeneous, 0.0f, 1.0f) : 0.0f;
  return clamp((1.0f - exp(-tau)) / opacityHomogeneous, 0.0f, 1.0f);
}

// Scale of the sky radiance for the ambient term (seed §4.4 leaves the function open): the
// ray's opacity, darkened by up to one half where the first matter lies deep along the chord
// (creases) rather than at its entry (edges). firstMatter ∈ [0, 1] is the table's channel 1.
CLOUDLUT_FN float ambientScale(float transmittance, float firstMatter) {
  return (1.0f - transmittance) * (1.0f - 0.5f * clamp(firstMatter, 0.0f, 1.0f));
}
