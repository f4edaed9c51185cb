// cloudlut_phase.glsl — phase functions, shared by the baker (C++ through GLM) and the shaders.
// Each returns the probability density of scattering by the angle θ, in sr⁻¹, normalised so
// that its integral over the sphere of directions is 1. mu = cos θ, the cosine of the
// scattering angle (1 = forward, i.e. looking into the sun).

#ifndef CLOUDLUT_FN
#define CLOUDLUT_FN
#endif

const float CLOUDLUT_INV_4PI = 0.0795774715459477f;

// Isotropic: 1 / 4π.
CLOUDLUT_FN float phaseIsotropic() { return CLOUDLUT_INV_4PI; }

// Henyey–Greenstein: (1 - g²) / (4π (1 + g² - 2 g mu)^{3/2}).
CLOUDLUT_FN float phaseHenyeyGreenstein(float mu, float g) {
  float d = max(1.0f + g * g - 2.0f * g * mu, 1e-12f);
  return CLOUDLUT_INV_4PI * (1.0f - g * g) / (d * sqrt(d));
}

// Cornette–Shanks, seed eq. 7: 3(1 - g²)(1 + mu²) / (8π (2 + g²)(1 + g² - 2 g mu)^{3/2}).
CLOUDLUT_FN float phaseCornetteShanks(float mu, float g) {
  float d = max(1.0f + g * g - 2.0f * g * mu, 1e-12f);
  return CLOUDLUT_INV_4PI * 1.5f * (1.0f - g * g) / (2.0f + g * g) * (1.0f + mu * mu) / (d * sqrt(d));
}

// Draine (2003): HG times (1 + a mu²) / (1 + a (1 + 2 g²) / 3); a = 1 gives Cornette–Shanks.
CLOUDLUT_FN float phaseDraine(float mu, float g, float a) {
  return phaseHenyeyGreenstein(mu, g) * (1.0f + a * mu * mu) / (1.0f + a * (1.0f + 2.0f * g * g) / 3.0f);
}

// Jendersie–d'Eon fit for water droplets of diameter d µm (valid 5 ≤ d ≤ 50), with the
// published constants (Jendersie & d'Eon 2023; seed 000 quotes the fit, its w constant with a
// typo, −0.664888 for −0.665888): returns (g_HG, g_D, alpha, w).
CLOUDLUT_FN vec4 jendersieDeonParameters(float d) {
  return vec4(exp(-0.0990567f / (d - 1.67154f)),
              exp(-2.20679f / (d + 3.91029f) - 0.428934f),
              exp(3.62489f - 8.29288f / (d + 5.52825f)),
              exp(-0.599085f / (d - 0.641583f) - 0.665888f));
}

// Jendersie–d'Eon phase: (1 - w) HG(g_HG) + w Draine(g_D, alpha), parameters from above.
CLOUDLUT_FN float phaseJendersieDeon(float mu, vec4 p) {
  return (1.0f - p.w) * phaseHenyeyGreenstein(mu, p.x) + p.w * phaseDraine(mu, p.y, p.z);
}

// The kinds of phaseFunction() (the tables' JSON stores the same numbers).
const int CLOUDLUT_PHASE_ISOTROPIC = 0;
const int CLOUDLUT_PHASE_HENYEY_GREENSTEIN = 1;
const int CLOUDLUT_PHASE_CORNETTE_SHANKS = 2;
const int CLOUDLUT_PHASE_JENDERSIE_DEON = 3;

// Phase function selected by kind: isotropic, Henyey–Greenstein (param = g), Cornette–Shanks
// (param = g) or Jendersie–d'Eon (param = droplet diameter in µm); any other kind is isotropic.
CLOUDLUT_FN float phaseFunction(int kind, float mu, float param) {
  if (kind == CLOUDLUT_PHASE_HENYEY_GREENSTEIN) return phaseHenyeyGreenstein(mu, param);
  if (kind == CLOUDLUT_PHASE_CORNETTE_SHANKS) return phaseCornetteShanks(mu, param);
  if (kind == CLOUDLUT_PHASE_JENDERSIE_DEON) return phaseJendersieDeon(mu, jendersieDeonParameters(param));
  return phaseIsotropic();
}
