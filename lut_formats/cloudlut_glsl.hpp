// cloudlut_glsl.hpp — the shared GLSL (parameterization, phase and shading functions, the
// atmosphere, the detail noise) compiled as C++ through GLM, for engines' CPU code and for
// cloudlut itself: the same source the shaders use, so CPU and GPU cannot disagree. Everything lands in namespace cloudlut::glsl.
#ifndef CLOUDLUT_GLSL_HPP
#define CLOUDLUT_GLSL_HPP

#include <cstdint>

#include <glm/glm.hpp>

namespace cloudlut::glsl {
using glm::abs;
using glm::acos;
using glm::asinh;
using glm::atan;
using glm::ceil;
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
using glm::mix;
using glm::min;
using glm::mod;
using glm::normalize;
using glm::sin;
using glm::sinh;
using glm::sqrt;
using glm::vec2;
using glm::vec3;
using glm::vec4;
using uint = std::uint32_t;

// An atmosphere table as the shared GLSL samples it (cloudlut_atmosphere_tables.glsl): `width` ×
// `height` RGB texels, x fastest (the Table4D layout of a table whose axes 2 and 3 have one
// node), sampled by atmosphereTexture as an OpenGL sampler2D with linear filtering and
// clamp-to-edge: texel i's centre sits at u = (i + 0.5) / width.
struct AtmosphereTexture {
  const float* texels = nullptr;
  int width = 0;
  int height = 0;
};

inline vec3 atmosphereTexel(const AtmosphereTexture& t, int i, int j) {
  const float* p = t.texels + 3 * (static_cast<long>(j) * t.width + i);
  return vec3(p[0], p[1], p[2]);
}

// Bilinear, clamp-to-edge lookup at texture coordinates uv (what texture() returns in GLSL).
inline vec3 atmosphereTexture(const AtmosphereTexture& t, vec2 uv) {
  const float x = glm::clamp(uv.x * static_cast<float>(t.width) - 0.5f, 0.0f, static_cast<float>(t.width - 1));
  const float y = glm::clamp(uv.y * static_cast<float>(t.height) - 0.5f, 0.0f, static_cast<float>(t.height - 1));
  const int i0 = static_cast<int>(x), j0 = static_cast<int>(y);
  const int i1 = i0 + 1 < t.width ? i0 + 1 : i0, j1 = j0 + 1 < t.height ? j0 + 1 : j0;
  const float fx = x - static_cast<float>(i0), fy = y - static_cast<float>(j0);
  return glm::mix(glm::mix(atmosphereTexel(t, i0, j0), atmosphereTexel(t, i1, j0), fx),
                  glm::mix(atmosphereTexel(t, i0, j1), atmosphereTexel(t, i1, j1), fx), fy);
}

#define CLOUDLUT_ATMOSPHERE_TEXTURE_DEFINED
#define CLOUDLUT_FN inline
#include "glsl/cloudlut_geometry.glsl"
#include "glsl/cloudlut_phase.glsl"
#include "glsl/cloudlut_shading.glsl"
#include "glsl/cloudlut_atmosphere.glsl"
#include "glsl/cloudlut_atmosphere_tables.glsl"
#include "glsl/cloudlut_atmosphere_sky.glsl"
#include "glsl/cloudlut_atmosphere_nodes.glsl"
#include "glsl/cloudlut_detail_noise.glsl"
#undef CLOUDLUT_FN
}  // namespace cloudlut::glsl

#endif
