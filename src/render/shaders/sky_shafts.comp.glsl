// sky_shafts.comp.glsl — the light shafts' loss ΔL (sky_shafts.glsl) of one frame: per screen cell
// of SkyPass::kShaftCell × kShaftCell pixels (the ray through its centre), the cumulative loss at each
// aerial slice distance d_k, RGB, sr⁻¹ per unit sun irradiance. Each slice's stretch of the ray
// inside the sun volume is cut into SHAFT_PIECES equal pieces, each losing
// (S₁(t_b) − S₁(t_a)) (1 − V(x at its middle)). Needs sky_uniforms.glsl, cloudlut_shading.glsl
// (slabTransmittance), the sun volume's sampling code, sky_aerial_slices.glsl and sky_shafts.glsl.
layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = 0) uniform writeonly image3D uShaftLoss;
uniform sampler3D uAerialSingle;  // S₁ at the aerial slices (sky_aerial.comp.glsl)

void main() {
  ivec2 size = imageSize(uShaftLoss).xy;
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= size.x || p.y >= size.y) return;
  vec2 uv = (vec2(p) + 0.5) / vec2(size);
  vec3 d = screenRay(uv);
  float r = length(uEyePlanet), mu = dot(uEyePlanet, d) / r;
  vec2 range = shaftRange(d, min(distanceToAtmosphereEnd(uAtmosphere, r, mu), uAerialMax));
  vec3 loss = vec3(0.0);
  float t0 = 0.0;
  for (int k = 0; k < AERIAL_SLICES; ++k) {
    float t1 = aerialSliceDistance(k);
    float a = max(t0, range.x), b = min(t1, range.y);
    if (b > a) {
      float piece = (b - a) / float(SHAFT_PIECES);
      vec3 Sa = cumulativeAt(uAerialSingle, uv, a);
      for (int i = 0; i < SHAFT_PIECES; ++i) {
        float ta = a + float(i) * piece;
        vec3 Sb = cumulativeAt(uAerialSingle, uv, ta + piece);
        float shadow = 1.0 - cloudSunVisibility(uEyeWorld + (ta + 0.5 * piece) * d);
        loss += (Sb - Sa) * shadow;
        Sa = Sb;
      }
    }
    imageStore(uShaftLoss, ivec3(p, k), vec4(loss, 1.0));
    t0 = t1;
  }
}
