#pragma once
// Default physical and table parameters: the seed paper's (§5.1) and its public code's.
#include <array>

namespace cloudlut::defaults {

inline constexpr double kExtinctionPerMetre = 0.07;  // β, m⁻¹
inline constexpr double kParticleRadiusMetres = 183.8;  // R, m (ring-0 cell of the public code)
inline constexpr int kDensitySlopeMin = -4;  // ρ = 2^s, s = -4 ... 3
inline constexpr int kDensitySlopeMax = 3;
inline constexpr std::array<int, 4> kOpticalDepthDims = {64, 32, 64, 32};  // φS, θS, φv, θv
inline constexpr std::array<int, 4> kScatteringDims = {32, 64, 16, 8};  // θS, φv, θv, ρ
inline constexpr int kScatteringOrders = 18;
inline constexpr float kFirstScatteringG = 0.9f;  // Cornette–Shanks g for sunlight's first bounce
inline constexpr float kMultipleScatteringG = 0.7f;  // ... and for every later one
// Density (normalised to [0, 1]) above which the optical-depth table counts "matter" for
// its distance-to-first-matter channel.
inline constexpr float kFirstMatterThreshold = 0.1f;

}  // namespace cloudlut::defaults
