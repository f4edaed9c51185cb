// cloudlut_atmosphere_tables.glsl — the atmosphere's sun-independent tables: how each is
// parameterised, what each node holds (the integrand the baker evaluates) and how each is
// looked up. Needs cloudlut_geometry.glsl (lutTexCoord), cloudlut_atmosphere.glsl.
//
//   transmittance       T(r, mu) to the top of the atmosphere, RGB, 256 × 64 (x_mu, x_r);
//   multiple scattering Ψms(r, mu_s) and its vertical moment, RGB, 32 × 32 × 2 (x_mu_s, x_r,
//                       block), the blocks stacked along the texture's height (Hillaire 2020,
//                       §5.5.2, with the moment of rayleighFromMoments);
//   sky irradiance      E(r, mu_s) on a horizontal surface, RGB, 64 × 16 (x_mu_s, x_r).
//
// Every table stores node i of an axis of n nodes at the unit-range value x = i / (n − 1), the
// centre of texel i (lutTexCoord). A table is sampled through AtmosphereTexture and
// atmosphereTexture(table, uv): a sampler2D and texture() in GLSL; in C++ a texel array and the
// same bilinear, clamp-to-edge filter (lut_formats/cloudlut_glsl.hpp).

#ifndef CLOUDLUT_FN
#define CLOUDLUT_FN
#endif

#ifndef CLOUDLUT_ATMOSPHERE_TEXTURE_DEFINED
#define CLOUDLUT_ATMOSPHERE_TEXTURE_DEFINED
#define AtmosphereTexture sampler2D
vec3 atmosphereTexture(sampler2D table, vec2 uv) { return texture(table, uv).rgb; }
#endif

const int CLOUDLUT_TRANSMITTANCE_WIDTH = 256;   // x_mu nodes
const int CLOUDLUT_TRANSMITTANCE_HEIGHT = 128;  // x_r nodes (64 leaves 1.6% at the horizon 500 m up)
const int CLOUDLUT_MULTIPLE_WIDTH = 32;         // x_mu_s nodes
const int CLOUDLUT_MULTIPLE_HEIGHT = 32;        // x_r nodes
const int CLOUDLUT_IRRADIANCE_WIDTH = 64;       // x_mu_s nodes
const int CLOUDLUT_IRRADIANCE_HEIGHT = 16;      // x_r nodes

// --- Transmittance: Bruneton & Neyret 2008 §4 (its r and mu mapping) as revised by Bruneton
// 2017 ("transmittance, precomputation"): x_r = ρ / H with ρ = sqrt(r² − bottom²) and
// H = sqrt(top² − bottom²); x_mu = (d − d_min) / (d_max − d_min) with d the distance to the top,
// d_min = top − r and d_max = ρ + H. Only rays that miss the ground are stored.

// (x_mu, x_r) ∈ [0, 1]² of (r, mu).
CLOUDLUT_FN vec2 transmittanceUnitRange(AtmosphereParameters a, float r, float mu) {
  float H = sqrt(a.topRadius * a.topRadius - a.bottomRadius * a.bottomRadius);
  float rho = sqrt(max(r * r - a.bottomRadius * a.bottomRadius, 0.0f));
  float d = distanceToTop(a, r, mu);
  float dMin = a.topRadius - r, dMax = rho + H;
  return vec2(dMax > dMin ? (d - dMin) / (dMax - dMin) : 0.0f, rho / H);
}

// (r, mu) of a node at (x_mu, x_r) ∈ [0, 1]²: the inverse of transmittanceUnitRange, with
// mu = (H² − ρ² − d²) / (2 r d) from the law of cosines.
CLOUDLUT_FN vec2 transmittanceRadiusMu(AtmosphereParameters a, vec2 x) {
  float H = sqrt(a.topRadius * a.topRadius - a.bottomRadius * a.bottomRadius);
  float rho = H * x.y;
  float r = sqrt(rho * rho + a.bottomRadius * a.bottomRadius);
  float dMin = a.topRadius - r, dMax = rho + H;
  float d = dMin + x.x * (dMax - dMin);
  float mu = d == 0.0f ? 1.0f : (H * H - rho * rho - d * d) / (2.0f * r * d);
  return vec2(r, clamp(mu, -1.0f, 1.0f));
}

