// particle_common.glsl — the per-particle record of every program that reads or writes particles
// (std430, seven vec4). The C++ side is render/GpuParticleRecord.h (GpuParticleRecord, checked
// against this layout when each program is linked), which documents every slot; in short:
//   toParticle[c].w: [0] |toParticle · l| (extinction scale toward the sun), [1] bounding-sphere
//                    radius (world units), [2] sunlight reaching the particle (occlusion.comp.glsl);
//   toWorld[c].w:    grid identity of a generated particle: [0] ring · GRID_LAYER_LIMIT + layer,
//                    [1] cell x, [2] cell z.
// The first four vec4 are all the ray marcher reads. Programs that only read particles define
// PARTICLES_ACCESS as readonly.

#ifndef PARTICLES_ACCESS
#define PARTICLES_ACCESS
#endif

struct GpuParticle {
  vec4 centerDensity;  // xyz: centre (world), w: density scale rho
  vec4 toParticle[3];  // columns of the inverse: p = toParticle * (x - centre)
  vec4 toWorld[3];     // columns of R * diag(radii): world offset = toWorld * p, p in the unit sphere
};

layout(std430, binding = 0) PARTICLES_ACCESS buffer Particles {
  GpuParticle particles[];
};

// The inverse map of particle p's ellipsoid (p = toParticle · (x − centre), the unit sphere).
mat3 particleToUnitSphere(GpuParticle p) { return mat3(p.toParticle[0].xyz, p.toParticle[1].xyz, p.toParticle[2].xyz); }
