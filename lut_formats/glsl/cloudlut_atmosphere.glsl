// cloudlut_atmosphere.glsl — the one definition of the atmosphere model: its parameters, the
// densities of its three constituents, their coefficients and phase functions, and the
// geometry of rays in a spherical shell. Shared by the baker (C++ through GLM, src/core/Glsl.h)
// and the shaders, in the subset both languages accept (see cloudlut_geometry.glsl).
//
// The model is the one of Bruneton & Neyret 2008 (§2) with the ozone layer of Bruneton 2017
// ("A new implementation", its atmosphere model section) and the constants Hillaire 2020
// (§4, table 1) uses for the Earth. Units: metres and m⁻¹. The planet's centre is the origin of
// the (r, mu) functions below; in the world (+y up, ground at y = 0) it sits at
// (0, -bottomRadius, 0), see atmosphereCentre().
//
// Radiance here is always per unit sun irradiance (sr⁻¹ m⁻² per W m⁻², i.e. sr⁻¹), as in the
// cloud tables.

#ifndef CLOUDLUT_FN
#define CLOUDLUT_FN
#endif

struct AtmosphereParameters {
  float bottomRadius;         // m, distance from the planet's centre to the ground
  float topRadius;            // m, distance from the centre to the top of the atmosphere
  vec3 rayleighScattering;    // m⁻¹, Rayleigh scattering coefficient at the ground (R, G, B)
  float rayleighScaleHeight;  // m, Rayleigh density falls as exp(-h / H_R)
  float mieScattering;        // m⁻¹, Mie (aerosol) scattering at the ground
  float mieAbsorption;        // m⁻¹, Mie absorption at the ground
  float mieScaleHeight;       // m, Mie density falls as exp(-h / H_M)
  float mieG;                 // Cornette–Shanks asymmetry g of the Mie phase, in (-1, 1)
  vec3 ozoneAbsorption;       // m⁻¹, ozone absorption at the tent's peak (R, G, B)
  float ozoneBottom;          // m, altitude where the ozone tent starts (density 0)
  float ozonePeak;            // m, altitude of the tent's peak (density 1)
  float ozoneTop;             // m, altitude where the tent ends (density 0)
  vec3 groundAlbedo;          // Lambertian reflectance of the ground, [0, 1]
};

// The Earth-like defaults (issue 13; Hillaire 2020 table 1 and Bruneton 2017's ozone layer).
CLOUDLUT_FN AtmosphereParameters defaultAtmosphere() {
  AtmosphereParameters a;
  a.bottomRadius = 6360e3f;
  a.topRadius = 6460e3f;
  a.rayleighScattering = vec3(5.802e-6f, 13.558e-6f, 33.1e-6f);
  a.rayleighScaleHeight = 8e3f;
  a.mieScattering = 3.996e-6f;
  a.mieAbsorption = 4.40e-6f;
  a.mieScaleHeight = 1.2e3f;
  a.mieG = 0.8f;
  a.ozoneAbsorption = vec3(0.650e-6f, 1.881e-6f, 0.085e-6f);
  a.ozoneBottom = 10e3f;
  a.ozonePeak = 25e3f;
  a.ozoneTop = 40e3f;
  a.groundAlbedo = vec3(0.1f);
  return a;
}

// Relative densities at altitude h (m) above the ground, each 1 at its reference altitude:
// x = Rayleigh exp(-h/H_R), y = Mie exp(-h/H_M) (Bruneton & Neyret 2008, eq. 1), z = ozone, a
// tent 0 at ozoneBottom, 1 at ozonePeak, 0 at ozoneTop (Bruneton 2017, the ozone layer).
CLOUDLUT_FN vec3 atmosphereDensities(AtmosphereParameters a, float h) {
  float up = max(a.ozonePeak - a.ozoneBottom, 1.0f), down = max(a.ozoneTop - a.ozonePeak, 1.0f);
  float ozone = h < a.ozonePeak ? (h - a.ozoneBottom) / up : (a.ozoneTop - h) / down;
  return vec3(exp(-max(h, 0.0f) / a.rayleighScaleHeight), exp(-max(h, 0.0f) / a.mieScaleHeight),
              clamp(ozone, 0.0f, 1.0f));
}

