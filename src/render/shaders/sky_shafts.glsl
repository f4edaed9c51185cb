// sky_shafts.glsl — light shafts (seed §5.6): the single-scattered sunlight that the clouds'
// shadow takes out of a view ray. Along the ray x(t) = eye + t·d the air's in-scattering of
// sunlight is S₁(t) = ∫₀ᵗ T(0, s) J₁(s) ds (the aerial volume's single channel); under a cloud
// the sunlight reaching x is the share V(x) = slabTransmittance(τ(x), g) of the sun's (τ the sun
// volume's optical depth toward the sun; the same share lights the ground in the clouds'
// shadow), so the ray loses
//   ΔL(t) = ∫₀ᵗ (1 − V(x(s))) dS₁(s).
// sky_shafts.comp.glsl tabulates ΔL per screen cell of SkyPass::kShaftCell × kShaftCell pixels
// at the aerial volume's slice distances; the composite reads it at each pixel's distances
// (cumulativeAt). The orders ≥ 2 are left as they are (the shadow's diffuse light is in V).
// Needs sky_aerial_slices.glsl.
uniform float uLaterAsymmetry;  // mean cosine of the clouds' later phase function (slabTransmittance)

// V(x): the share of the sun's irradiance that reaches world point x through the clouds, direct
// and scattered (slabTransmittance of the sun volume's optical depth toward the sun); it lights
// the ground in the clouds' shadow and the air the light shafts take from.
float cloudSunVisibility(vec3 x) { return slabTransmittance(sunOpticalDepth(x), uLaterAsymmetry); }

// A quantity accumulated from the camera (S₁, ΔL) at distance t (m) along the ray through screen
// point uv, from a volume that holds it at the aerial slices (depth AERIAL_SLICES): linear in t
// between slices and from 0 at the camera to the first, as the in-scattering of a short piece
// of air is; the last slice's value beyond it.
vec3 cumulativeAt(sampler3D volume, vec2 uv, float t) {
  float w = aerialSliceCoordinate(t);
  int k = int(floor(w));
  if (k < 0)
    return texture(volume, vec3(uv, 0.5 / float(AERIAL_SLICES))).rgb * clamp(t / aerialSliceDistance(0), 0.0, 1.0);
  if (k >= AERIAL_SLICES - 1) return texture(volume, vec3(uv, 1.0 - 0.5 / float(AERIAL_SLICES))).rgb;
  float da = aerialSliceDistance(k), db = aerialSliceDistance(k + 1);
  vec3 a = texture(volume, vec3(uv, (float(k) + 0.5) / float(AERIAL_SLICES))).rgb;
  vec3 b = texture(volume, vec3(uv, (float(k) + 1.5) / float(AERIAL_SLICES))).rgb;
  return mix(a, b, clamp((t - da) / (db - da), 0.0, 1.0));
}

// The part [tIn, tOut] of the ray eye + t·d, t ∈ [0, tEnd], inside the sun volume's coarsest
// cascade's columns and below its top slice, where alone the volume holds a shadow (empty when
// tOut <= tIn, or when no volume was built).
vec2 shaftRange(vec3 d, float tEnd) {
  if (uSunCascades <= 0) return vec2(0.0);
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
