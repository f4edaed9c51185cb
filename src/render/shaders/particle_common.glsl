// particle_common.glsl — the per-particle record shared by the particle shaders (std430).
// Written by Renderer.cpp (GpuParticle); keep the two in step.

struct GpuParticle {
  vec4 centerDensity;  // xyz: centre (world), w: density scale rho
  vec4 toWorld[3];     // columns of R * diag(radii): world offset = toWorld * p, p in the unit sphere
  vec4 toParticle[3];  // columns of the inverse: p = toParticle * (x - centre)
};

layout(std430, binding = 0) readonly buffer Particles {
  GpuParticle particles[];
};
