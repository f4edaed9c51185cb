// cloudlut_atmosphere_nodes.glsl — what one node of the multiple-scattering and sky-irradiance
// tables holds, as the integrals the baker evaluates (src/bake/AtmosphereBaker.h; an engine may
// bake them on the GPU with the same code). Needs cloudlut_atmosphere_sky.glsl and what it needs.

#ifndef CLOUDLUT_FN
#define CLOUDLUT_FN
#endif

// Ψms(r, mu_s), sr⁻¹ (Hillaire 2020, §5.5.2). From the point at radius r, over `dirs` × `dirs`
// directions ω of equal solid angle (uniform in cos θ and φ), each ray is marched in `steps`
// pieces to the ground or the top, with an isotropic phase 1/(4π):
//   L₂   = (1/4π) ∫ [∫ T σs T_sun /(4π) dt + T(ground) T_sun(ground) (albedo/π) max(mu_s,g, 0)] dω  (eq. 8)
//   f_ms = (1/4π) ∫ ∫ T σs dt dω                                                              (eq. 9)
// and returns L₂ / (1 − f_ms), the geometric series of the orders ≥ 2 (eq. 10).
CLOUDLUT_FN vec3 multipleScatteringNode(AtmosphereParameters a, AtmosphereTexture transmittanceTable, float r, float muS,
                                        int dirs, int steps) {
  vec3 sunDir = vec3(sqrt(max(1.0f - muS * muS, 0.0f)), muS, 0.0f);
  vec3 L2 = vec3(0.0f), fms = vec3(0.0f);
  float n = float(steps);
  for (int j = 0; j < dirs; ++j) {
    float cosTheta = 1.0f - 2.0f * (float(j) + 0.5f) / float(dirs);
    float sinTheta = sqrt(max(1.0f - cosTheta * cosTheta, 0.0f));
    for (int k = 0; k < dirs; ++k) {
      float phi = 2.0f * CLOUDLUT_PI * (float(k) + 0.5f) / float(dirs);
      vec3 w = vec3(sinTheta * cos(phi), cosTheta, sinTheta * sin(phi));
      float mu = w.y, nu = dot(w, sunDir);
      bool ground = rayHitsGround(a, r, mu);
      float tMax = distanceToAtmosphereEnd(a, r, mu);
      vec3 T = vec3(1.0f), L = vec3(0.0f), F = vec3(0.0f);
      for (int i = 0; i < steps; ++i) {
        float f0 = float(i) / n, f1 = float(i + 1) / n, fm = (float(i) + 0.5f) / n;
        float dt = tMax * (f1 * f1 - f0 * f0), t = tMax * fm * fm;
        float rt = clamp(radiusAlongRay(r, mu, t), a.bottomRadius, a.topRadius);
        float h = rt - a.bottomRadius;
        float muSt = clamp((r * muS + t * nu) / rt, -1.0f, 1.0f);
        vec3 sigmaT = atmosphereExtinction(a, h);
        vec3 sigmaS = rayleighScatteringAt(a, h) + vec3(mieScatteringAt(a, h));
        vec3 stepT = exp(-sigmaT * dt);
        vec3 w1 = T * (vec3(1.0f) - stepT) / max(sigmaT, vec3(1e-20f));  // ∫ T dt over the piece
        L += w1 * sigmaS * transmittanceToSun(a, transmittanceTable, rt, muSt, CLOUDLUT_SUN_ANGULAR_RADIUS) *
             CLOUDLUT_INV_4PI;
        F += w1 * sigmaS;
        T *= stepT;
      }
      if (ground) {
        float muSg = clamp((r * muS + tMax * nu) / a.bottomRadius, -1.0f, 1.0f);
        L += T * transmittanceToSun(a, transmittanceTable, a.bottomRadius, muSg, CLOUDLUT_SUN_ANGULAR_RADIUS) *
             a.groundAlbedo * (4.0f * CLOUDLUT_INV_4PI) * max(muSg, 0.0f);
      }
      L2 += L;
      fms += F;
    }
  }
  float count = float(dirs * dirs);
  L2 /= count;  // (1/4π) ∫ dω over equal-solid-angle cells of 4π / count each
  fms /= count;
  return L2 / max(vec3(1.0f) - fms, vec3(1e-3f));
}