// Optical depth from (r, mu) to the top, ∫ σt dt (m⁻¹·m, dimensionless), by the composite
// Gauss–Legendre rule of two points per panel over `panels` equal panels. What a
// transmittance node stores is exp(−this) (Bruneton & Neyret 2008, eq. 3).
CLOUDLUT_FN vec3 opticalDepthToTop(AtmosphereParameters a, float r, float mu, int panels) {
  float d = distanceToTop(a, r, mu);
  float dt = d / float(panels);
  vec3 sum = vec3(0.0f);
  for (int i = 0; i < panels; ++i) {
    float t0 = (float(i) + 0.5f - 0.288675134594813f) * dt;
    float t1 = (float(i) + 0.5f + 0.288675134594813f) * dt;
    sum += atmosphereExtinction(a, radiusAlongRay(r, mu, t0) - a.bottomRadius);
    sum += atmosphereExtinction(a, radiusAlongRay(r, mu, t1) - a.bottomRadius);
  }
  return sum * (0.5f * dt);
}

// T(r, mu) to the top from the table (the ray must miss the ground).
CLOUDLUT_FN vec3 transmittanceToTop(AtmosphereParameters a, AtmosphereTexture table, float r, float mu) {
  vec2 x = transmittanceUnitRange(a, r, mu);
  return atmosphereTexture(table, vec2(lutTexCoord(x.x, float(CLOUDLUT_TRANSMITTANCE_WIDTH)),
                                       lutTexCoord(x.y, float(CLOUDLUT_TRANSMITTANCE_HEIGHT))));
}

// Transmittance of sunlight reaching altitude r when the sun's zenith cosine is mu_s: T to the
// top times the fraction of the sun's disc (angular radius `sunRadius`, rad) above the
// horizon, a linear ramp over the disc (Bruneton 2017, "transmittance to the sun").
CLOUDLUT_FN vec3 transmittanceToSun(AtmosphereParameters a, AtmosphereTexture table, float r, float muS, float sunRadius) {
  float sinHorizon = a.bottomRadius / r;
  float cosHorizon = -sqrt(max(1.0f - sinHorizon * sinHorizon, 0.0f));
  float visible = clamp((muS - cosHorizon) / (2.0f * sunRadius) + 0.5f, 0.0f, 1.0f);
  return visible == 0.0f ? vec3(0.0f) : transmittanceToTop(a, table, r, max(muS, cosHorizon)) * visible;
}

// T between (r, mu) and the point a distance t along the ray: the ratio of two transmittances
// to the top, taken toward the ground when the ray meets it (Bruneton 2017, "transmittance to a
// point").
CLOUDLUT_FN vec3 transmittanceAlongRay(AtmosphereParameters a, AtmosphereTexture table, float r, float mu, float t,
                                       bool hitsGround) {
  float rt = clamp(radiusAlongRay(r, mu, t), a.bottomRadius, a.topRadius);
  float mut = clamp((r * mu + t) / rt, -1.0f, 1.0f);
  vec3 num = hitsGround ? transmittanceToTop(a, table, rt, -mut) : transmittanceToTop(a, table, r, mu);
  vec3 den = hitsGround ? transmittanceToTop(a, table, r, -mu) : transmittanceToTop(a, table, rt, mut);
  return min(num / max(den, vec3(1e-30f)), vec3(1.0f));
}

// --- Multiple scattering and irradiance: x_mu_s = (1 ± sqrt(|mu_s|)) / 2 (the sign of mu_s), which
// crowds the nodes about the horizon, where twilight changes fastest (32 nodes put the two
// nearest the horizon at mu_s = ±0.001 and the next at ±0.009; Hillaire 2020 §5.5.2 uses
// (mu_s + 1) / 2), and x_r = (r − bottom) / (top − bottom) (Bruneton 2017's irradiance texture
// uses the same r axis).

// (x_mu_s, x_r) of (r, mu_s).
CLOUDLUT_FN vec2 sunTableUnitRange(AtmosphereParameters a, float r, float muS) {
  float m = clamp(muS, -1.0f, 1.0f);
  return vec2(0.5f * (1.0f + (m < 0.0f ? -sqrt(-m) : sqrt(m))), (r - a.bottomRadius) / (a.topRadius - a.bottomRadius));
}

