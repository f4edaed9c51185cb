// cloudlut_atmosphere_nodes.glsl — what one node of the multiple-scattering and sky-irradiance
// tables holds, as the integrals the baker evaluates (src/bake/AtmosphereBaker.h; an engine may
// bake them on the GPU with the same code). Needs cloudlut_atmosphere_sky.glsl and what it needs.
// On the GPU a node costs dirs² · steps loop passes in one invocation: the baker's 8² · 16 = 1024
// is safe, but Mesa's llvmpipe ends an invocation's loops after 65 535 passes in all, silently,
// so 64² directions (Hillaire's) with 16 steps would come out short there.

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
        AtmosphereRayStep st = atmosphereRayStep(a, r, mu, muS, nu, tMax, i, steps);
        float dt = st.dt, rt = st.rt, h = st.h, muSt = st.muSt;
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
//   L_n(ω) = ∫ T(0, t) σs(t) J_{n−1}(t, ω) dt + T(0, ground) (albedo/π) E_{n−1}(ground),
// with the source of order 1 the sun seen through the true phase functions,
//   σs J_0 = (σs_R P_R(nu) + σs_M P_M(nu)) T_sun, E_0 = T_sun max(mu_s, 0),
// and, from order 2 on, the order below scattered toward the ray's start through its moments
// (multipleScatteringSource: exact for the Rayleigh phase, the mean and dipole for Mie), taken
// where each point of the ray is (its own r, mu_s and frame) rather than where the ray starts:
// the Bruneton & Neyret 2008 §4 iteration (eqs. 6–9) with a source kept to the field's moments
// (Hillaire 2020 §5.5.2 keeps its mean alone). E_{n−1} is the irradiance of order n − 1 on the
// ground, ∫ L_{n−1} cos θ dω over the upper hemisphere. Each table block is the sum over n ≥ 1 of
// the order's moment.

// The moments of the radiance of scattering order n arriving at (r, mu_s) (the six blocks of the
// multiple-scattering table, see cloudlut_atmosphere_tables.glsl; sr⁻¹) and its horizontal
// irradiance (per unit sun irradiance, dimensionless).
struct ScatteringOrder {
  vec3 average;     // J_n   = (1/4π) ∫ L_n dω
  vec3 momentYY;    // Myy_n = (1/4π) ∫ L_n ω_y² dω (ω_y = cos θ from the zenith)
  vec3 momentXX;    // Mxx_n = (1/4π) ∫ L_n ω_x² dω (ω_x toward the sun's azimuth)
  vec3 momentXY;    // Mxy_n = (1/4π) ∫ L_n ω_x ω_y dω
  vec3 dipoleX;     // Dx_n  = (1/4π) ∫ L_n ω_x dω
  vec3 dipoleY;     // Dy_n  = (1/4π) ∫ L_n ω_y dω
  vec3 irradiance;  // E_n   = ∫ L_n max(ω_y, 0) dω
};

// The cosine from the zenith of the edge s ∈ [−1, 1] of the directions' zenith bins: s |s|, which
// crowds the bins about the horizon (8 bins put edges at cos θ = 0, ±0.0625, ±0.25, ±0.5625, ±1),
// where the radiance arriving at a point changes fastest with the elevation (the long grazing
// paths, the Earth's shadow at twilight).
CLOUDLUT_FN float orderBinCosine(float s) { return s * abs(s); }

