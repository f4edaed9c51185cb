// sky_shafts.glsl — light shafts (seed §5.6): the single-scattered sunlight that the clouds'
// shadow takes out of a view ray. Along the ray x(t) = eye + t·d the air's in-scattering of
// sunlight is ∫ T(0, t) J₁(t) dt (the aerial volume's single channel, S₁(t) from the camera to t);
// under a cloud the sunlight reaching x is the share V(x) = slabTransmittance(τ(x), g) of the
// sun's (τ the sun volume's optical depth toward the sun, the same share that lights the ground in
// the clouds' shadow), so the ray loses
//   ΔL = ∫ (1 − V(x(t))) dS₁(t) ≈ Σ_pieces (S₁(t_b) − S₁(t_a)) (1 − V(x(t_a + ξ (t_b − t_a))))
// over uShaftSteps equal pieces of the part of the ray inside the sun volume's coarsest cascade
// (columns and below its top slice: elsewhere the volume says no cloud lies toward the sun), ξ a
// fixed per-pixel offset in [0, 1) (interleaved gradient noise: banding becomes fine noise, the
// same every run). The orders ≥ 2 are left as they are (the shadow's diffuse light is in V).
// Needs sky_uniforms.glsl, cloudlut_shading.glsl (slabTransmittance) and the sun volume's
// sampling code.
uniform sampler3D uAerialSingle;  // S₁ at the aerial volume's slices
uniform float uAerialMax;         // m, the aerial volume's reach
uniform int uShaftSteps;          // pieces per ray; 0 = no light shafts
uniform float uLaterAsymmetry;    // mean cosine of the clouds' later phase function (slabTransmittance)

// S₁(t), sr⁻¹ per unit sun irradiance: the single scattering of sunlight from the camera to
// distance t (m) along the ray through screen point uv, from the aerial volume: linear in t
// between its slices d_k = uAerialMax ((k + 1) / AERIAL_SLICES)² (and from 0 at the camera to
// the first), as the in-scattering of a short piece of air is.
vec3 aerialSingleAt(vec2 uv, float t) {
  float w = sqrt(clamp(t / uAerialMax, 0.0, 1.0)) * float(AERIAL_SLICES) - 1.0;  // slice coordinate
  int k = int(floor(w));
  if (k < 0) {
    float d0 = uAerialMax / float(AERIAL_SLICES * AERIAL_SLICES);
    return texture(uAerialSingle, vec3(uv, 0.5 / float(AERIAL_SLICES))).rgb * clamp(t / d0, 0.0, 1.0);
  }
  if (k >= AERIAL_SLICES - 1) return texture(uAerialSingle, vec3(uv, 1.0 - 0.5 / float(AERIAL_SLICES))).rgb;
  float da = uAerialMax * float((k + 1) * (k + 1)) / float(AERIAL_SLICES * AERIAL_SLICES);
  float db = uAerialMax * float((k + 2) * (k + 2)) / float(AERIAL_SLICES * AERIAL_SLICES);
  vec3 Sa = texture(uAerialSingle, vec3(uv, (float(k) + 0.5) / float(AERIAL_SLICES))).rgb;
  vec3 Sb = texture(uAerialSingle, vec3(uv, (float(k) + 1.5) / float(AERIAL_SLICES))).rgb;
  return mix(Sa, Sb, clamp((t - da) / (db - da), 0.0, 1.0));
}

// The part [tIn, tOut] of the ray eye + t·d, t ∈ [0, tEnd], inside the coarsest cascade's
// columns and below its top slice (empty when tOut <= tIn).
vec2 shaftRange(vec3 d, float tEnd) {
  int k = uSunCascades - 1;
  vec3 g0 = (uSunToGrid[k] * vec4(uEyeWorld, 1.0)).xyz, gd = (uSunToGrid[k] * vec4(d, 0.0)).xyz;
  vec3 lo = vec3(0.0, 0.0, -1e30), hi = vec3(vec2(uSunDims.xy) - 1.0, float(uSunDims.z) - 1.0);
  vec2 range = vec2(0.0, tEnd);
  for (int i = 0; i < 3; ++i) {
    if (abs(gd[i]) < 1e-12) {
      if (g0[i] < lo[i] || g0[i] > hi[i]) return vec2(0.0);
      continue;
    }
    float a = (lo[i] - g0[i]) / gd[i], b = (hi[i] - g0[i]) / gd[i];
    range = vec2(max(range.x, min(a, b)), min(range.y, max(a, b)));
  }
  return range;
}

// The shafts' loss ΔL of in-scattered radiance along the ray d of screen point uv, pixel `pixel`
// (sr⁻¹ per unit sun irradiance): lossFar from the camera to tEnd (m; the ray's end, the ground or
// the top, capped at the aerial volume's reach), lossNear from the camera to tNear (m; the
// clouds' distance). Both 0 when the shafts are off or no sun volume was built.
void shaftLoss(vec3 d, vec2 uv, ivec2 pixel, float tEnd, float tNear, out vec3 lossFar, out vec3 lossNear) {
  lossFar = vec3(0.0);
  lossNear = vec3(0.0);
  if (uShaftSteps <= 0 || uSunCascades <= 0) return;
  vec2 range = shaftRange(d, min(tEnd, uAerialMax));
  if (range.y <= range.x) return;
  float xi = fract(52.9829189 * fract(0.06711056 * float(pixel.x) + 0.00583715 * float(pixel.y)));
  float piece = (range.y - range.x) / float(uShaftSteps);
  vec3 Sa = aerialSingleAt(uv, range.x);
  for (int i = 0; i < uShaftSteps; ++i) {
    float ta = range.x + float(i) * piece, tb = ta + piece;
    vec3 Sb = aerialSingleAt(uv, tb);
    float shadow = 1.0 - slabTransmittance(sunOpticalDepth(uEyeWorld + (ta + xi * piece) * d), uLaterAsymmetry);
    lossFar += (Sb - Sa) * shadow;
    if (tb <= tNear)
      lossNear += (Sb - Sa) * shadow;
    else if (ta < tNear)
      lossNear += (aerialSingleAt(uv, tNear) - Sa) * shadow;
    Sa = Sb;
  }
}
