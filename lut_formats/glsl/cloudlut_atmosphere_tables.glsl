// cloudlut_atmosphere_tables.glsl — the atmosphere's sun-independent tables: how each is
// parameterised, what each node holds (the integrand the baker evaluates) and how each is
// looked up. Needs cloudlut_geometry.glsl (lutTexCoord), cloudlut_atmosphere.glsl.
//
//   transmittance       T(r, mu) to the top of the atmosphere, RGB, 256 × 64 (x_mu, x_r);
//   multiple scattering Ψms(r, mu_s) and the field's other moments, RGB, 32 × 32 × 6 (x_mu_s,
//                       x_r, block), the blocks stacked along the texture's height (Hillaire
//                       2020, §5.5.2, with the moments of rayleighFromMoments, mieFromMoments);
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

// --- Multiple scattering and irradiance: x_mu_s = (1 + sqrt(mu_s)) / 2 with the sun above the
// horizon, (1 − sqrt(−mu_s / 0.2)) / 2 below it, which crowds the nodes about the horizon, where
// twilight changes fastest (32 nodes put the nearest above the horizon at mu_s = 0.001, 0.009,
// 0.026, and below it at −0.0002, −0.0019, −0.0052, −0.0102, −0.0169, −0.025, −0.035: the
// field falls about exponentially as the sun sinks, and linear interpolation between nodes any
// farther apart overestimates it, by 9% at the sun −2° with the sky looking away from it, when
// the negative half spanned mu_s down to −1; Hillaire 2020 §5.5.2 uses (mu_s + 1) / 2), and
// x_r = (r − bottom) / (top − bottom) (Bruneton 2017's irradiance texture uses the same r axis).

// The deepest twilight the sun tables hold: |mu_s| of the lowest sun, below the horizon (−0.2,
// the sun 11.5° down, as Bruneton 2017's mu_s_min for the Earth); a lower sun reads that node.
const float CLOUDLUT_SUN_TABLE_MU_S_MIN = 0.2f;

// (x_mu_s, x_r) of (r, mu_s).
CLOUDLUT_FN vec2 sunTableUnitRange(AtmosphereParameters a, float r, float muS) {
  float m = clamp(muS, -1.0f, 1.0f);
  return vec2(0.5f * (1.0f + (m < 0.0f ? -sqrt(min(-m / CLOUDLUT_SUN_TABLE_MU_S_MIN, 1.0f)) : sqrt(m))),
              (r - a.bottomRadius) / (a.topRadius - a.bottomRadius));
}

// (r, mu_s) of a node at (x_mu_s, x_r).
CLOUDLUT_FN vec2 sunTableRadiusMu(AtmosphereParameters a, vec2 x) {
  float s = 2.0f * x.x - 1.0f;
  return vec2(a.bottomRadius + x.y * (a.topRadius - a.bottomRadius), s * abs(s) * (s < 0.0f ? CLOUDLUT_SUN_TABLE_MU_S_MIN : 1.0f));
}

// A table on the (x_mu_s, x_r) grid of `width` × `height` nodes whose texture holds `blocks` such
// grids stacked along its height; block `block` (0-based) at (r, mu_s).
CLOUDLUT_FN vec3 sunTableLookup(AtmosphereParameters a, AtmosphereTexture table, float r, float muS, int width,
                                int height, int block, int blocks) {
  vec2 x = sunTableUnitRange(a, r, muS);
  return atmosphereTexture(table, vec2(lutTexCoord(x.x, float(width)),
                                       (float(block) + lutTexCoord(x.y, float(height))) / float(blocks)));
}

// The multiple-scattering table holds, per node (r, mu_s), the first three moments of the radiance
// of orders ≥ 1 arriving at the point, L(ω) with ω the direction looked along, in the frame
// x = the sun's horizontal direction, y = the local zenith, z the horizontal 90° from x: the
// field is mirror-symmetric about the sun's vertical plane (z → −z), so the moments odd in z
// vanish and these six blocks are all of them, each sr⁻¹ per unit sun irradiance:
//   0  J    = (1/4π) ∫ L dω               Ψms (Hillaire 2020 §5.5.2)
//   1  Myy  = (1/4π) ∫ L ω_y² dω           the vertical moment
//   2  Mxx  = (1/4π) ∫ L ω_x² dω           along the sun's azimuth
//   3  Mxy  = (1/4π) ∫ L ω_x ω_y dω
//   4  Dx   = (1/4π) ∫ L ω_x dω            the dipole toward the sun's azimuth
//   5  Dy   = (1/4π) ∫ L ω_y dω            the dipole toward the zenith
// (Mzz = J − Mxx − Myy.) The Rayleigh phase, a polynomial of degree 2 in the scattering cosine,
// sees no more of the field than J and M: through them its in-scattering is exact.
const int CLOUDLUT_MULTIPLE_BLOCKS = 6;

