#pragma once
// The clipmap grid functions of src/render/shaders/cloudscape_grid.glsl compiled as C++ through
// GLM (the same source the generator shader uses), in namespace cloudlut::render::grid.
#include <cstdint>

#include <glm/glm.hpp>

namespace cloudlut::render::grid {
using glm::clamp;
using glm::dot;
using glm::exp2;
using glm::floor;
using glm::ivec2;
using glm::length;
using glm::max;
using glm::min;
using glm::mix;
using glm::smoothstep;
using glm::vec2;
using glm::vec3;
using glm::vec4;
using uint = std::uint32_t;
#define CLOUDLUT_FN inline
#include "render/shaders/cloudscape_grid.glsl"
#undef CLOUDLUT_FN
}  // namespace cloudlut::render::grid