// One node of order n from the tables of order n − 1 (`previous` its moments in the
// multiple-scattering table's layout, `previousIrradiance` E_{n−1} on its grid; unused when
// fromSun, which computes order 1 from the sun). The midpoint rule over `dirs` bins of cos θ in
// [−1, 1] (crowded about the horizon, orderBinCosine) times `dirs` bins of azimuth in [0, π], doubled (the field is symmetric about the
// sun's vertical plane), each ray in `steps` pieces whose ends grow as (i / steps)², each piece
// integrated exactly for a source and extinction constant over it.
CLOUDLUT_FN ScatteringOrder scatteringOrderNode(AtmosphereParameters a, AtmosphereTexture transmittanceTable,
                                                AtmosphereTexture previous,
                                                AtmosphereTexture previousIrradiance, float r, float muS,
                                                int dirs, int steps, bool fromSun) {
  vec3 sunDir = vec3(sqrt(max(1.0f - muS * muS, 0.0f)), muS, 0.0f);
  ScatteringOrder o;
  o.average = vec3(0.0f);
  o.momentYY = vec3(0.0f);
  o.momentXX = vec3(0.0f);
  o.momentXY = vec3(0.0f);
  o.dipoleX = vec3(0.0f);
  o.dipoleY = vec3(0.0f);
  o.irradiance = vec3(0.0f);
  for (int j = 0; j < dirs; ++j) {
    // zenith bin j between the edges orderBinCosine(1 − 2j/dirs) and orderBinCosine(1 − 2(j + 1)/dirs),
    // sampled at the image of its middle; its share of the sphere is half its width in cos θ
    float cosTheta = orderBinCosine(1.0f - 2.0f * (float(j) + 0.5f) / float(dirs));
    float share = 0.5f * (orderBinCosine(1.0f - 2.0f * float(j) / float(dirs)) -
                          orderBinCosine(1.0f - 2.0f * float(j + 1) / float(dirs))) / float(dirs);
    float sinTheta = sqrt(max(1.0f - cosTheta * cosTheta, 0.0f));
    for (int k = 0; k < dirs; ++k) {
      float phi = CLOUDLUT_PI * (float(k) + 0.5f) / float(dirs);
      vec3 w = vec3(sinTheta * cos(phi), cosTheta, sinTheta * sin(phi));
      float mu = w.y, nu = dot(w, sunDir);
      float pR = phaseRayleigh(nu), pM = phaseCornetteShanks(nu, a.mieG);
      float tMax = distanceToAtmosphereEnd(a, r, mu);
      vec3 T = vec3(1.0f), L = vec3(0.0f);
      for (int i = 0; i < steps; ++i) {
        AtmosphereRayStep st = atmosphereRayStep(a, r, mu, muS, nu, tMax, i, steps);
        float dt = st.dt, t = st.t, rt = st.rt, h = st.h, muSt = st.muSt;
        vec3 sigmaT = atmosphereExtinction(a, h);
        vec3 sR = rayleighScatteringAt(a, h);
        float sM = mieScatteringAt(a, h);
        vec3 J = fromSun ? (sR * pR + vec3(sM * pM)) *
                               transmittanceToSun(a, transmittanceTable, rt, muSt, CLOUDLUT_SUN_ANGULAR_RADIUS)
                         : multipleScatteringSource(a, previous, rt, muSt, clamp((r * mu + t) / rt, -1.0f, 1.0f), nu);
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
      L *= share;  // (1/4π) ∫ over the cell and its mirror image
      o.average += L;
      o.momentYY += L * (w.y * w.y);
      o.momentXX += L * (w.x * w.x);
      o.momentXY += L * (w.x * w.y);
      o.dipoleX += L * w.x;
      o.dipoleY += L * w.y;
      o.irradiance += L * (4.0f * CLOUDLUT_PI * max(w.y, 0.0f));
    }
  }
  return o;
}

// The ratio of successive orders q = J_N / J_{N−1} per channel, from the averages of the last two
// orders (`last` J_N, `previous` J_{N−1}), clamped to [0, 0.9] (it settles after a few orders).
CLOUDLUT_FN vec3 multipleScatteringOrderRatio(vec3 last, vec3 previous) {
  return clamp(last / max(previous, vec3(1e-30f)), vec3(0.0f), vec3(0.9f));
}

// One moment (any block) of the orders ≥ 1 from its sum over the orders 1 … N (`sum`) and its
// value at order N (`last`): the orders beyond N as the geometric tail last · q / (1 − q), q from
// multipleScatteringOrderRatio (every moment decays as the average does once the field's shape
// settles).
CLOUDLUT_FN vec3 multipleScatteringFromOrders(vec3 sum, vec3 last, vec3 q) {
  return sum + last * q / (vec3(1.0f) - q);
}
