// cloudscape_grid.glsl — the camera-centred clipmap particle grid (seed §5.2), one definition for
// the GPU generator (cloudscape_generate.comp.glsl) and the CPU reference (scene/Cloudscape.cpp,
// compiled as C++ through GLM by scene/CloudscapeGrid.h). Same GLSL/C++ subset as
// lut_formats/glsl: float literals with `f`, no in/out, every function prefixed by CLOUDLUT_FN.
//
// Grid: `rings` square rings of `ringDim`² cells around the camera; ring r's cells are
// cellSize0 · 2^r wide. Ring r is centred on the camera snapped to multiples of 2 of its cells,
// so a ring moves in steps of two cells and every cell is a fixed square of the world. A cell is
// identified by (ring, ix, iz): it covers [ix, ix + 1] × [iz, iz + 1] · cellSize(ring) in x, z.
// Overlapping rings cross-fade: ring r fades out between a_r and b_r (Chebyshev distance of the
// cell centre from the camera, continuous camera position), ring r + 1 fades in over the same
// span, so a change of level of detail never pops.
//
// Parameters (packed in four vec4):
//   g0 = (cellSize0 [m], ringDim, rings, layers)
//   g1 = (coverage [0, 1], density scale, cloud base [m], cloud top [m])
//   g2 = (size min, size max (particle radius / cell size), vertical aspect, coverage noise scale [m])
//   g3 = (jitter (fraction of a cell), far distance [m], seed, fade fraction of a ring)

#ifndef CLOUDLUT_FN
#define CLOUDLUT_FN
#endif

// Radius of the reference particle of the tables (R = 183.8 m, core/Defaults.h
// kParticleRadiusMetres; tests/test_defaults.cpp checks they are equal): a particle of world
// radius r is given density ρ·r/R so that it is as thick as a reference particle of that size.
const float CG_REFERENCE_RADIUS = 183.8f;

struct CgParticle {
  vec3 centre;
  vec3 radii;    // x, z horizontal semi-axes, y vertical
  float yaw;     // rotation about +y, radians
  float density;
  float weight;  // level-of-detail fade weight in (0, 1]
};

// A 32-bit integer hash (good avalanche, exact on every platform).
CLOUDLUT_FN uint cgHash(uint x) {
  x = x ^ (x >> 16u);
  x = x * 0x7feb352du;
  x = x ^ (x >> 15u);
  x = x * 0x846ca68bu;
  x = x ^ (x >> 16u);
  return x;
}

CLOUDLUT_FN uint cgHash3(int x, int y, uint z) {
  return cgHash((uint(x) * 0x8da6b343u) ^ cgHash(uint(y) ^ cgHash(z)));
}

// [0, 1) from the top 24 bits: exact in float on both sides.
CLOUDLUT_FN float cgUnit(uint h) { return float(h >> 8u) * (1.0f / 16777216.0f); }

// Value noise in [0, 1] on the integer lattice, smoothly interpolated.
CLOUDLUT_FN float cgValueNoise(vec2 p, uint seed) {
  vec2 i = floor(p);
  vec2 f = p - i;
  int x = int(i.x);
  int y = int(i.y);
  vec2 u = f * f * (vec2(3.0f) - 2.0f * f);
  float a = cgUnit(cgHash3(x, y, seed));
  float b = cgUnit(cgHash3(x + 1, y, seed));
  float c = cgUnit(cgHash3(x, y + 1, seed));
  float d = cgUnit(cgHash3(x + 1, y + 1, seed));
  return mix(mix(a, b, u.x), mix(c, d, u.x), u.y);
}

// Four octaves, normalised to [0, 1], stretched about 0.5 so that the field spans the range.
CLOUDLUT_FN float cgFbm(vec2 p, uint seed) {
  float sum = 0.0f;
  float amplitude = 0.5f;
  float norm = 0.0f;
  for (int o = 0; o < 4; ++o) {
    sum += amplitude * cgValueNoise(p, seed + uint(o) * 0x68e31da4u);
    norm += amplitude;
    amplitude *= 0.5f;
    p = p * 2.03f + vec2(17.3f, -9.1f);
  }
  return clamp((sum / norm - 0.5f) * 2.2f + 0.5f, 0.0f, 1.0f);
}

// Cloud amount in [0, 1] at the world point (x, z): 0 = clear sky, 1 = the full column. About
// `coverage` of the sky has a positive amount.
CLOUDLUT_FN float cgCoverage(vec2 xz, vec4 g1, vec4 g2, vec4 g3) {
  float n = cgFbm(xz / g2.w, uint(g3.z));
  float threshold = 1.0f - g1.x;
  return clamp((n - threshold) / 0.3f, 0.0f, 1.0f);
}

CLOUDLUT_FN float cgCellSize(int ring, vec4 g0) { return g0.x * exp2(float(ring)); }

// Index of the first cell (lowest x, z) of ring `ring` for a camera at camXZ.
CLOUDLUT_FN ivec2 cgRingOrigin(vec2 camXZ, int ring, vec4 g0) {
  float s = cgCellSize(ring, g0);
  ivec2 centre = ivec2(floor(camXZ / (2.0f * s) + vec2(0.5f))) * 2;
  return centre - ivec2(int(g0.y) / 2);
}