// Extinction coefficient σt(h) = σs_R ρ_R + (σs_M + σa_M) ρ_M + σa_O ρ_O, m⁻¹ (Bruneton & Neyret
// 2008, eq. 2 with the ozone term).
CLOUDLUT_FN vec3 atmosphereExtinction(AtmosphereParameters a, float h) {
  vec3 d = atmosphereDensities(a, h);
  return a.rayleighScattering * d.x + vec3((a.mieScattering + a.mieAbsorption) * d.y) + a.ozoneAbsorption * d.z;
}

// Rayleigh scattering coefficient at h, m⁻¹.
CLOUDLUT_FN vec3 rayleighScatteringAt(AtmosphereParameters a, float h) {
  return a.rayleighScattering * atmosphereDensities(a, h).x;
}

// Mie scattering coefficient at h, m⁻¹ (grey).
CLOUDLUT_FN float mieScatteringAt(AtmosphereParameters a, float h) {
  return a.mieScattering * atmosphereDensities(a, h).y;
}

// Rayleigh phase function 3/(16π)(1 + nu²), sr⁻¹, nu the cosine of the scattering angle
// (Bruneton & Neyret 2008, eq. 2). The Mie phase is phaseCornetteShanks (cloudlut_phase.glsl).
CLOUDLUT_FN float phaseRayleigh(float nu) {
  return 0.0596831036594608f * (1.0f + nu * nu);
}

// --- Rays in the shell. r: distance from the centre (m); mu: cosine of the ray's zenith angle.

// Distance along the ray to the top boundary, m: the positive root of
// t² + 2 r mu t + r² − top² = 0 (Bruneton 2017, "distance to the top atmosphere boundary").
CLOUDLUT_FN float distanceToTop(AtmosphereParameters a, float r, float mu) {
  float disc = r * r * (mu * mu - 1.0f) + a.topRadius * a.topRadius;
  return max(-r * mu + sqrt(max(disc, 0.0f)), 0.0f);
}

// Distance along the ray to the ground, m (meaningful when rayHitsGround).
CLOUDLUT_FN float distanceToGround(AtmosphereParameters a, float r, float mu) {
  float disc = r * r * (mu * mu - 1.0f) + a.bottomRadius * a.bottomRadius;
  return max(-r * mu - sqrt(max(disc, 0.0f)), 0.0f);
}

// True when the ray from (r, mu) meets the ground: mu < 0 and r²(mu² − 1) + bottom² ≥ 0.
CLOUDLUT_FN bool rayHitsGround(AtmosphereParameters a, float r, float mu) {
  return mu < 0.0f && r * r * (mu * mu - 1.0f) + a.bottomRadius * a.bottomRadius >= 0.0f;
}

// Distance to where the ray leaves the atmosphere: the ground if it hits it, else the top.
CLOUDLUT_FN float distanceToAtmosphereEnd(AtmosphereParameters a, float r, float mu) {
  return rayHitsGround(a, r, mu) ? distanceToGround(a, r, mu) : distanceToTop(a, r, mu);
}

// Distance from the centre after travelling t along the ray: sqrt(t² + 2 r mu t + r²), m
// (Bruneton 2017, the law of cosines used by every integral along a ray).
CLOUDLUT_FN float radiusAlongRay(float r, float mu, float t) {
  return sqrt(max(t * t + 2.0f * r * mu * t + r * r, 0.0f));
}

// The planet's centre in world coordinates (+y up, ground at y = 0), m.
CLOUDLUT_FN vec3 atmosphereCentre(AtmosphereParameters a) {
  return vec3(0.0f, -a.bottomRadius, 0.0f);
}
