// particle_common.glsl — the per-particle record shared by the particle shaders (std430).
// Written by Renderer.cpp (GpuParticle) and cloudscape_generate.comp.glsl; keep them in step.

struct GpuParticle {
  vec4 centerDensity;  // xyz: centre (world), w: density scale rho
  vec4 toWorld[3];     // columns of R * diag(radii): world offset = toWorld * p, p in the unit sphere
                       // w: [0] sunlight reaching the particle (occlusion.comp.glsl), [1] level-of-detail
                       // weight of a generated particle (1 otherwise), [2] unused
  vec4 toParticle[3];  // columns of the inverse: p = toParticle * (x - centre)
                       // w: generated particles' identity: ring * 16 + layer, cell x, cell z
};

layout(std430, binding = 0) buffer Particles {
  GpuParticle particles[];
};
