#include "core/Noise.h"

#include <cmath>
#include <numeric>

namespace cloudlut {

std::uint64_t splitMix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

GradientNoise::GradientNoise(std::uint64_t seed) {
  std::array<std::uint8_t, 256> p{};
  std::iota(p.begin(), p.end(), std::uint8_t{0});
  std::uint64_t state = seed;
  for (int i = 255; i > 0; --i) {  // Fisher–Yates with a portable generator
    const int j = static_cast<int>(splitMix64(state) % static_cast<std::uint64_t>(i + 1));
    std::swap(p[i], p[j]);
  }
  for (int i = 0; i < 512; ++i) perm_[i] = p[i & 255];
}

namespace {
inline float fade(float t) { return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f); }
inline float lerp(float a, float b, float t) { return a + t * (b - a); }
inline float grad(int hash, float x, float y, float z) {
  const int h = hash & 15;  // the 12 cube-edge directions (and 4 repeats)
  const float u = h < 8 ? x : y;
  const float v = h < 4 ? y : (h == 12 || h == 14 ? x : z);
  return ((h & 1) ? -u : u) + ((h & 2) ? -v : v);
}
}  // namespace

float GradientNoise::noise(const glm::vec3& p) const {
  const float fx = std::floor(p.x), fy = std::floor(p.y), fz = std::floor(p.z);
  const int X = static_cast<int>(fx) & 255, Y = static_cast<int>(fy) & 255,
            Z = static_cast<int>(fz) & 255;
  const float x = p.x - fx, y = p.y - fy, z = p.z - fz;
  const float u = fade(x), v = fade(y), w = fade(z);
  const int A = perm_[X] + Y, AA = perm_[A] + Z, AB = perm_[A + 1] + Z;
  const int B = perm_[X + 1] + Y, BA = perm_[B] + Z, BB = perm_[B + 1] + Z;
  return lerp(lerp(lerp(grad(perm_[AA], x, y, z), grad(perm_[BA], x - 1, y, z), u),
                   lerp(grad(perm_[AB], x, y - 1, z), grad(perm_[BB], x - 1, y - 1, z), u), v),
              lerp(lerp(grad(perm_[AA + 1], x, y, z - 1), grad(perm_[BA + 1], x - 1, y, z - 1), u),
                   lerp(grad(perm_[AB + 1], x, y - 1, z - 1),
                        grad(perm_[BB + 1], x - 1, y - 1, z - 1), u),
                   v),
              w);
}

float GradientNoise::fbm(const glm::vec3& p, int octaves) const {
  float sum = 0.0f, amplitude = 1.0f, norm = 0.0f;
  glm::vec3 q = p;
  for (int o = 0; o < octaves; ++o) {
    sum += amplitude * noise(q);
    norm += amplitude;
    amplitude *= 0.5f;
    q = q * 2.0f + glm::vec3(17.13f, 31.7f, 5.31f);  // shift octaves off each other's lattice
  }
  return norm > 0.0f ? sum / norm : 0.0f;
}

}  // namespace cloudlut
