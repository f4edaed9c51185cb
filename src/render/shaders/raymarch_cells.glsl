// raymarch_cells.glsl — the particles a ray crosses, found through the particle cell grid
// (render/ParticleCellGrid.h): the ray's cells in order (Amanatides & Woo's traversal), each
// listed particle's ellipsoid interval tested, the particles kept sorted by entry. A particle is
// taken in the cell where its entry point lies (the first cell also takes entries before the
// grid, the last those beyond it), so one listed in several cells is taken once. Preceded by
// particle_common.glsl (the particle records: M⁻¹ is toParticle, toParticle[1].w the
// bounding-sphere radius). render/RayMarchRenderer.cpp #defines MAX_CELLS_PER_AXIS and the most
// particles kept on a view ray and on a shadow ray, MAX_HITS and MAX_SHADOW_HITS, and
// particleRecordDefines() (render/GpuParticleRecord.h) a record's texels, PARTICLE_RECORD_TEXELS.

// The records and the cell lists are read through buffer textures over their storage buffers
// (RayMarchRenderer binds them; why: render/GpuStorage.h, BufferTexels).
uniform samplerBuffer uParticleTexels;       // RGBA32F, a GpuParticle record every PARTICLE_RECORD_TEXELS
uniform usamplerBuffer uCellStartTexels;     // R32UI, cellStart[]
uniform usamplerBuffer uCellParticleTexels;  // R32UI, cellParticle[]

// Particle i's centerDensity (texel 0) and toParticle[k] (texel 1 + k).
vec4 particleCenterDensity(int i) { return texelFetch(uParticleTexels, PARTICLE_RECORD_TEXELS * i); }
vec4 particleToParticle(int i, int k) { return texelFetch(uParticleTexels, PARTICLE_RECORD_TEXELS * i + 1 + k); }

mat3 toParticle(int i) {
  return mat3(particleToParticle(i, 0).xyz, particleToParticle(i, 1).xyz, particleToParticle(i, 2).xyz);
}

// World interval [t0, t1] of the ray (o, d) inside particle i (false when it misses).
bool interval(int i, vec3 o, vec3 d, out float t0, out float t1) {
  vec3 c = particleCenterDensity(i).xyz;
  vec3 oc = o - c;
  float bound = particleToParticle(i, 1).w;
  float bb = dot(oc, d);
  if (dot(oc, oc) - bb * bb > bound * bound) { t0 = t1 = 0.0; return false; }
  mat3 m = toParticle(i);
  vec3 po = m * oc, pd = m * d;
  float a = dot(pd, pd), b = dot(po, pd), cc = dot(po, po) - 1.0;
  float disc = b * b - a * cc;
  if (disc <= 0.0) { t0 = t1 = 0.0; return false; }
  float s = sqrt(disc);
  t0 = max((-b - s) / a, 0.0);
  t1 = (-b + s) / a;
  return t1 > t0;
}

uniform vec3 uGridOrigin, uGridCell;
uniform ivec3 uGridDims;

// The last ray's particles (particlesOnRay), in globals so that no call copies arrays.
int hitIndex[MAX_HITS];
float hitT0[MAX_HITS], hitT1[MAX_HITS];

// The particles on the ray o + t·d (d unit), t ≥ 0, sorted by entry into hitIndex, hitT0 (entry)
// and hitT1 (exit); at most maxHits (≤ MAX_HITS), the nearest kept. Returns how many; `dropped`
// counts the ones left out.
int particlesOnRay(vec3 o, vec3 d, int maxHits, inout int dropped) {
  int hits = 0;
  // The ray's stretch inside the grid box [ta, tb]; a zero direction component never steps.
  vec3 safeD = mix(d, vec3(1e-30), equal(d, vec3(0.0)));
  vec3 inv = 1.0 / safeD;
  vec3 lo = uGridOrigin, hi = uGridOrigin + uGridCell * vec3(uGridDims);
  vec3 tLo = (lo - o) * inv, tHi = (hi - o) * inv;
  vec3 tNear = min(tLo, tHi), tFar = max(tLo, tHi);
  float ta = max(max(tNear.x, tNear.y), max(tNear.z, 0.0));
  float tb = min(min(tFar.x, tFar.y), tFar.z);
  if (!(ta < tb)) return 0;
  ivec3 cell = clamp(ivec3(floor((o + ta * d - lo) / uGridCell)), ivec3(0), uGridDims - 1);
  ivec3 stepCell = ivec3(sign(safeD));
  vec3 tDelta = abs(uGridCell * inv);
  vec3 tNext = (lo + (vec3(cell) + step(0.0, safeD)) * uGridCell - o) * inv;
  float tc0 = ta;
  for (int visit = 0; visit < 3 * MAX_CELLS_PER_AXIS + 3; ++visit) {
    // The next cell along the ray, and where this one ends.
    int axis = tNext.x <= tNext.y && tNext.x <= tNext.z ? 0 : (tNext.y <= tNext.z ? 1 : 2);
    float tc1 = min(tNext[axis], tb);
    ivec3 next = cell;
    next[axis] += stepCell[axis];
    bool last = tc1 >= tb || next[axis] < 0 || next[axis] >= uGridDims[axis];
    bool first = visit == 0;
    int c = (cell.z * uGridDims.y + cell.y) * uGridDims.x + cell.x;
    uint listEnd = texelFetch(uCellStartTexels, c + 1).x;
    for (uint k = texelFetch(uCellStartTexels, c).x; k < listEnd; ++k) {
      int i = int(texelFetch(uCellParticleTexels, int(k)).x);
      float t0, t1;
      if (!interval(i, o, d, t0, t1)) continue;
      if ((t0 < tc0 && !first) || (t0 >= tc1 && !last)) continue;  // its entry lies in another cell
      if (hits == maxHits && t0 >= hitT0[maxHits - 1]) { ++dropped; continue; }
      if (hits == maxHits) ++dropped; // the farthest kept makes room
      else ++hits;
      int j = hits - 1;
      while (j > 0 && hitT0[j - 1] > t0) {
        hitIndex[j] = hitIndex[j - 1]; hitT0[j] = hitT0[j - 1]; hitT1[j] = hitT1[j - 1]; --j;
      }
      hitIndex[j] = i; hitT0[j] = t0; hitT1[j] = t1;
    }
    if (last) break;
    cell = next;
    tNext[axis] += tDelta[axis];
    tc0 = tc1;
  }
  return hits;
}
