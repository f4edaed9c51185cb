// particle_varyings.glsl — what particle.vert.glsl hands the particle pass's fragment shaders
// (particle.frag.glsl, particle_count.frag.glsl). Preceded by particle_common.glsl.
//
// The particle's record travels as flat varyings, one value for all the fragments of a SIMD batch,
// not as an index to read the storage buffer at in the fragment shader, which llvmpipe does lane
// by lane (render/GpuStorage.h, BufferTexels; the read was about a seventh of cluster36's frame).

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
