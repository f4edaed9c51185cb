// raymarch.frag.glsl — the ray-marched baseline (seeds 000/003) on the particle list: the
// medium of reference/ScenePathTracer.h (densities of overlapping particles add; each particle's
// extinction is σ·ρ·ρ̂ in its own unit-sphere units, so along a world direction ω it is
// σ·ρ·ρ̂·|M⁻¹ω|), marched with Beer–Lambert transmittance and Hillaire's energy-conserving
// step integration, shadow rays toward the sun, and Wrenninge's multiple-scattering octaves.
// Preceded by cloudlut_phase.glsl, particle_common.glsl (the particle records, read only; M⁻¹
// is toParticle, toParticle[0].w = |M⁻¹ l| the extinction scale toward the sun) and
// raymarch_cells.glsl (the particles on a ray) and loop_budget.glsl. See src/render/RayMarchRenderer.h for the
// parameters.

uniform vec3 uEye;
uniform vec3 uRay00, uRayDx, uRayDy;  // unnormalised ray = uRay00 + px·uRayDx + py·uRayDy
uniform float uHeight;
uniform vec3 uSun, uSunColor, uSkyColor;
uniform int uTerms;                    // 1 single (octave 0), 2 multiple (octaves ≥ 1), 4 ambient
uniform int uSteps, uAdaptive, uShadowSteps, uOctaves;
uniform vec3 uOctaveABC;               // a: extinction, b: contribution, c: anisotropy, per octave
uniform int uFirstKind, uLaterKind;
uniform float uFirstParam, uLaterParam;
uniform float uSigma;                  // β·R, unit optical radius
uniform int uModel;                    // 0 homogeneous, 1 radial (1 − r²)², 2 grid texture
uniform sampler3D uDensity;
uniform float uGridRes;
uniform float uMinTransmittance, uMinOpacityForDistance, uNoDistance;

layout(location = 0) out vec4 outColour;    // radiance, transmittance
layout(location = 1) out float outDistance;

// Pixels whose view ray or a shadow ray crossed more particles than it keeps (the farthest left
// out), and pixels whose loops the GL cut short (loop_budget.glsl).
layout(std430, binding = 3) buffer RayMarchCounters {
  uint droppedPixels;
  uint budgetPixels;
};

float rhoHat(vec3 p) {
  float r2 = dot(p, p);
  if (r2 > 1.0) return 0.0;
  if (uModel == 0) return 1.0;
  if (uModel == 1) { float a = 1.0 - r2; return a * a; }
  vec3 tc = ((p + 1.0) * 0.5 * (uGridRes - 1.0) + 0.5) / uGridRes;
  return texture(uDensity, tc).r;
}

float octavePhase(int i, float mu) {
  if (i == 0) return phaseFunction(uFirstKind, mu, uFirstParam);
  float ci = pow(uOctaveABC.z, float(i));
  if (uLaterKind == 1 || uLaterKind == 2) return phaseFunction(uLaterKind, mu, uLaterParam * ci);
  return mix(phaseIsotropic(), phaseFunction(uLaterKind, mu, uLaterParam), ci);
}

