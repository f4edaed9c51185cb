// occlusion.comp.glsl — light-space occlusion (seed §5.3). Preceded by particle_common.glsl and
// the defines of render/LightOcclusion.cpp, which sizes the buffers and dispatches the stages:
// GROUP_SIZE (threads per work group) and STAGE; the grid's tiles per side are uTiles (T, from
// the particle count, render/LightOcclusion.h). The tiles are binned by counting, a prefix sum
// and a scatter (no linked lists), and the particles are then processed in the order of the tile
// holding their centre, each tile's particles and its occluders contiguous in memory:
//   STAGE 0  (per particle): bounds of the particles seen from the sun (atomic min/max in light
//            space u, v);
//   STAGE 1  (per particle): counts: the tile holding the centre, and every tile the particle,
//            extended by half a tile (conservative), covers;
//   STAGE 2  (per row of each count grid): exclusive prefix sum along the row, the row's total;
//   STAGE 3  (one thread): exclusive prefix sum of the row totals, the grand totals;
//   STAGE 4  (per tile of each grid): start = row offset + start within the row;
//   STAGE 5  (per particle): each index into the centre bins (order[]);
//   STAGE 6  (per tile): sorts its centre bin by centre position (the binned order, and every sum
//            below, then does not depend on the order of the particle list);
//   STAGE 7  (per binned position k): copies particle order[k] into occluders[k] (contiguous per
//            tile) and pushes k into the cover bin of every tile it covers;
//   STAGE 8  (per tile): sorts its cover bin by k (a deterministic order of the sums below);
//   STAGE 9  (per k): the ray from the centre toward the sun against every other particle of the
//            cover bin of the tile holding the centre: optical depth of each chord (homogeneous
//            ellipsoid, ρ·σ per unit-sphere length) scaled by ξ: sunlight = exp(−ξ Σ τ);
//   STAGE 10 (per k): density-weighted smoothing of the sunlight over the particles of the same
//            cover bin within twice the particle's reach (light diffusing through the cloud body),
//            written into the particle's record.

layout(local_size_x = GROUP_SIZE) in;

uniform int uTiles;     // tiles per side of the light-space grid
#define TILES uTiles
uniform uint uCount;
uniform vec3 uSun;      // toward the sun
uniform vec3 uLightU;   // light-space axes, perpendicular to uSun
uniform vec3 uLightV;
uniform float uSigma;   // optical radius of a unit-density particle (beta * R)
uniform float uXi;      // extinction scale for occlusion (seed: 0.05)
uniform int uSmooth;
uniform uint uCoverCapacity;  // entries the cover bins hold (more are dropped and counted)

// Words after the header: centre counts [0, T²), cover counts [T², 2T²), centre starts
// [2T², 3T²), cover starts [3T², 4T²) (after the scatters: the bins' ends), row totals
// [4T², 4T² + 2T) (centre rows, then cover rows; after stage 3 the rows' offsets).
layout(std430, binding = 3) buffer Tiles {
  ivec4 bounds;         // ordered-int min u, min v, max u, max v
  uint coverTotal;      // entries of all cover bins (stage 3)
  uint centreTotal;     // = the particle count
  uint coverOverflow;   // cover entries dropped for want of room
  uint pad;
  uint words[];
};

layout(std430, binding = 4) buffer RawSunlight {
  float rawSunlight[];  // per binned position k
};

layout(std430, binding = 5) buffer Order {
  uint order[];         // binned position k → particle index
};

struct Occluder {
  vec4 centerDensity;   // as the record
  vec4 toParticle[3];   // columns as the record; [0].w the particle's reach (world units)
};
layout(std430, binding = 6) buffer Occluders {
  Occluder occluders[];
};

layout(std430, binding = 7) buffer CoverBins {
  uint cover[];         // binned positions k of the particles covering each tile, bin after bin
};

uint tileWords() { return uint(TILES * TILES); }
uint countIndex(int which, uint tile) { return uint(which) * tileWords() + tile; }
uint startIndex(int which, uint tile) { return (2u + uint(which)) * tileWords() + tile; }
uint rowTotalIndex(int which, int row) { return 4u * tileWords() + uint(which * TILES + row); }

int orderedInt(float f) {
  int i = floatBitsToInt(f);
  return i >= 0 ? i : i ^ 0x7fffffff;
}
float orderedFloat(int i) { return intBitsToFloat(i >= 0 ? i : i ^ 0x7fffffff); }

float reach(GpuParticle p) {
  return max(length(p.toWorld[0].xyz), max(length(p.toWorld[1].xyz), length(p.toWorld[2].xyz)));
}

