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
// Parameters (packed in five vec4):
//   g0 = (cellSize0 [m], ringDim, rings, layers)
//   g1 = (coverage [0, 1], density scale, cloud base [m], cloud top [m])
//   g2 = (size min, size max (particle radius / cell size), vertical aspect, coverage noise scale [m])
//   g3 = (jitter (fraction of a cell), far distance [m], seed, fade fraction of a ring)
//   g4 = (reference radius R of the tables [m], height-profile exponent, top taper, edge density)
//
// Mass conservation (docs/SCENE_FORMAT.md, "Cloudscapes"): a particle of semi-axes (a, b, a) and density scale ρ
// adds ∫ τ dA = (4π/3) σ ρ a² to the area integral of the vertical column optical depth (σ the
// tables' unit optical radius, τ = σ ρ ℓ along a unit-sphere chord ℓ; independent of b). A ring
// keeps the same layers per cell and the same radius per cell size, so the column optical depth
// per unit area is the same in every ring when ρ does not depend on the ring: ρ is that of the
// ring-0 particle of the same relative size. A coarse cell stands for the (2^r)² ring-0 cells under
// it: it takes its amount and its column from the coverage averaged over its footprint
// (cgCellCloud), not from the coverage at its centre. The level-of-detail weights of two
// overlapping rings sum to 1 and multiply ρ only, so a cross-fade conserves it too.

#ifndef CLOUDLUT_FN
#define CLOUDLUT_FN
#endif