// Block `block` of the multiple-scattering table at (r, mu_s).
CLOUDLUT_FN vec3 multipleScatteringBlock(AtmosphereParameters a, AtmosphereTexture table, float r, float muS, int block) {
  return sunTableLookup(a, table, r, muS, CLOUDLUT_MULTIPLE_WIDTH, CLOUDLUT_MULTIPLE_HEIGHT, block,
                        CLOUDLUT_MULTIPLE_BLOCKS);
}

// Ψms(r, mu_s), sr⁻¹: block 0; the in-scattered radiance of orders ≥ 2 per metre of an isotropic
// phase would be σs Ψms (Hillaire 2020, §5.5.2, eq. 11).
CLOUDLUT_FN vec3 multipleScatteringLookup(AtmosphereParameters a, AtmosphereTexture table, float r, float muS) {
  return multipleScatteringBlock(a, table, r, muS, 0);
}

// The components (v_x, v_y, v_z²) of a unit direction of zenith cosine mu at cosine nu from the
// sun, itself at zenith cosine muS, in the tables' frame (x the sun's horizontal direction):
// v_x = (nu − mu muS) / sqrt(1 − muS²) (0 with the sun at the zenith, where the field has no
// azimuth), v_z² = 1 − mu² − v_x².
CLOUDLUT_FN vec3 sunFrameDirection(float mu, float muS, float nu) {
  float sinS = sqrt(max(1.0f - muS * muS, 0.0f));
  float across = max(1.0f - mu * mu, 0.0f);
  float vx = sinS > 1e-4f ? clamp((nu - mu * muS) / sinS, -sqrt(across), sqrt(across)) : 0.0f;
  return vec3(vx, mu, max(across - vx * vx, 0.0f));
}

// Radiance the Rayleigh phase 3/(16π)(1 + (ω·v)²) scatters toward v out of the field of the six
// moments, per unit scattering coefficient: ∫ L(ω) P_R(ω·v) dω = (3/4)(J + vᵀMv), exact. J, the
// blocks 0–3 (J, Myy, Mxx, Mxy), v from sunFrameDirection.
CLOUDLUT_FN vec3 rayleighFromMoments(vec3 J, vec3 Myy, vec3 Mxx, vec3 Mxy, vec3 v) {
  vec3 Mzz = J - Mxx - Myy;
  return 0.75f * (J + Mxx * (v.x * v.x) + Myy * (v.y * v.y) + Mzz * v.z + 2.0f * Mxy * (v.x * v.y));
}

// Radiance the Cornette–Shanks phase of asymmetry g scatters toward v out of the field,
// per unit scattering coefficient, from the field's bands 0 and 1 (its mean and dipole):
// J + 3 g₁ D·v, with g₁ = 3g(4 + g²)/(5(2 + g²)) the phase's mean cosine (its first Legendre
// moment, from Henyey–Greenstein's g^ℓ and the factor (1 + ν²)); not below 0.
CLOUDLUT_FN vec3 mieFromMoments(vec3 J, vec3 Dx, vec3 Dy, vec3 v, float g) {
  float g1 = 3.0f * g * (4.0f + g * g) / (5.0f * (2.0f + g * g));
  return max(J + 3.0f * g1 * (Dx * v.x + Dy * v.y), vec3(0.0f));
}

// The in-scattered radiance of orders ≥ 2 per metre at (r, mu_s) toward a direction of zenith
// cosine mu at cosine nu from the sun, per unit sun irradiance (m⁻¹ sr⁻¹): σs_R times the Rayleigh
// phase on the field (rayleighFromMoments) plus σs_M times the Mie phase on it (mieFromMoments).
CLOUDLUT_FN vec3 multipleScatteringSource(AtmosphereParameters a, AtmosphereTexture table, float r, float muS, float mu,
                                          float nu) {
  float h = r - a.bottomRadius;
  vec3 v = sunFrameDirection(mu, muS, nu);
  vec3 J = multipleScatteringBlock(a, table, r, muS, 0);
  vec3 rayleigh = rayleighFromMoments(J, multipleScatteringBlock(a, table, r, muS, 1),
                                      multipleScatteringBlock(a, table, r, muS, 2),
                                      multipleScatteringBlock(a, table, r, muS, 3), v);
  vec3 mie = mieFromMoments(J, multipleScatteringBlock(a, table, r, muS, 4), multipleScatteringBlock(a, table, r, muS, 5),
                            v, a.mieG);
  return rayleighScatteringAt(a, h) * rayleigh + vec3(mieScatteringAt(a, h)) * mie;
}

// Sky irradiance on a horizontal surface at (r, mu_s), per unit sun irradiance (W m⁻² per
// W m⁻²): the integral over the upper hemisphere of the sky radiance (all orders the table was
// baked with) times the cosine to the zenith (Bruneton & Neyret 2008, eq. 10, indirect term).
CLOUDLUT_FN vec3 skyIrradianceLookup(AtmosphereParameters a, AtmosphereTexture table, float r, float muS) {
  return sunTableLookup(a, table, r, muS, CLOUDLUT_IRRADIANCE_WIDTH, CLOUDLUT_IRRADIANCE_HEIGHT, 0, 1);
}