// Sky irradiance E(r, mu_s) on a horizontal surface, per unit sun irradiance: ∫ L(ω) cos θ dω
// over the upper hemisphere (Bruneton & Neyret 2008, eq. 10), by the midpoint rule in
// (cos θ, φ) over `dirs` × `dirs` cells with φ over [0, π] doubled (the sky is symmetric about
// the sun's vertical plane), each ray integrated by integrateSkySegment with `steps` pieces.
CLOUDLUT_FN vec3 skyIrradianceNode(AtmosphereParameters a, AtmosphereTexture transmittanceTable,
                                   AtmosphereTexture multipleTable, float r, float muS, int dirs, int steps,
                                   float msWeight) {
  vec3 sunDir = vec3(sqrt(max(1.0f - muS * muS, 0.0f)), muS, 0.0f);
  vec3 E = vec3(0.0f);
  for (int j = 0; j < dirs; ++j) {
    float cosTheta = (float(j) + 0.5f) / float(dirs);
    float sinTheta = sqrt(max(1.0f - cosTheta * cosTheta, 0.0f));
    for (int k = 0; k < dirs; ++k) {
      float phi = CLOUDLUT_PI * (float(k) + 0.5f) / float(dirs);
      vec3 w = vec3(sinTheta * cos(phi), cosTheta, sinTheta * sin(phi));
      float tMax = distanceToAtmosphereEnd(a, r, w.y);
      SkySegment s = integrateSkySegment(a, transmittanceTable, multipleTable, r, w.y, muS, dot(w, sunDir), tMax,
                                         steps, msWeight);
      E += s.radiance * cosTheta;
    }
  }
  // cell area: (1 / dirs) in cos θ times (π / dirs) in φ, twice for the mirrored half
  return E * (2.0f * CLOUDLUT_PI / float(dirs * dirs));
}

// --- Scattering orders, one at a time (what the baker uses for Ψms by default; Hillaire's
// geometric series above stays for comparison). Order n's radiance arriving at a point along
// direction ω is, per unit sun irradiance,
//   L_n(ω) = ∫ T(0, t) σs(t) J_{n−1}(t) dt + T(0, ground) (albedo/π) E_{n−1}(ground),
// with the source of order 1 the sun seen through the true phase functions,
//   σs J_0 = (σs_R P_R(nu) + σs_M P_M(nu)) T_sun, E_0 = T_sun max(mu_s, 0),
// and, from order 2 on, the order below scattered toward the ray's start: its average
// J_{n−1} = (1/4π) ∫ L_{n−1} dω and vertical moment K_{n−1} = (1/4π) ∫ L_{n−1} cos²θ dω through
// the Rayleigh phase (rayleighFromMoments), its average alone for Mie, taken where each point of
// the ray is (its own r and mu_s) rather than where the ray starts: the Bruneton & Neyret 2008 §4
// iteration (eqs. 6–9) with a source that depends on the direction only through its zenith angle
// from the second order on (Hillaire 2020 §5.5.2 takes it isotropic). E_{n−1} is the irradiance
// of order n − 1 on the ground, ∫ L_{n−1} cos θ dω over the upper hemisphere.
// Ψms = Σ_{n ≥ 1} J_n and its moment Σ_{n ≥ 1} K_n (sr⁻¹).

// J_n, K_n and E_n of one node: average radiance, its vertical moment (sr⁻¹) and horizontal
// irradiance (per unit sun irradiance) of scattering order n at (r, mu_s).
struct ScatteringOrder {
  vec3 average;     // J_n = (1/4π) ∫ L_n dω, sr⁻¹
  vec3 moment;      // K_n = (1/4π) ∫ L_n cos²θ dω, sr⁻¹
  vec3 irradiance;  // E_n = ∫ L_n max(cos θ, 0) dω, dimensionless
};

