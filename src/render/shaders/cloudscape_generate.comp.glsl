// cloudscape_generate.comp.glsl — GPU particle generation (seed §5.2). Preceded by
// cloudscape_grid.glsl and particle_common.glsl, and by the defines of
// render/CloudscapeGeneration.cpp: STAGE (below), GROUP_SIZE (threads per work group, from which
// the C++ and stage 1 compute the dispatch sizes) and GRID_LAYER_LIMIT (the grid identity):
//   STAGE 0: one thread per grid cell (ring-major); non-empty cells within the far distance are
//            appended (atomic counter) to the cell list with their cloud (cgCellCloud: amount,
//            mass factor);
//   STAGE 1: one thread writes the indirect dispatch arguments for stage 2 from the counter;
//   STAGE 2: one thread per valid cell (glDispatchComputeIndirect): its particles (from the cloud
//            listed by stage 0, not sampled again) within the far distance, appended to the
//            particle buffer, whatever the frustum: the light-space passes (sun, zenith and
//            diffusion volumes, the seed's occlusion) take every one, so that the light of what
//            the camera sees does not change as particles leave the view (they cast shadows and
//            make up clouds all the same). Those in the frustum also get a back-to-front sort key,
//            appended at the front of the key buffer (visibleCount of them): the particle pass
//            draws those. The level-of-detail weight is folded into each particle's
//            density (cgParticle) and not stored. A record maps the unit sphere by
//            diag(radii) · Q (Q the particle's rotation of the reference particle).

layout(local_size_x = GROUP_SIZE) in;

uniform vec4 uG0;
uniform vec4 uG1;
uniform vec4 uG2;
uniform vec4 uG3;
uniform vec4 uG4;
uniform vec3 uEye;
uniform vec3 uSun;  // unit, toward the sun (the records' shadow-ray extinction scale)
uniform vec4 uPlanes[5];

struct GenerationCell {
  ivec4 id;    // (ix, iz, ring, layers)
  vec4 cloud;  // (amount, mass factor f, 0, 0): cgCellCloud
};

layout(std430, binding = 6) buffer Generation {
  uint cellCount;
  uint particleCount;
  uint particleCapacity;
  uint particleOverflow;
  uvec4 dispatchArgs;  // x, y, z groups for stage 2
  uint visibleCount;   // keys written: the particles in the frustum
  uint visiblePad0, visiblePad1, visiblePad2;
  GenerationCell cells[];
};

layout(std430, binding = 1) buffer SortKeys {
  uvec2 sortKeys[];  // (floatBitsToUint(distance), particle index)
};

void main() {
  uint id = gl_GlobalInvocationID.x;
#if STAGE == 0
  int dim = int(uG0.y);
  uint perRing = uint(dim * dim);
  if (id >= perRing * uint(uG0.z)) return;
  int ring = int(id / perRing);
  int rem = int(id % perRing);
  vec2 camXZ = vec2(uEye.x, uEye.z);
  ivec2 origin = cgRingOrigin(camXZ, ring, uG0);
  int ix = origin.x + rem % dim;
  int iz = origin.y + rem / dim;
  vec2 centre = cgCellCentre(ring, ix, iz, uG0);
  vec2 delta = abs(centre - camXZ);
  float w = cgRingWeight(ring, max(delta.x, delta.y), uG0, uG3);
  if (!(w > 0.0f)) return;
  vec4 b = cgCellBound(ring, ix, iz, uG0, uG1, uG2, uG3);
  if (!cgWithinFar(b.xyz, b.w, uEye, uG3.y)) return;  // a cell that may hold a particle in range
  vec2 cloud = cgCellCloud(ring, ix, iz, uG0, uG1, uG2, uG3, uG4);
  int layers = cgLayerCount(cloud.x, uG0, uG4);
  if (layers < 1) return;
  uint slot = atomicAdd(cellCount, 1u);
  cells[slot].id = ivec4(ix, iz, ring, layers);
  cells[slot].cloud = vec4(cloud, 0.0f, 0.0f);
#elif STAGE == 1
  if (id == 0u) dispatchArgs = uvec4((cellCount + uint(GROUP_SIZE) - 1u) / uint(GROUP_SIZE), 1u, 1u, 0u);
#else
  if (id >= cellCount) return;
  ivec4 cell = cells[id].id;
  vec2 cloud = cells[id].cloud.xy;  // (amount, mass factor)
  int ring = cell.z;
  vec2 camXZ = vec2(uEye.x, uEye.z);
  vec2 centre = cgCellCentre(ring, cell.x, cell.y, uG0);
  vec2 delta = abs(centre - camXZ);
  float w = cgRingWeight(ring, max(delta.x, delta.y), uG0, uG3);
  for (int k = 0; k < cell.w; ++k) {
    CgParticle p = cgParticle(ring, cell.x, cell.y, k, cloud.x, cloud.y, w, uG0, uG1, uG2, uG3, uG4);
    float reach = max(p.radii.x, p.radii.y);
    if (!cgWithinFar(p.centre, 0.0f, uEye, uG3.y)) continue;  // lit; keyed below if also in the frustum
    uint slot = atomicAdd(particleCount, 1u);
    if (slot >= particleCapacity) {
      atomicAdd(particleOverflow, 1u);
      continue;
    }
    // toWorld = diag(r) · Q (column k: r ⊙ Q column k); toParticle = Qᵀ · diag(1/r).
    mat3 q = cgRotationMatrix(p.noise);
    vec3 c0 = q[0] * p.radii;
    vec3 c1 = q[1] * p.radii;
    vec3 c2 = q[2] * p.radii;
    mat3 inv = transpose(q) * mat3(vec3(1.0f / p.radii.x, 0.0f, 0.0f), vec3(0.0f, 1.0f / p.radii.y, 0.0f),
                                   vec3(0.0f, 0.0f, 1.0f / p.radii.z));
    vec3 i0 = inv[0];
    vec3 i1 = inv[1];
    vec3 i2 = inv[2];
    GpuParticle g;
    g.centerDensity = vec4(p.centre, p.density);
    g.toParticle[0] = vec4(i0, length(mat3(i0, i1, i2) * uSun));
    g.toParticle[1] = vec4(i1, 1.0001f * max(p.radii.x, max(p.radii.y, p.radii.z)));
    g.toParticle[2] = vec4(i2, 1.0f);  // sunlight until the occlusion pass
    g.toWorld[0] = vec4(c0, float(ring * GRID_LAYER_LIMIT + k));
    g.toWorld[1] = vec4(c1, float(cell.x));
    g.toWorld[2] = vec4(c2, float(cell.y));
    particles[slot] = g;
    if (cgVisible(p.centre, reach, uEye, uG3.y, uPlanes[0], uPlanes[1], uPlanes[2], uPlanes[3], uPlanes[4]))
      sortKeys[atomicAdd(visibleCount, 1u)] = uvec2(floatBitsToUint(length(p.centre - uEye)), slot);
  }
#endif
}
