// cloudlut_detail_noise.glsl — the detail noise of the cloud's density (seed §5.4: "3D noise is
// used to add small details"), one definition for the particle renderer
// (render/shaders/particle_detail.glsl) and the path tracer (reference/ScenePathTracer, through
// src/core/DetailNoise.h). Same GLSL/C++ subset as cloudlut_geometry.glsl, plus `uint`.
//
// The model: the density of the whole medium (every particle, overlapping ones summed) is
// multiplied, at every world point x, by the factor
//     m(x) = 1 + a · n(x / s)
// with a ∈ [0, 1] the amplitude, s the feature size (world units) and n ∈ [−1, 1] a fractal sum of
// gradient noise whose gradients are drawn symmetrically about 0, so that E[n] = 0 at every point
// and E[m] = 1: the mean density, and with it the mean optical depth of any chord, is unchanged.
// The renderer multiplies a chord's optical depth by the mean of m along it (detailChordFactor);
// the path tracer multiplies the extinction by m at each point. The packed parameters
// d = (a, 1/s, seed, 0); a = 0 switches the detail off (m = 1 exactly).

#ifndef CLOUDLUT_FN
#define CLOUDLUT_FN
#endif

// A 32-bit integer hash (a permuted congruential step; exact on every platform).
CLOUDLUT_FN uint detailHash(uint x) {
  uint s = x * 747796405u + 2891336453u;
  uint w = ((s >> ((s >> 28u) + 4u)) ^ s) * 277803737u;
  return (w >> 22u) ^ w;
}

// Gradient-noise contribution of the lattice corner c (integer-valued floats) at the offset f
// from it: dot(g, f), g's components drawn from 1024 levels symmetric about 0 (g and −g equally
// likely, so the contribution has mean 0).
CLOUDLUT_FN float detailCorner(vec3 c, vec3 f, uint seed) {
  uint h = detailHash(uint(int(c.x)) ^ detailHash(uint(int(c.y)) ^ detailHash(uint(int(c.z)) ^ seed)));
  vec3 g = vec3(float(h & 1023u), float((h >> 10u) & 1023u), float((h >> 20u) & 1023u)) * (2.0f / 1023.0f) -
           vec3(1.0f);
  return dot(g, f);
}

// Gradient noise at p (lattice units), quintic interpolation of the eight corners; 0 at the
// lattice points, mean 0.
CLOUDLUT_FN float detailGradientNoise(vec3 p, uint seed) {
  vec3 i = floor(p);
  vec3 f = p - i;
  vec3 u = f * f * f * (f * (f * 6.0f - vec3(15.0f)) + vec3(10.0f));
  float n000 = detailCorner(i, f, seed);
  float n100 = detailCorner(i + vec3(1.0f, 0.0f, 0.0f), f - vec3(1.0f, 0.0f, 0.0f), seed);
  float n010 = detailCorner(i + vec3(0.0f, 1.0f, 0.0f), f - vec3(0.0f, 1.0f, 0.0f), seed);
  float n110 = detailCorner(i + vec3(1.0f, 1.0f, 0.0f), f - vec3(1.0f, 1.0f, 0.0f), seed);
  float n001 = detailCorner(i + vec3(0.0f, 0.0f, 1.0f), f - vec3(0.0f, 0.0f, 1.0f), seed);
  float n101 = detailCorner(i + vec3(1.0f, 0.0f, 1.0f), f - vec3(1.0f, 0.0f, 1.0f), seed);
  float n011 = detailCorner(i + vec3(0.0f, 1.0f, 1.0f), f - vec3(0.0f, 1.0f, 1.0f), seed);
  float n111 = detailCorner(i + vec3(1.0f), f - vec3(1.0f), seed);
  return mix(mix(mix(n000, n100, u.x), mix(n010, n110, u.x), u.y),
             mix(mix(n001, n101, u.x), mix(n011, n111, u.x), u.y), u.z);
}

// Octaves of the detail noise, and the gain that brings their normalised sum to a standard
// deviation of about 0.4 (measured over 10⁵ points, tests/test_detail_noise.cpp), so that the
// clamp to [−1, 1] (symmetric: the mean stays 0) touches about 1% of the points.
const int CLOUDLUT_DETAIL_OCTAVES = 3;
const float CLOUDLUT_DETAIL_GAIN = 3.2f;

// The first `octaves` octaves of n (wavelengths 1, 1/2, 1/4 lattice units, amplitudes 1, 1/2,
// 1/4), the others taken at their mean 0, normalised by the sum of all the amplitudes (1.75),
// times the gain, clamped to [−1, 1].
CLOUDLUT_FN float detailNoiseOctaves(vec3 p, uint seed, int octaves) {
  float sum = 0.0f;
  float amplitude = 1.0f;
  for (int o = 0; o < octaves; ++o) {
    sum += amplitude * detailGradientNoise(p, detailHash(seed + uint(o)));
    amplitude *= 0.5f;
    p = p * 2.0f + vec3(19.19f, 7.31f, 13.7f);  // each octave off the lattice of the one before
  }
  return clamp(CLOUDLUT_DETAIL_GAIN * sum / 1.75f, -1.0f, 1.0f);
}

// n(p) ∈ [−1, 1]: all three octaves.
CLOUDLUT_FN float detailNoise(vec3 p, uint seed) { return detailNoiseOctaves(p, seed, CLOUDLUT_DETAIL_OCTAVES); }

// m(x) = 1 + a · n(x / s): the density factor at the world point x (dimensionless, in [1 − a, 1 + a]).
CLOUDLUT_FN float detailDensityFactor(vec3 x, vec4 d) {
  return 1.0f + d.x * detailNoise(x * d.y, uint(d.z));
}

// The mean of m along the world segment [a, b] of length L (the factor of a chord's optical depth,
// τ' = τ · mean(m); exact under a density uniform along the chord): the midpoint rule at
// k = clamp(⌈L/s⌉, 1, 4) points, over the octaves whose wavelength s/2^o is at least the spacing
// L/k; the finer ones, sampled less than once per wavelength, are taken at their chord mean's
// expectation, 0 (a smaller error than their value at a few points). 1 exactly when off (d.x = 0).
CLOUDLUT_FN float detailChordFactor(vec3 a, vec3 b, vec4 d) {
  if (!(d.x > 0.0f)) return 1.0f;
  float len = length(b - a) * d.y;  // L / s
  float k = clamp(ceil(len), 1.0f, 4.0f);
  int octaves = clamp(int(floor(log2(k / max(len, 1e-6f)))) + 1, 1, CLOUDLUT_DETAIL_OCTAVES);
  float sum = 0.0f;
  for (float i = 0.5f; i < k; i += 1.0f) sum += detailNoiseOctaves(mix(a, b, i / k) * d.y, uint(d.z), octaves);
  return 1.0f + d.x * sum / k;
}
