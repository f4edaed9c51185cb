// sky_aerial.comp.glsl — aerial perspective of one frame (Hillaire 2020, §5.4): a volume over the
// camera's frustum, AERIAL_SIZE × AERIAL_SIZE screen cells by AERIAL_SLICES distances
// d_k (aerialSliceDistance, sky_aerial_slices.glsl), holding the in-scattered radiance (RGB), the
// transmittance (RGB) and the single scattering of sunlight within that in-scattering (RGB; what
// the clouds' shadow can take away, sky_shafts.glsl) from the camera to d_k along the cell's ray.
// Each invocation marches one ray, segment by segment (integrateSkySegment re-based at the start
// of each).
layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = 0) uniform writeonly image3D uAerialInScatter;
layout(rgba32f, binding = 1) uniform writeonly image3D uAerialTransmittance;
layout(rgba32f, binding = 2) uniform writeonly image3D uAerialSingle;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= AERIAL_SIZE || p.y >= AERIAL_SIZE) return;
  vec3 d = screenRay((vec2(p) + 0.5) / float(AERIAL_SIZE));  // the cell's centre
  vec3 L = vec3(0.0), L1 = vec3(0.0), T = vec3(1.0);
  float t0 = 0.0;
  for (int k = 0; k < AERIAL_SLICES; ++k) {
    float t1 = aerialSliceDistance(k);
    vec3 x = uEyePlanet + t0 * d;
    float r = clamp(length(x), uAtmosphere.bottomRadius, uAtmosphere.topRadius);
    SkySegment s = integrateSkySegment(uAtmosphere, uTransmittance, uMultiple, r, dot(x, d) / length(x),
                                       dot(x, uSun) / length(x), dot(d, uSun), t1 - t0, 3, uMsWeight);
    L += T * s.radiance;
    L1 += T * s.single;
    T *= s.transmittance;
    imageStore(uAerialInScatter, ivec3(p, k), vec4(L, 1.0));
    imageStore(uAerialTransmittance, ivec3(p, k), vec4(T, 1.0));
    imageStore(uAerialSingle, ivec3(p, k), vec4(L1, 1.0));
    t0 = t1;
  }
}
