// cloudlut_glsl.hpp — the shared GLSL (parameterization and phase functions) compiled as C++
// through GLM, for engines' CPU code and for cloudlut itself: the same source the shaders use,
// so CPU and GPU cannot disagree. Everything lands in namespace cloudlut::glsl.
#ifndef CLOUDLUT_GLSL_HPP
#define CLOUDLUT_GLSL_HPP

#include <glm/glm.hpp>

namespace cloudlut::glsl {
using glm::abs;
using glm::acos;
using glm::asinh;
using glm::atan;
using glm::clamp;
using glm::cos;
using glm::cross;
using glm::dot;
using glm::exp;
using glm::exp2;
using glm::floor;
using glm::length;
using glm::log2;
using glm::max;
using glm::min;
using glm::mod;
using glm::normalize;
using glm::sin;
using glm::sinh;
using glm::sqrt;
using glm::vec2;
using glm::vec3;
using glm::vec4;
#define CLOUDLUT_FN inline
#include "glsl/cloudlut_geometry.glsl"
#include "glsl/cloudlut_phase.glsl"
#include "glsl/cloudlut_shading.glsl"
#undef CLOUDLUT_FN
}  // namespace cloudlut::glsl

#endif
