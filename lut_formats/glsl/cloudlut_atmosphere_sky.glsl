// cloudlut_atmosphere_sky.glsl — radiance of the sky, the sun's disc and the ground from the
// atmosphere's tables: what the renderer evaluates per frame and the bench checks against the
// brute-force reference (src/reference/AtmosphereReference.h). Needs cloudlut_geometry.glsl,
// cloudlut_phase.glsl, cloudlut_atmosphere.glsl and cloudlut_atmosphere_tables.glsl.

#ifndef CLOUDLUT_FN
#define CLOUDLUT_FN
#endif

// Angular radius of the sun's disc, rad (0.2666°).
const float CLOUDLUT_SUN_ANGULAR_RADIUS = 0.004653f;

// Pieces per view ray of the renderer's sky and of the bench's check of it.
const int CLOUDLUT_SKY_STEPS = 40;

// In-scattered radiance and transmittance of a segment of a view ray.
struct SkySegment {
  vec3 radiance;       // sr⁻¹ per unit sun irradiance, all the orders asked for
  vec3 single;         // sr⁻¹ per unit sun irradiance, the single scattering of sunlight in it
  vec3 transmittance;  // dimensionless
};

// Piece i of `steps` of the ray segment [0, tMax] (m) from radius r (m) with zenith cosine mu,
// the sun at zenith cosine muS and at cosine nu from the ray. The pieces' ends grow as
// (i / steps)², so they are short near the start where the air is densest along a level ray:
// dt its length and t its middle (m), rt the radius there (m, clamped to the atmosphere), h the
// altitude (m) and muSt the sun's zenith cosine at that point.
struct AtmosphereRayStep {
  float dt, t, rt, h, muSt;
};
CLOUDLUT_FN AtmosphereRayStep atmosphereRayStep(AtmosphereParameters a, float r, float mu, float muS, float nu,
                                                float tMax, int i, int steps) {
  float n = float(steps);
  float f0 = float(i) / n, f1 = float(i + 1) / n, fm = (float(i) + 0.5f) / n;
  AtmosphereRayStep s;
  s.dt = tMax * (f1 * f1 - f0 * f0);
  s.t = tMax * fm * fm;
  s.rt = clamp(radiusAlongRay(r, mu, s.t), a.bottomRadius, a.topRadius);
  s.h = s.rt - a.bottomRadius;
  s.muSt = clamp((r * muS + s.t * nu) / s.rt, -1.0f, 1.0f);
  return s;
}

// The segment [0, tMax] (m) of the ray from radius r (m) with zenith cosine mu, the sun at zenith
// cosine muS and at cosine nu from the ray: L = ∫ T(0, t) J(t) dt, T = exp(−∫ σt), with the
// source J = (σs_R P_R(nu) + σs_M P_M(nu)) T_sun + msWeight · multipleScatteringSource (single
// scattering, Bruneton & Neyret 2008 eq. 4; orders ≥ 2, Hillaire 2020 §5.5.2 eq. 11 with the
// phase functions applied to the field's moments, multipleScatteringSource). The
// segment is cut into `steps` pieces (atmosphereRayStep), each integrated exactly
// for a source and extinction constant over it (Hillaire 2015, energy-conserving integration).
// msWeight = 0 gives single scattering only (--sky-orders 1).
CLOUDLUT_FN SkySegment integrateSkySegment(AtmosphereParameters a, AtmosphereTexture transmittanceTable,
                                           AtmosphereTexture multipleTable, float r, float mu, float muS, float nu,
                                           float tMax, int steps, float msWeight) {
  float pR = phaseRayleigh(nu), pM = phaseCornetteShanks(nu, a.mieG);
  SkySegment s;
  s.radiance = vec3(0.0f);
  s.single = vec3(0.0f);
  s.transmittance = vec3(1.0f);
  for (int i = 0; i < steps; ++i) {
    AtmosphereRayStep st = atmosphereRayStep(a, r, mu, muS, nu, tMax, i, steps);
    float dt = st.dt, t = st.t, rt = st.rt, h = st.h, muSt = st.muSt;
    vec3 sigmaT = atmosphereExtinction(a, h);
    vec3 sR = rayleighScatteringAt(a, h);
    float sM = mieScatteringAt(a, h);
    vec3 sun = transmittanceToSun(a, transmittanceTable, rt, muSt, CLOUDLUT_SUN_ANGULAR_RADIUS);
    vec3 J1 = (sR * pR + vec3(sM * pM)) * sun;
    vec3 J = J1;
    if (msWeight > 0.0f)
      J += msWeight * multipleScatteringSource(a, multipleTable, rt, muSt, clamp((r * mu + t) / rt, -1.0f, 1.0f), nu);
    vec3 stepT = exp(-sigmaT * dt);
    vec3 weight = s.transmittance * (vec3(1.0f) - stepT) / max(sigmaT, vec3(1e-20f));  // ∫ T dt over the piece
    s.radiance += weight * J;
    s.single += weight * J1;
    s.transmittance *= stepT;
  }
  return s;
}

// Radiance leaving the Lambertian ground (albedo/π) at zenith cosine of the sun muS, per unit sun
// irradiance: direct sunlight through the atmosphere times `sunVisibility` (the clouds' shadow,
// 1 = unshadowed) plus the sky's irradiance (Bruneton & Neyret 2008, eq. 10, first bounce).
CLOUDLUT_FN vec3 groundRadiance(AtmosphereParameters a, AtmosphereTexture transmittanceTable,
                                AtmosphereTexture irradianceTable, float muS, float sunVisibility) {
  vec3 sun = transmittanceToSun(a, transmittanceTable, a.bottomRadius, muS, CLOUDLUT_SUN_ANGULAR_RADIUS);
  vec3 sky = skyIrradianceLookup(a, irradianceTable, a.bottomRadius, muS);
  return a.groundAlbedo * CLOUDLUT_INV_4PI * 4.0f * (sun * max(muS, 0.0f) * sunVisibility + sky);
}

// Limb darkening of the sun's disc, I(θ)/I(0) = 1 − u (1 − cos ψ) with ψ the angle between the
// surface normal and the line of sight, u = 0.6 (the linear law; Neckel & Labs 1994 give
// u ≈ 0.6 in the visible). cosAngle: cosine between the view ray and the sun's centre.
CLOUDLUT_FN float sunLimbDarkening(float cosAngle) {
  float sinRatio = sqrt(max(1.0f - cosAngle * cosAngle, 0.0f)) / sin(CLOUDLUT_SUN_ANGULAR_RADIUS);
  float cosPsi = sqrt(max(1.0f - sinRatio * sinRatio, 0.0f));
  return 1.0f - 0.6f * (1.0f - cosPsi);
}

// Radiance of the sun's disc at the top of the atmosphere per unit sun irradiance, sr⁻¹: the
// limb-darkened profile normalised so that its integral over the disc is 1 (the mean of the
// linear law over the disc is 1 − u/3). 0 outside the disc.
CLOUDLUT_FN float sunDiscRadiance(float cosAngle) {
  float cosRadius = cos(CLOUDLUT_SUN_ANGULAR_RADIUS);
  if (cosAngle < cosRadius) return 0.0f;
  float halfSin = sin(0.5f * CLOUDLUT_SUN_ANGULAR_RADIUS);
  float solidAngle = 4.0f * CLOUDLUT_PI * halfSin * halfSin;  // 2π (1 − cos α), without cancellation
  return sunLimbDarkening(cosAngle) / ((1.0f - 0.2f) * solidAngle);
}
