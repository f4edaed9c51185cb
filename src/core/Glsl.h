#pragma once
// The shared GLSL (lut_formats/glsl) compiled as C++ through GLM: one definition of the
// parameterization and of the phase functions for the baker, the CLI, the tests and the shaders.
#include <glm/glm.hpp>

namespace cloudlut::glsl {
using glm::abs;
using glm::acos;
using glm::atan;
using glm::clamp;
using glm::cos;
using glm::cross;
using glm::dot;
using glm::exp;
using glm::length;
using glm::log2;
using glm::max;
using glm::min;
using glm::normalize;
using glm::sin;
using glm::sqrt;
using glm::vec2;
using glm::vec3;
using glm::vec4;
#define CLOUDLUT_FN inline
#include "glsl/cloudlut_geometry.glsl"
#include "glsl/cloudlut_phase.glsl"
#undef CLOUDLUT_FN
}  // namespace cloudlut::glsl