struct CgParticle {
  vec3 centre;
  vec3 radii;     // x, z horizontal semi-axes, y vertical (axis-aligned ellipsoid)
  vec4 noise;     // unit quaternion (x, y, z, w) turning the reference particle before scaling
  float density;  // ρ, the level-of-detail weight folded in
  float weight;   // level-of-detail fade weight in (0, 1]
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

// Height of the cloud column above the base, as a fraction of the layer (0, 1]: amount^p with
// the profile exponent p = g4.y (p < 1: flat-topped sheets, stratocumulus; p ≈ 1: domed heaps).
CLOUDLUT_FN float cgColumnHeight(float c, vec4 g4) { return pow(max(c, 1e-6f), g4.y); }

// Number of particle layers of a cell of cloud amount c (0 = an empty cell): the layers of the
// column's height, at least one when the cell has cloud.
CLOUDLUT_FN int cgLayerCount(float c, vec4 g0, vec4 g4) {
  if (!(c > 0.0f)) return 0;
  return clamp(int(ceil(cgColumnHeight(c, g4) * g0.w - 0.05f)), 1, int(g0.w));
}

// Largest horizontal and vertical radius a particle of ring `ring` can have [m]; particles stay
// inside the layer, so the vertical one is at most half the layer.
CLOUDLUT_FN vec2 cgMaxRadii(int ring, vec4 g0, vec4 g1, vec4 g2) {
  float r = cgCellSize(ring, g0) * g2.y;
  float spacing = (g1.w - g1.z) / g0.w;
  return vec2(r, min(max(r * g2.z, 0.6f * spacing), 0.5f * (g1.w - g1.z)));
}

// A sphere that holds every particle a cell can emit (centre xyz, radius w).
CLOUDLUT_FN vec4 cgCellBound(int ring, int ix, int iz, vec4 g0, vec4 g1, vec4 g2, vec4 g3) {
  float s = cgCellSize(ring, g0);
  vec2 c = cgCellCentre(ring, ix, iz, g0);
  vec2 rr = cgMaxRadii(ring, g0, g1, g2);
  float halfWidth = 0.5f * s * (1.0f + g3.x) + rr.x;
  float halfHeight = 0.5f * (g1.w - g1.z);
  return vec4(c.x, 0.5f * (g1.z + g1.w), c.y, length(vec3(halfWidth, halfHeight, halfWidth)));
}

// True when some point of the sphere (centre c, radius r, metres) may lie within the far
// distance of the eye, |c − eye| ≤ far + r: the cloudscape's range, the same for the particles
// the light-space passes read and for the cells that hold them.
CLOUDLUT_FN bool cgWithinFar(vec3 c, float r, vec3 eye, float far) { return length(c - eye) <= far + r; }

// True when the sphere (centre c, radius r) is not entirely outside one of the planes
// (dot(n, p) + w ≥ 0 inside) and its centre is within the far distance of the eye.
CLOUDLUT_FN bool cgVisible(vec3 c, float r, vec3 eye, float far, vec4 p0, vec4 p1, vec4 p2, vec4 p3,
                           vec4 p4) {
  if (!cgWithinFar(c, 0.0f, eye, far)) return false;
  if (dot(vec3(p0), c) + p0.w < -r) return false;
  if (dot(vec3(p1), c) + p1.w < -r) return false;
  if (dot(vec3(p2), c) + p2.w < -r) return false;
  if (dot(vec3(p3), c) + p3.w < -r) return false;
  if (dot(vec3(p4), c) + p4.w < -r) return false;
  return true;
}

// A uniformly distributed unit quaternion (x, y, z, w) from three numbers in [0, 1) (Shoemake's
// subgroup method: q = (√(1−u0) sin 2πu1, √(1−u0) cos 2πu1, √u0 sin 2πu2, √u0 cos 2πu2)).
CLOUDLUT_FN vec4 cgRandomRotation(float u0, float u1, float u2) {
  float a = sqrt(1.0f - u0);
  float b = sqrt(u0);
  float t1 = 6.28318530718f * u1;
  float t2 = 6.28318530718f * u2;
  return vec4(a * sin(t1), a * cos(t1), b * sin(t2), b * cos(t2));
}

// The rotation matrix of the unit quaternion q = (x, y, z, w) (columns).
CLOUDLUT_FN mat3 cgRotationMatrix(vec4 q) {
  float x = q.x;
  float y = q.y;
  float z = q.z;
  float w = q.w;
  return mat3(vec3(1.0f - 2.0f * (y * y + z * z), 2.0f * (x * y + w * z), 2.0f * (x * z - w * y)),
              vec3(2.0f * (x * y - w * z), 1.0f - 2.0f * (x * x + z * z), 2.0f * (y * z + w * x)),
              vec3(2.0f * (x * z + w * y), 2.0f * (y * z - w * x), 1.0f - 2.0f * (x * x + y * y)));
}

// Density of the cloud at amount c relative to its core [0, 1]: the edge density e = g4.w rising
// smoothly to 1 where the amount reaches 0.6, so a cloud's edge particles are thin and its core
// dense.
CLOUDLUT_FN float cgDensityRamp(float c, vec4 g4) { return mix(g4.w, 1.0f, smoothstep(0.0f, 0.6f, c)); }

// Relative size of a particle of a cell of amount c, as a factor of its random size: 0.7 at a
// cloud's edge to 1 in a full column (dimensionless).
CLOUDLUT_FN float cgAmountSize(float c) { return mix(0.7f, 1.0f, c); }

// Column weight of a cell of amount c: its expected vertical column optical depth per unit area up
// to a factor that is the same for every cell of every ring (density scale, σ, the cube of the
// mean random size): Σ over its layers of ramp(c) · (cgAmountSize(c) · taper)³, since a particle
// adds ∝ ρ a² with ρ ∝ ramp · a and a ∝ cgAmountSize · taper · size (cgParticle). 0 when c = 0.
CLOUDLUT_FN float cgColumnWeight(float c, vec4 g0, vec4 g4) {
  int count = cgLayerCount(c, g0, g4);
  float sum = 0.0f;
  for (int k = 0; k < count; ++k) {
    float taper = 1.0f - g4.z * float(k) / max(float(count) - 1.0f, 1.0f);
    sum += taper * taper * taper;
  }
  float m = cgAmountSize(c);
  return cgDensityRamp(c, g4) * m * m * m * sum;
}

// Coverage samples per side of a cell of ring `ring`: one per ring-0 cell under it (2^ring), at
// most 4 (ring 3 samples the centres of the ring-1 cells under it).
CLOUDLUT_FN int cgCoverageSamples(int ring) { return ring < 2 ? (1 << ring) : 4; }

// The cloud of cell (ring, ix, iz) as (amount c [0, 1], mass factor f): a ring-0 cell takes the
// coverage at its centre, f = 1. A coarser cell averages over an n × n grid of sub-cell centres
// (n = cgCoverageSamples): c = the mean amount (its column's shape), f = the mean column weight
// over the samples / the column weight at c, so that its column optical depth is the mean of the
// finer cells it stands for (the coverage is thresholded: the amount at one point, or the weight
// of the mean amount, does not carry their mean). f ≤ 1 / (ramp(c) · cgAmountSize(c)): no
// particle is denser than a full cloud's core particle of its size (cloudscapeDensityRange).
CLOUDLUT_FN vec2 cgCellCloud(int ring, int ix, int iz, vec4 g0, vec4 g1, vec4 g2, vec4 g3, vec4 g4) {
  vec2 centre = cgCellCentre(ring, ix, iz, g0);
  if (ring == 0) return vec2(cgCoverage(centre, g1, g2, g3), 1.0f);
  int n = cgCoverageSamples(ring);
  float s = cgCellSize(ring, g0);
  float amount = 0.0f;
  float weight = 0.0f;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      vec2 offset = (vec2(float(i), float(j)) + vec2(0.5f)) / float(n) - vec2(0.5f);
      float a = cgCoverage(centre + offset * s, g1, g2, g3);
      amount += a;
      weight += cgColumnWeight(a, g0, g4);
    }
  float samples = float(n * n);
  float c = amount / samples;
  if (!(c > 0.0f)) return vec2(0.0f, 0.0f);
  float f = (weight / samples) / cgColumnWeight(c, g0, g4);
  return vec2(c, min(f, 1.0f / (cgDensityRamp(c, g4) * cgAmountSize(c))));
}