vec4 tileFrame() {  // (min u, min v, tile width u, tile width v)
  vec2 lo = vec2(orderedFloat(bounds.x), orderedFloat(bounds.y));
  vec2 hi = vec2(orderedFloat(bounds.z), orderedFloat(bounds.w));
  vec2 size = max((hi - lo) / float(TILES), vec2(1e-6f * max(max(abs(lo.x), abs(hi.x)), 1.0f)));
  return vec4(lo, size);
}

ivec2 tileOf(vec2 uv, vec4 frame) {
  return clamp(ivec2(floor((uv - frame.xy) / frame.zw)), ivec2(0), ivec2(TILES - 1));
}

vec2 lightUv(vec3 c) { return vec2(dot(c, uLightU), dot(c, uLightV)); }

uint tileIndexOf(vec3 centre) {
  ivec2 t = tileOf(lightUv(centre), tileFrame());
  return uint(t.y * TILES + t.x);
}

// The tiles a particle at `centre` of reach r is listed in: [lo, hi] (inclusive).
void coveredTiles(vec3 centre, float r, out ivec2 lo, out ivec2 hi) {
  vec4 frame = tileFrame();
  vec2 uv = lightUv(centre);
  lo = tileOf(uv - vec2(r) - 0.5f * frame.zw, frame);
  hi = tileOf(uv + vec2(r) + 0.5f * frame.zw, frame);
}

// The bin [first, end) of `tile` in grid `which` after its scatter (starts then hold the ends).
uvec2 binOf(int which, uint tile) {
  uint end = words[startIndex(which, tile)];
  return uvec2(end - words[countIndex(which, tile)], end);
}

// The order of a bin's values: centre bins (which 0) by the particle's centre (x, then y, then z;
// the particle index breaks exact ties), so that the binned order and every sum over it do not
// depend on the order of the particle list; cover bins (which 1) by binned position.
bool before(int which, uint x, uint y) {
  if (which == 0) {
    vec3 a = particles[x].centerDensity.xyz, b = particles[y].centerDensity.xyz;
    if (a.x != b.x) return a.x < b.x;
    if (a.y != b.y) return a.y < b.y;
    if (a.z != b.z) return a.z < b.z;
  }
  return x < y;
}

// Heap sort of order[first, end) (which 0) or cover[first, end) (which 1) by before():
// O(n log n) however many particles share a tile.
uint binValue(int which, uint i) { return which == 0 ? order[i] : cover[i]; }
void setBinValue(int which, uint i, uint v) {
  if (which == 0)
    order[i] = v;
  else
    cover[i] = v;
}
void siftDown(int which, uint first, uint root, uint n) {
  uint v = binValue(which, first + root);
  for (;;) {
    uint child = 2u * root + 1u;
    if (child >= n) break;
    if (child + 1u < n && before(which, binValue(which, first + child), binValue(which, first + child + 1u))) ++child;
    uint c = binValue(which, first + child);
    if (!before(which, v, c)) break;
    setBinValue(which, first + root, c);
    root = child;
  }
  setBinValue(which, first + root, v);
}
void sortBin(int which, uint first, uint end) {
  uint n = end - first;
  if (n < 2u) return;
  for (uint r = n / 2u; r-- > 0u;) siftDown(which, first, r, n);
  for (uint last = n - 1u; last > 0u; --last) {
    uint top = binValue(which, first);
    setBinValue(which, first, binValue(which, first + last));
    setBinValue(which, first + last, top);
    siftDown(which, first, 0u, last);
  }
}

