#pragma once
// Default physical and table parameters, written once: the seed paper's (§5.1) and its public
// code's. Every default of the bakers, the references, the renderers and the command line's
// options comes from here; GLSL constants that must equal one of them are checked by a test
// (tests/test_defaults.cpp).
#include <array>

#include "core/Phase.h"

namespace cloudlut::defaults {

inline constexpr double kExtinctionPerMetre = 0.07;  // β, m⁻¹
inline constexpr double kParticleRadiusMetres = 183.8;  // R, m (ring-0 cell of the public code)
// The cloudscape grid's ring-0 cell, m: the public code's, whose size R is.
inline constexpr double kCloudscapeCellMetres = kParticleRadiusMetres;
// σ of a particle of density scale ρ = 1 in unit-sphere units: β·R (dimensionless).
inline constexpr double kUnitOpticalRadius = kExtinctionPerMetre * kParticleRadiusMetres;
inline constexpr int kDensitySlopeMin = -4;  // ρ = 2^s, s = -4 ... 3
inline constexpr int kDensitySlopeMax = 3;
inline constexpr std::array<int, 4> kOpticalDepthDims = {64, 32, 64, 32};  // φS, θS, φv, θv
// Scattering tables (θS, φv, θv, ρ): φv folded onto [0, π] by the sphere's mirror symmetry
// (33 nodes, 5.6° apart, the spacing of the seed's 64 over [0, 2π]) and two density slices per
// octave (15 over s = −4 … 3): 32·33·16·15 fp16 = 495 KiB, within the seed's 32·64·16·8 (512 KiB).
inline constexpr int kDensitySlicesPerOctave = 2;
inline constexpr std::array<int, 4> kScatteringDims = {
    32, 33, 16, (kDensitySlopeMax - kDensitySlopeMin) * kDensitySlicesPerOctave + 1};
inline constexpr int kScatteringOrders = 18;
inline constexpr float kFirstScatteringG = 0.9f;  // Cornette–Shanks g for sunlight's first bounce
inline constexpr float kMultipleScatteringG = 0.7f;  // ... and for every later one
inline constexpr Phase kFirstPhase{PhaseKind::CornetteShanks, kFirstScatteringG};
inline constexpr Phase kLaterPhase{PhaseKind::CornetteShanks, kMultipleScatteringG};
// Droplet diameter of the Jendersie–d'Eon phase when none is given, µm (its fit covers 5 … 50).
inline constexpr float kDropletDiameterUm = 10.0f;
inline constexpr float kDropletDiameterMinUm = 5.0f;
inline constexpr float kDropletDiameterMaxUm = 50.0f;
// Density (normalised to [0, 1]) above which the optical-depth table counts "matter" for
// its distance-to-first-matter channel.
inline constexpr float kFirstMatterThreshold = 0.1f;

}  // namespace cloudlut::defaults