// Particle `layer` of cell (ring, ix, iz) of cloud amount c, mass factor f (cgCellCloud) and
// level-of-detail weight w. Position, size and the reference particle's rotation come from a hash
// of the cell's world coordinates (stable as the camera moves). The bottom layer rests on the
// cloud base (flat bases); higher layers are smaller by the top taper g4.z (heaped, cauliflower
// tops); no particle leaves [base, top].
// Density: ρ = density scale · ramp(c) · f · r₀ / R · w, r₀ the radius the particle would have in
// ring 0 (the same relative size), R the tables' reference radius.
CLOUDLUT_FN CgParticle cgParticle(int ring, int ix, int iz, int layer, float c, float f, float w, vec4 g0,
                                  vec4 g1, vec4 g2, vec4 g3, vec4 g4) {
  uint h = cgHash3(ix, iz, uint(g3.z) ^ (uint(ring) * 0x9e3779b9u) ^ (uint(layer) * 0x85ebca6bu));
  float u0 = cgUnit(h);
  float u1 = cgUnit(cgHash(h ^ 0x1u));
  float u2 = cgUnit(cgHash(h ^ 0x2u));
  float u3 = cgUnit(cgHash(h ^ 0x3u));
  float s = cgCellSize(ring, g0);
  int count = cgLayerCount(c, g0, g4);
  float topness = float(layer) / max(float(count) - 1.0f, 1.0f);  // 0 bottom … 1 top of this column
  float taper = 1.0f - g4.z * topness;
  // Tops of tall columns draw in toward the cell centre (domes), bases spread.
  float spread = g3.x * mix(1.0f, 0.6f, topness);
  vec2 xz = cgCellCentre(ring, ix, iz, g0) + (vec2(u0, u1) - vec2(0.5f)) * (spread * s);
  float thickness = g1.w - g1.z;
  float spacing = thickness / g0.w;
  float rel = mix(g2.x, g2.y, u3) * taper * cgAmountSize(c);
  float r = s * rel;
  float want = max(r * g2.z, 0.6f * spacing * taper);
  float rv;
  float y;
  if (layer == 0) {
    rv = min(want, 0.5f * thickness);
    y = g1.z + rv;  // flat base
  } else {
    y = g1.z + (float(layer) + 0.5f + 0.4f * (u2 - 0.5f)) * spacing;
    rv = max(min(want, min(y - g1.z, g1.w - y)), 1e-3f * spacing);
  }
  CgParticle p;
  p.centre = vec3(xz.x, y, xz.y);
  p.radii = vec3(r, rv, r);
  p.noise = cgRandomRotation(cgUnit(cgHash(h ^ 0x5u)), cgUnit(cgHash(h ^ 0x6u)), cgUnit(cgHash(h ^ 0x7u)));
  p.density = g1.y * cgDensityRamp(c, g4) * f * (g0.x * rel / g4.x) * w;
  p.weight = w;
  return p;
}
