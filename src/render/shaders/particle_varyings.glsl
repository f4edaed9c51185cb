// particle_varyings.glsl — what particle.vert.glsl hands the particle pass's fragment shaders
// (particle.frag.glsl, particle_count.frag.glsl). Preceded by particle_common.glsl.
//
// The particle's record travels as flat varyings, not as an index to read in the fragment shader:
// llvmpipe reads a storage buffer at a per-fragment index in a bounds-checked scalar loop over
// its SIMD lanes, while a flat varying is one value broadcast to them (the record's read was
// about a seventh of cluster36's frame, docs/BENCHMARKS.md).

in vec3 vWorld;                // the proxy's point (world)
flat in int vParticle;         // the particle's index in the particle buffer
flat in vec4 vCenterDensity;   // its GpuParticle::centerDensity
flat in vec4 vToParticle[3];   // its GpuParticle::toParticle

// The fragment's particle (toWorld, which no fragment shader uses, left zero).
GpuParticle fragmentParticle() {
  GpuParticle p;
  p.centerDensity = vCenterDensity;
  p.toParticle = vToParticle;
  p.toWorld = vec4[3](vec4(0.0), vec4(0.0), vec4(0.0));
  return p;
}
