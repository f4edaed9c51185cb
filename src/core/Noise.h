#pragma once
// Seeded 3D gradient noise (Perlin's improved noise) and its fractal sum (fBm).
// Deterministic for a given seed on every platform: the permutation comes from a
// self-contained integer hash, not from the standard library's distributions.
#include <array>
#include <cstdint>

#include <glm/vec3.hpp>

namespace cloudlut {

class GradientNoise {
 public:
  explicit GradientNoise(std::uint64_t seed);

  // Gradient noise at p, in about [-1, 1]; zero at integer lattice points.
  float noise(const glm::vec3& p) const;

  // Fractal sum of `octaves` octaves (frequency ×2, amplitude ×1/2 per octave), divided by
  // the sum of amplitudes so that it stays in about [-1, 1].
  float fbm(const glm::vec3& p, int octaves) const;

 private:
  std::array<std::uint8_t, 512> perm_{};
};

// SplitMix64: a small, well-mixed integer hash used for seeding.
std::uint64_t splitMix64(std::uint64_t& state);

}  // namespace cloudlut