// (r, mu_s) of a node at (x_mu_s, x_r).
CLOUDLUT_FN vec2 sunTableRadiusMu(AtmosphereParameters a, vec2 x) {
  float s = 2.0f * x.x - 1.0f;
  return vec2(a.bottomRadius + x.y * (a.topRadius - a.bottomRadius), s * abs(s));
}

// A table on the (x_mu_s, x_r) grid of `width` × `height` nodes whose texture holds `blocks` such
// grids stacked along its height; block `block` (0-based) at (r, mu_s).
CLOUDLUT_FN vec3 sunTableLookup(AtmosphereParameters a, AtmosphereTexture table, float r, float muS, int width,
                                int height, int block, int blocks) {
  vec2 x = sunTableUnitRange(a, r, muS);
  return atmosphereTexture(table, vec2(lutTexCoord(x.x, float(width)),
                                       (float(block) + lutTexCoord(x.y, float(height))) / float(blocks)));
}

// Ψms(r, mu_s), sr⁻¹: the isotropic average (1/4π) ∫ L dω of the radiance of orders ≥ 1 arriving
// at a point, per unit sun irradiance; the in-scattered radiance of orders ≥ 2 per metre is
// about σs(h) Ψms (Hillaire 2020, §5.5.2, eq. 11). Block 0 of the multiple-scattering table.
CLOUDLUT_FN vec3 multipleScatteringLookup(AtmosphereParameters a, AtmosphereTexture table, float r, float muS) {
  return sunTableLookup(a, table, r, muS, CLOUDLUT_MULTIPLE_WIDTH, CLOUDLUT_MULTIPLE_HEIGHT, 0, 2);
}

// Its second moment in the vertical, (1/4π) ∫ L cos²θ dω (θ from the local zenith), sr⁻¹: 1/3 of
// Ψms for a field the same from every direction. Block 1 of the multiple-scattering table.
CLOUDLUT_FN vec3 multipleScatteringMomentLookup(AtmosphereParameters a, AtmosphereTexture table, float r, float muS) {
  return sunTableLookup(a, table, r, muS, CLOUDLUT_MULTIPLE_WIDTH, CLOUDLUT_MULTIPLE_HEIGHT, 1, 2);
}

// Radiance the Rayleigh phase scatters out of a field of average J and vertical moment K (both
// sr⁻¹) toward a direction of zenith cosine mu, per unit scattering coefficient, for a field the
// same at every azimuth: ∫ L(ω) 3/(16π)(1 + (ω·v)²) dω = (3/4)[(3J − K)/2 + (3K − J)/2 · mu²]
// (the second-moment tensor of L is diag((J − K)/2, K, (J − K)/2) · 4π). Equals J when K = J/3.
CLOUDLUT_FN vec3 rayleighFromMoments(vec3 J, vec3 K, float mu) {
  return 0.75f * (0.5f * (3.0f * J - K) + 0.5f * (3.0f * K - J) * (mu * mu));
}

// The in-scattered radiance of orders ≥ 2 per metre toward a direction of zenith cosine mu at
// (r, mu_s): Rayleigh through rayleighFromMoments, Mie as if the field were isotropic (σs_M Ψms).
CLOUDLUT_FN vec3 multipleScatteringSource(AtmosphereParameters a, AtmosphereTexture table, float r, float muS, float mu) {
  float h = r - a.bottomRadius;
  vec3 J = multipleScatteringLookup(a, table, r, muS);
  vec3 K = multipleScatteringMomentLookup(a, table, r, muS);
  return rayleighScatteringAt(a, h) * rayleighFromMoments(J, K, mu) + vec3(mieScatteringAt(a, h)) * J;
}

// Sky irradiance on a horizontal surface at (r, mu_s), per unit sun irradiance (W m⁻² per
// W m⁻²): the integral over the upper hemisphere of the sky radiance (all orders the table was
// baked with) times the cosine to the zenith (Bruneton & Neyret 2008, eq. 10, indirect term).
CLOUDLUT_FN vec3 skyIrradianceLookup(AtmosphereParameters a, AtmosphereTexture table, float r, float muS) {
  return sunTableLookup(a, table, r, muS, CLOUDLUT_IRRADIANCE_WIDTH, CLOUDLUT_IRRADIANCE_HEIGHT, 0, 1);
}