void main() {
  float px = gl_FragCoord.x, py = uHeight - gl_FragCoord.y;
  vec3 dir = normalize(uRay00 + px * uRayDx + py * uRayDy);

  // Particles on the view ray, by entry: index, interval (raymarch_cells.glsl).
  int dropped = 0;
  int hits = particlesOnRay(uEye, dir, MAX_HITS, dropped);
  if (hits == 0) { outColour = vec4(0.0, 0.0, 0.0, 1.0); outDistance = uNoDistance; return; }
  int viewIndex[MAX_HITS];
  float viewT0[MAX_HITS], viewT1[MAX_HITS];
  float viewScale[MAX_HITS];  // extinction scale |M⁻¹ dir|
  float tMin = hitT0[0], tMax = 0.0;
  for (int k = 0; k < hits; ++k) {
    viewIndex[k] = hitIndex[k]; viewT0[k] = hitT0[k]; viewT1[k] = hitT1[k];
    viewScale[k] = length(toParticle(hitIndex[k]) * dir);
    tMax = max(tMax, hitT1[k]);
  }

  // Segments to march: the union of the intervals (adaptive: empty space is skipped and the
  // steps are spread over the occupied length only) or the whole extent (fixed).
  float segA[MAX_HITS], segB[MAX_HITS];
  int segments = 0;
  if (uAdaptive != 0) {
    for (int k = 0; k < hits; ++k) {
      if (segments > 0 && viewT0[k] <= segB[segments - 1]) segB[segments - 1] = max(segB[segments - 1], viewT1[k]);
      else { segA[segments] = viewT0[k]; segB[segments] = viewT1[k]; ++segments; }
    }
  } else {
    segA[0] = tMin; segB[0] = tMax; segments = 1;
  }
  float occupied = 0.0;
  for (int k = 0; k < segments; ++k) occupied += segB[k] - segA[k];
  float dt = occupied / float(uSteps);

  float mu = dot(dir, uSun);
  float phase[16];
  for (int o = 0; o < uOctaves; ++o) phase[o] = octavePhase(o, mu);

  vec3 radiance = vec3(0.0);
  float T = 1.0;
  float distance = uNoDistance;
  int first = 0;
  for (int sg = 0; sg < segments && T > uMinTransmittance; ++sg) {
   int n = max(1, int(ceil((segB[sg] - segA[sg]) / dt - 1e-3)));
   float h = (segB[sg] - segA[sg]) / float(n);
   for (int j = 0; j < n && T > uMinTransmittance; ++j) {
    float t = segA[sg] + float(j) * h;
    float tm = t + 0.5 * h;
    vec3 x = uEye + tm * dir;
    float sigma = 0.0;
    // The particles whose interval holds tm: entries sorted, so from the first not yet left
    // behind (the midpoints only move on) to the first not yet entered.
    while (first < hits && viewT1[first] < tm) ++first;
    for (int k = first; k < hits && viewT0[k] <= tm; ++k) {
      if (tm > viewT1[k]) continue;
      int i = viewIndex[k];
      vec4 centerDensity = particleCenterDensity(i);
      sigma += uSigma * centerDensity.w * rhoHat(toParticle(i) * (x - centerDensity.xyz)) * viewScale[k];
    }
    if (sigma > 0.0) {
      vec3 source = vec3(0.0);
      if ((uTerms & 3) != 0) {
        // Shadow ray toward the sun: optical depth over the particles it crosses.
        int sHits = particlesOnRay(x, uSun, MAX_SHADOW_HITS, dropped);
        float sEnd = 0.0;
        for (int k = 0; k < sHits; ++k) sEnd = max(sEnd, hitT1[k]);
        float tau = 0.0;
        float sdt = sEnd / float(uShadowSteps);
        for (int j = 0; j < uShadowSteps && sHits > 0; ++j) {
          vec3 y = x + (float(j) + 0.5) * sdt * uSun;
          for (int k = 0; k < sHits; ++k) {
            int i = hitIndex[k];
            vec4 centerDensity = particleCenterDensity(i);
            tau += uSigma * centerDensity.w * rhoHat(toParticle(i) * (y - centerDensity.xyz)) * particleToParticle(i, 0).w *
                   sdt;
          }
        }
        float sun = 0.0;
        for (int o = 0; o < uOctaves; ++o) {
          if ((o == 0 && (uTerms & 1) == 0) || (o > 0 && (uTerms & 2) == 0)) continue;
          sun += pow(uOctaveABC.y, float(o)) * phase[o] * exp(-pow(uOctaveABC.x, float(o)) * tau);
        }
        source += uSunColor * sun;
      }
      // A uniform sky seen from inside a non-absorbing medium: in-scattered radiance = sky.
      if ((uTerms & 4) != 0) source += uSkyColor;
      // Hillaire: ∫ T σs S over the step with σ constant = T · S · (1 − e^{−σ h}) (albedo 1).
      float stepT = exp(-sigma * h);
      radiance += T * source * (1.0 - stepT);
      T *= stepT;
      if (distance == uNoDistance && 1.0 - T >= uMinOpacityForDistance) distance = tm;
    }
   }
  }
  outColour = vec4(radiance, T);
  outDistance = distance;
  if (dropped > 0) atomicAdd(droppedPixels, 1u);
  if (loopsWereCut()) atomicAdd(budgetPixels, 1u);
}