// Fade-out span [a, b] of ring r (Chebyshev distance from the camera). Every cell whose centre is
// closer than b is present whatever the snapping (ring half-extent ≥ (ringDim/2 − 1) cells).
CLOUDLUT_FN vec2 cgFadeSpan(int ring, vec4 g0, vec4 g3) {
  float s = cgCellSize(ring, g0);
  float b = (0.5f * g0.y - 2.0f) * s;
  return vec2(b * (1.0f - g3.w), b);
}

// Level-of-detail weight of a cell of ring `ring` whose centre is at Chebyshev distance d.
CLOUDLUT_FN float cgRingWeight(int ring, float d, vec4 g0, vec4 g3) {
  float w = 1.0f;
  if (ring > 0) {
    vec2 inner = cgFadeSpan(ring - 1, g0, g3);
    w *= smoothstep(inner.x, inner.y, d);
  }
  if (ring < int(g0.z) - 1) {
    vec2 own = cgFadeSpan(ring, g0, g3);
    w *= 1.0f - smoothstep(own.x, own.y, d);
  }
  return w;
}

CLOUDLUT_FN vec2 cgCellCentre(int ring, int ix, int iz, vec4 g0) {
  return (vec2(float(ix), float(iz)) + vec2(0.5f)) * cgCellSize(ring, g0);
}

// Number of particle layers of a cell of cloud amount c (0 = an empty cell).
CLOUDLUT_FN int cgLayerCount(float c, vec4 g0) {
  return min(int(g0.w), int(c * g0.w + 0.5f));
}

// Largest horizontal and vertical radius a particle of ring `ring` can have.
CLOUDLUT_FN vec2 cgMaxRadii(int ring, vec4 g0, vec4 g1, vec4 g2) {
  float r = cgCellSize(ring, g0) * g2.y;
  float spacing = (g1.w - g1.z) / g0.w;
  return vec2(r, max(r * g2.z, 0.6f * spacing));
}

// A sphere that holds every particle a cell can emit (centre xyz, radius w).
CLOUDLUT_FN vec4 cgCellBound(int ring, int ix, int iz, vec4 g0, vec4 g1, vec4 g2, vec4 g3) {
  float s = cgCellSize(ring, g0);
  vec2 c = cgCellCentre(ring, ix, iz, g0);
  vec2 rr = cgMaxRadii(ring, g0, g1, g2);
  float halfWidth = 0.5f * s * (1.0f + g3.x) + rr.x;
  float halfHeight = 0.5f * (g1.w - g1.z) + rr.y;
  return vec4(c.x, 0.5f * (g1.z + g1.w), c.y, length(vec3(halfWidth, halfHeight, halfWidth)));
}

// True when the sphere (centre c, radius r) is not entirely outside one of the planes
// (dot(n, p) + w ≥ 0 inside) and its centre is within the far distance of the eye.
CLOUDLUT_FN bool cgVisible(vec3 c, float r, vec3 eye, float far, vec4 p0, vec4 p1, vec4 p2, vec4 p3,
                           vec4 p4) {
  if (length(c - eye) > far) return false;
  if (dot(vec3(p0), c) + p0.w < -r) return false;
  if (dot(vec3(p1), c) + p1.w < -r) return false;
  if (dot(vec3(p2), c) + p2.w < -r) return false;
  if (dot(vec3(p3), c) + p3.w < -r) return false;
  if (dot(vec3(p4), c) + p4.w < -r) return false;
  return true;
}

// Particle `layer` of cell (ring, ix, iz) of cloud amount c and weight w: position jittered and
// rotated by a hash of the cell's world coordinates (stable as the camera moves); higher layers
// are smaller (narrow tops, wide bases); density and size fade with w.
CLOUDLUT_FN CgParticle cgParticle(int ring, int ix, int iz, int layer, float c, float w, vec4 g0, vec4 g1,
                                  vec4 g2, vec4 g3) {
  uint h = cgHash3(ix, iz, uint(g3.z) ^ (uint(ring) * 0x9e3779b9u) ^ (uint(layer) * 0x85ebca6bu));
  float u0 = cgUnit(h);
  float u1 = cgUnit(cgHash(h ^ 0x1u));
  float u2 = cgUnit(cgHash(h ^ 0x2u));
  float u3 = cgUnit(cgHash(h ^ 0x3u));
  float u4 = cgUnit(cgHash(h ^ 0x4u));
  float s = cgCellSize(ring, g0);
  vec2 xz = cgCellCentre(ring, ix, iz, g0) + (vec2(u0, u1) - vec2(0.5f)) * (g3.x * s);
  float layers = g0.w;
  float spacing = (g1.w - g1.z) / layers;
  float y = g1.z + (float(layer) + 0.5f + 0.5f * (u2 - 0.5f)) * spacing;
  float taper = 1.0f - 0.45f * float(layer) / max(layers - 1.0f, 1.0f);
  float lod = 0.5f + 0.5f * w;
  float r = s * mix(g2.x, g2.y, u3) * taper * mix(0.6f, 1.0f, c) * lod;
  float rv = max(r * g2.z, 0.6f * spacing * taper * lod);
  float density = g1.y * mix(0.5f, 1.0f, c) * (r / CG_REFERENCE_RADIUS) * w;
  // member by member: C++ compilers without parenthesised aggregate initialisation accept it too
  CgParticle p;
  p.centre = vec3(xz.x, y, xz.y);
  p.radii = vec3(r, rv, r);
  p.yaw = u4 * 6.28318530718f;
  p.density = density;
  p.weight = w;
  return p;
}
