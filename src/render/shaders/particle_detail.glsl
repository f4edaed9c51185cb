// particle_detail.glsl — the detail noise of the particle pass (seed §5.4). Preceded by
// cloudlut_detail_noise.glsl (lut_formats/glsl, the definition the path tracer shares); used by
// particle.frag.glsl.

// The factor of the optical depth of the visible chord [tNear, tExit] (world distances along the
// unit direction dir from eye): the mean of the density factor 1 + a·n(x/s) along it
// (detailChordFactor), so that τ' = τ · factor; 1 exactly when the detail is off, and the
// program compiled without the detail (PARTICLE_DETAIL_NOISE 0) has none of its code.
#if PARTICLE_DETAIL_NOISE
uniform vec4 uDetailNoise;  // (amplitude, 1 / feature size [world units⁻¹], seed, 0)

float particleDetailFactor(vec3 eye, vec3 dir, float tNear, float tExit) {
  return detailChordFactor(eye + dir * tNear, eye + dir * tExit, uDetailNoise);
}
#else
float particleDetailFactor(vec3 eye, vec3 dir, float tNear, float tExit) { return 1.0; }
#endif
