#pragma once
// The detail noise of the cloud density (seed §5.4): its parameters. Its function is the shared
// GLSL of lut_formats/glsl/cloudlut_detail_noise.glsl, compiled as C++ with the rest of the
// shared GLSL (core/Glsl.h, namespace cloudlut::glsl), the same source the particle shader
// uses. The path tracer multiplies the extinction at x by detailDensityFactor(x, packed()); the
// renderer a chord's optical depth by detailChordFactor (the mean of that factor along it).
#include <glm/vec4.hpp>

#include "core/Glsl.h"

namespace cloudlut {

// Limits of the parameters (scene files, presets and options alike).
inline constexpr float kMaxDetailAmplitude = 1.0f;  // m = 1 + a·n stays ≥ 0
inline constexpr int kMaxDetailSeed = 1 << 24;      // exact in the float the shader receives

// The detail of a scene or cloudscape: density factor 1 + amplitude · n(x / scale) (dimensionless
// amplitude in [0, 1], 0 = off; feature size in world units, > 0; the noise's seed in [0, 2^24)).
struct DetailNoise {
  float amplitude = 0.0f;
  float scale = 1.0f;
  int seed = 1;

  bool enabled() const { return amplitude > 0.0f; }
  // (a, 1/s, seed, 0) as cloudlut_detail_noise.glsl takes it; all 0 when off.
  glm::vec4 packed() const {
    return enabled() ? glm::vec4(amplitude, 1.0f / scale, static_cast<float>(seed), 0.0f) : glm::vec4(0.0f);
  }
};

}  // namespace cloudlut