void main() {
  uint id = gl_GlobalInvocationID.x;
#if STAGE == 0
  if (id >= uCount) return;
  GpuParticle p = particles[id];
  vec2 uv = lightUv(p.centerDensity.xyz);
  float r = reach(p);
  atomicMin(bounds.x, orderedInt(uv.x - r));
  atomicMin(bounds.y, orderedInt(uv.y - r));
  atomicMax(bounds.z, orderedInt(uv.x + r));
  atomicMax(bounds.w, orderedInt(uv.y + r));
#elif STAGE == 1
  if (id >= uCount) return;
  GpuParticle p = particles[id];
  atomicAdd(words[countIndex(0, tileIndexOf(p.centerDensity.xyz))], 1u);
  ivec2 lo, hi;
  coveredTiles(p.centerDensity.xyz, reach(p), lo, hi);
  for (int y = lo.y; y <= hi.y; ++y)
    for (int x = lo.x; x <= hi.x; ++x) atomicAdd(words[countIndex(1, uint(y * TILES + x))], 1u);
#elif STAGE == 2
  if (id >= uint(2 * TILES)) return;
  int which = int(id) / TILES, row = int(id) % TILES;
  uint running = 0u;
  for (int x = 0; x < TILES; ++x) {
    uint tile = uint(row * TILES + x);
    words[startIndex(which, tile)] = running;
    running += words[countIndex(which, tile)];
  }
  words[rowTotalIndex(which, row)] = running;
#elif STAGE == 3
  if (id != 0u) return;
  for (int which = 0; which < 2; ++which) {
    uint running = 0u;
    for (int row = 0; row < TILES; ++row) {
      uint total = words[rowTotalIndex(which, row)];
      words[rowTotalIndex(which, row)] = running;
      running += total;
    }
    if (which == 0)
      centreTotal = running;
    else
      coverTotal = running;
  }
#elif STAGE == 4
  if (id >= 2u * tileWords()) return;
  int which = int(id / tileWords());
  uint tile = id % tileWords();
  words[startIndex(which, tile)] += words[rowTotalIndex(which, int(tile) / TILES)];
#elif STAGE == 5
  if (id >= uCount) return;
  uint slot = atomicAdd(words[startIndex(0, tileIndexOf(particles[id].centerDensity.xyz))], 1u);
  order[slot] = id;
#elif STAGE == 6 || STAGE == 8
  if (id >= tileWords()) return;
  const int which = STAGE == 6 ? 0 : 1;
  uvec2 bin = binOf(which, id);
  if (which == 1) bin = min(bin, uvec2(uCoverCapacity));
  sortBin(which, bin.x, bin.y);
#elif STAGE == 7
  if (id >= uCount) return;
  GpuParticle p = particles[order[id]];
  float r = reach(p);
  Occluder o;
  o.centerDensity = p.centerDensity;
  o.toParticle[0] = vec4(p.toParticle[0].xyz, r);
  o.toParticle[1] = vec4(p.toParticle[1].xyz, 0.0f);
  o.toParticle[2] = vec4(p.toParticle[2].xyz, 0.0f);
  occluders[id] = o;
  ivec2 lo, hi;
  coveredTiles(p.centerDensity.xyz, r, lo, hi);
  for (int y = lo.y; y <= hi.y; ++y)
    for (int x = lo.x; x <= hi.x; ++x) {
      uint slot = atomicAdd(words[startIndex(1, uint(y * TILES + x))], 1u);
      if (slot < uCoverCapacity)
        cover[slot] = id;
      else
        atomicAdd(coverOverflow, 1u);
    }
#elif STAGE == 9
  if (id >= uCount) return;
  vec3 c = occluders[id].centerDensity.xyz;
  uvec2 bin = min(binOf(1, tileIndexOf(c)), uvec2(uCoverCapacity));
  float tau = 0.0f;
  for (uint e = bin.x; e < bin.y; ++e) {
    uint j = cover[e];
    if (j == id) continue;
    Occluder q = occluders[j];
    mat3 toParticle = mat3(q.toParticle[0].xyz, q.toParticle[1].xyz, q.toParticle[2].xyz);
    vec3 o = toParticle * (c - q.centerDensity.xyz);
    vec3 d = toParticle * uSun;
    float a = dot(d, d);
    float b = dot(o, d);
    float cc = dot(o, o) - 1.0f;
    float disc = b * b - a * cc;
    if (disc <= 0.0f) continue;
    float s = sqrt(disc);
    float t0 = max((-b - s) / a, 0.0f);
    float t1 = (-b + s) / a;
    if (t1 <= t0) continue;
    tau += q.centerDensity.w * uSigma * (t1 - t0) * sqrt(a);
  }
  rawSunlight[id] = exp(-uXi * tau);
#else
  if (id >= uCount) return;
  float own = rawSunlight[id];
  float result = own;
  if (uSmooth != 0) {
    Occluder self = occluders[id];
    vec3 c = self.centerDensity.xyz;
    float radius = 2.0f * self.toParticle[0].w;
    float wsum = self.centerDensity.w;
    float sum = wsum * own;
    uvec2 bin = min(binOf(1, tileIndexOf(c)), uvec2(uCoverCapacity));
    for (uint e = bin.x; e < bin.y; ++e) {
      uint j = cover[e];
      if (j == id) continue;
      vec4 q = occluders[j].centerDensity;
      float dist = length(q.xyz - c);
      if (dist >= radius) continue;
      float w = q.w * (1.0f - dist / radius);
      sum += w * rawSunlight[j];
      wsum += w;
    }
    result = wsum > 0.0f ? sum / wsum : own;
  }
  particles[order[id]].toParticle[2].w = result;
#endif
}