// One node of order n from the tables of order n − 1 (`previous` J_{n−1} and K_{n−1} in the
// multiple-scattering table's layout, `previousIrradiance` E_{n−1} on its grid; unused when
// fromSun, which computes order 1 from the sun). The midpoint rule over `dirs` bins of cos θ in
// [−1, 1] times `dirs` bins of azimuth in [0, π], doubled (the field is symmetric about the
// sun's vertical plane), each ray in `steps` pieces whose ends grow as (i / steps)², each piece
// integrated exactly for a source and extinction constant over it.
CLOUDLUT_FN ScatteringOrder scatteringOrderNode(AtmosphereParameters a, AtmosphereTexture transmittanceTable,
                                                AtmosphereTexture previous,
                                                AtmosphereTexture previousIrradiance, float r, float muS,
                                                int dirs, int steps, bool fromSun) {
  vec3 sunDir = vec3(sqrt(max(1.0f - muS * muS, 0.0f)), muS, 0.0f);
  ScatteringOrder o;
  o.average = vec3(0.0f);
  o.moment = vec3(0.0f);
  o.irradiance = vec3(0.0f);
  float n = float(steps);
  for (int j = 0; j < dirs; ++j) {
    float cosTheta = 1.0f - 2.0f * (float(j) + 0.5f) / float(dirs);
    float sinTheta = sqrt(max(1.0f - cosTheta * cosTheta, 0.0f));
    for (int k = 0; k < dirs; ++k) {
      float phi = CLOUDLUT_PI * (float(k) + 0.5f) / float(dirs);
      vec3 w = vec3(sinTheta * cos(phi), cosTheta, sinTheta * sin(phi));
      float mu = w.y, nu = dot(w, sunDir);
      float pR = phaseRayleigh(nu), pM = phaseCornetteShanks(nu, a.mieG);
      float tMax = distanceToAtmosphereEnd(a, r, mu);
      vec3 T = vec3(1.0f), L = vec3(0.0f);
      for (int i = 0; i < steps; ++i) {
        float f0 = float(i) / n, f1 = float(i + 1) / n, fm = (float(i) + 0.5f) / n;
        float dt = tMax * (f1 * f1 - f0 * f0), t = tMax * fm * fm;
        float rt = clamp(radiusAlongRay(r, mu, t), a.bottomRadius, a.topRadius);
        float h = rt - a.bottomRadius;
        float muSt = clamp((r * muS + t * nu) / rt, -1.0f, 1.0f);
        vec3 sigmaT = atmosphereExtinction(a, h);
        vec3 sR = rayleighScatteringAt(a, h);
        float sM = mieScatteringAt(a, h);
        vec3 J = fromSun ? (sR * pR + vec3(sM * pM)) *
                               transmittanceToSun(a, transmittanceTable, rt, muSt, CLOUDLUT_SUN_ANGULAR_RADIUS)
                         : multipleScatteringSource(a, previous, rt, muSt, clamp((r * mu + t) / rt, -1.0f, 1.0f));
        vec3 stepT = exp(-sigmaT * dt);
        L += T * J * (vec3(1.0f) - stepT) / max(sigmaT, vec3(1e-20f));
        T *= stepT;
      }
      if (rayHitsGround(a, r, mu)) {
        float muSg = clamp((r * muS + tMax * nu) / a.bottomRadius, -1.0f, 1.0f);
        vec3 E = fromSun ? transmittanceToSun(a, transmittanceTable, a.bottomRadius, muSg, CLOUDLUT_SUN_ANGULAR_RADIUS) *
                               max(muSg, 0.0f)
                         : sunTableLookup(a, previousIrradiance, a.bottomRadius, muSg, CLOUDLUT_MULTIPLE_WIDTH,
                                          CLOUDLUT_MULTIPLE_HEIGHT, 0, 1);
        L += T * a.groundAlbedo * (4.0f * CLOUDLUT_INV_4PI) * E;
      }
      o.average += L;
      o.moment += L * (mu * mu);
      o.irradiance += L * max(mu, 0.0f);
    }
  }
  // each of the dirs² cells, mirrored, covers 4π / dirs² sr
  float count = float(dirs * dirs);
  o.average /= count;
  o.moment /= count;
  o.irradiance *= 4.0f * CLOUDLUT_PI / count;
  return o;
}

// Ψms (or its moment) from the orders 1 … N of J (or K) summed (`sum`) and the last two (`last`
// J_N, `previous` J_{N−1}): the orders beyond N as the geometric tail J_N q / (1 − q) with
// q = J_N / J_{N−1} per channel, clamped to [0, 0.9] (the ratio of successive orders settles
// after a few).
CLOUDLUT_FN vec3 multipleScatteringFromOrders(vec3 sum, vec3 last, vec3 previous) {
  vec3 q = clamp(last / max(previous, vec3(1e-30f)), vec3(0.0f), vec3(0.9f));
  return sum + last * q / (vec3(1.0f) - q);
}
