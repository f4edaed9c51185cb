#pragma once
// The clipmap grid functions of src/scene/glsl/cloudscape_grid.glsl compiled as C++ through
// GLM (the same source the generator shader uses), in namespace cloudlut::scene::grid.
#include <cstdint>

#include <glm/glm.hpp>

namespace cloudlut::scene::grid {
using glm::ceil;
using glm::clamp;
using glm::cos;
using glm::dot;
using glm::exp2;
using glm::floor;
using glm::ivec2;
using glm::length;
using glm::mat3;
using glm::max;
using glm::min;
using glm::mix;
using glm::pow;
using glm::sin;
using glm::smoothstep;
using glm::sqrt;
using glm::vec2;
using glm::vec3;
using glm::vec4;
using uint = std::uint32_t;
#define CLOUDLUT_FN inline
#include "scene/glsl/cloudscape_grid.glsl"
#undef CLOUDLUT_FN
}  // namespace cloudlut::scene::grid
