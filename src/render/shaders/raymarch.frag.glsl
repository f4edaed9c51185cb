// raymarch.frag.glsl — the ray-marched baseline (seeds 000/003) on the particle list: the
// medium of reference/ScenePathTracer.h (densities of overlapping particles add; each particle's
// extinction is σ·ρ·ρ̂ in its own unit-sphere units, so along a world direction ω it is
// σ·ρ·ρ̂·|M⁻¹ω|), marched with Beer–Lambert transmittance and Hillaire's energy-conserving
// step integration, shadow rays toward the sun, and Wrenninge's multiple-scattering octaves.
// Preceded by cloudlut_phase.glsl and particle_common.glsl (the particle records, read only; M⁻¹
// is toParticle, toParticle[0].w = |M⁻¹ l| the extinction scale toward the sun, toParticle[1].w
// the bounding-sphere radius). See src/render/RayMarchRenderer.h for the parameters.

uniform int uCount;
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

const int MAX_HITS = 48;
const int MAX_SHADOW_HITS = 24;

mat3 toParticle(int i) {
  return mat3(particles[i].toParticle[0].xyz, particles[i].toParticle[1].xyz, particles[i].toParticle[2].xyz);
}

float rhoHat(vec3 p) {
  float r2 = dot(p, p);
  if (r2 > 1.0) return 0.0;
  if (uModel == 0) return 1.0;
  if (uModel == 1) { float a = 1.0 - r2; return a * a; }
  vec3 tc = ((p + 1.0) * 0.5 * (uGridRes - 1.0) + 0.5) / uGridRes;
  return texture(uDensity, tc).r;
}

// World interval [t0, t1] of the ray (o, d) inside particle i (false when it misses).
bool interval(int i, vec3 o, vec3 d, out float t0, out float t1) {
  vec3 c = particles[i].centerDensity.xyz;
  vec3 oc = o - c;
  float bound = particles[i].toParticle[1].w;
  float bb = dot(oc, d);
  if (dot(oc, oc) - bb * bb > bound * bound) { t0 = t1 = 0.0; return false; }
  mat3 m = toParticle(i);
  vec3 po = m * oc, pd = m * d;
  float a = dot(pd, pd), b = dot(po, pd), cc = dot(po, po) - 1.0;
  float disc = b * b - a * cc;
  if (disc <= 0.0) { t0 = t1 = 0.0; return false; }
  float s = sqrt(disc);
  t0 = max((-b - s) / a, 0.0);
  t1 = (-b + s) / a;
  return t1 > t0;
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

  // Particles on the view ray: index, interval, extinction scale |M⁻¹ dir|.
  int hitIndex[MAX_HITS];
  float hitT0[MAX_HITS], hitT1[MAX_HITS];
  int hits = 0;
  float tMin = 1e30, tMax = 0.0;
  for (int i = 0; i < uCount && hits < MAX_HITS; ++i) {
    float t0, t1;
    if (!interval(i, uEye, dir, t0, t1)) continue;
    // Keep them sorted by entry (insertion sort).
    int k = hits++;
    while (k > 0 && hitT0[k - 1] > t0) {
      hitIndex[k] = hitIndex[k - 1]; hitT0[k] = hitT0[k - 1]; hitT1[k] = hitT1[k - 1]; --k;
    }
    hitIndex[k] = i; hitT0[k] = t0; hitT1[k] = t1;
    tMin = min(tMin, t0);
    tMax = max(tMax, t1);
  }
  if (hits == 0) { outColour = vec4(0.0, 0.0, 0.0, 1.0); outDistance = uNoDistance; return; }
  float viewScale[MAX_HITS];
  for (int k = 0; k < hits; ++k) viewScale[k] = length(toParticle(hitIndex[k]) * dir);

  // Segments to march: the union of the intervals (adaptive: empty space is skipped and the
  // steps are spread over the occupied length only) or the whole extent (fixed).
  float segA[MAX_HITS], segB[MAX_HITS];
  int segments = 0;
  if (uAdaptive != 0) {
    for (int k = 0; k < hits; ++k) {
      if (segments > 0 && hitT0[k] <= segB[segments - 1]) segB[segments - 1] = max(segB[segments - 1], hitT1[k]);
      else { segA[segments] = hitT0[k]; segB[segments] = hitT1[k]; ++segments; }
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
  for (int sg = 0; sg < segments && T > uMinTransmittance; ++sg) {
   int n = max(1, int(ceil((segB[sg] - segA[sg]) / dt - 1e-3)));
   float h = (segB[sg] - segA[sg]) / float(n);
   for (int j = 0; j < n && T > uMinTransmittance; ++j) {
    float t = segA[sg] + float(j) * h;
    float tm = t + 0.5 * h;
    vec3 x = uEye + tm * dir;
    float sigma = 0.0;
    for (int k = 0; k < hits; ++k) {
      if (tm < hitT0[k] || tm > hitT1[k]) continue;
      int i = hitIndex[k];
      sigma += uSigma * particles[i].centerDensity.w * rhoHat(toParticle(i) * (x - particles[i].centerDensity.xyz)) * viewScale[k];
    }
    if (sigma > 0.0) {
      vec3 source = vec3(0.0);
      if ((uTerms & 3) != 0) {
        // Shadow ray toward the sun: optical depth over the particles it crosses.
        int sIndex[MAX_SHADOW_HITS];
        int sHits = 0;
        float sEnd = 0.0;
        for (int i = 0; i < uCount && sHits < MAX_SHADOW_HITS; ++i) {
          float s0, s1;
          if (!interval(i, x, uSun, s0, s1)) continue;
          sIndex[sHits++] = i;
          sEnd = max(sEnd, s1);
        }
        float tau = 0.0;
        float sdt = sEnd / float(uShadowSteps);
        for (int j = 0; j < uShadowSteps && sHits > 0; ++j) {
          vec3 y = x + (float(j) + 0.5) * sdt * uSun;
          for (int k = 0; k < sHits; ++k) {
            int i = sIndex[k];
            tau += uSigma * particles[i].centerDensity.w * rhoHat(toParticle(i) * (y - particles[i].centerDensity.xyz)) *
                   particles[i].toParticle[0].w * sdt;
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
}
