#pragma once
// The optical-depth table as the sun and zenith volumes' splat reads it (render/SunVolume.h,
// shaders/sun_volume_build.comp.glsl), from ShadingTables::splatTable.
#include <glm/vec4.hpp>

#include "render/GlFunctions.h"

namespace cloudlut::render {

struct SplatTable {
  GLuint texture = 0;      // the optical-depth texture, its last matter derived (LastMatterTexture.h)
  glm::vec4 dims{0.0f};    // its axes' sizes
  float sigma = 0.0f;      // unit optical radius σ = β·R (dimensionless, unit-sphere units)
  // the table's chord_outer_third_share (core/TableLookup.h chordOuterThird): how each chord's
  // optical depth is laid along a column (chordMatterShare, cloudlut_shading.glsl)
  float chordOuterThird = 1.0f / 3.0f;
};

}  // namespace cloudlut::render
