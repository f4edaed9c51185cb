// sky_view.comp.glsl — the sky-view table of one frame (Hillaire 2020, §5.3): per texel, the
// in-scattered radiance along its direction from the camera to the ground or the top of the
// atmosphere (integrateSkySegment), per unit sun irradiance. Needs sky_uniforms.glsl.
layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = 0) uniform writeonly image3D uSkyView;

void main() {
  ivec2 size = imageSize(uSkyView).xy;
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= size.x || p.y >= size.y) return;
  // texel centres at the ends of both axes: u covers [0, π] and v both poles exactly
  vec2 uv = vec2(p) / vec2(size - 1);
  vec3 d = skyViewDirection(uv);
  float r = length(uEyePlanet);
  float mu = dot(uEyePlanet, d) / r, muS = dot(uEyePlanet, uSun) / r;
  float tMax = distanceToAtmosphereEnd(uAtmosphere, r, mu);
  SkySegment s = integrateSkySegment(uAtmosphere, uTransmittance, uMultiple, r, mu, muS, dot(d, uSun), tMax,
                                     CLOUDLUT_SKY_STEPS, uMsWeight);
  imageStore(uSkyView, ivec3(p, 0), vec4(s.radiance, 1.0));
}
