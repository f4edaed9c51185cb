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
