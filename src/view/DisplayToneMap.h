#pragma once
// The viewer's tone mapping: the one function that turns a rendered frame into the colours the
// window shows. It applies the same curve as the PNG writer (render/ImageWriters.h), so that what
// the window shows is what F12 and `cloudlut render` write; swap it here when the tone curve
// changes.
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "render/RenderTypes.h"

namespace cloudlut::view {

// Per pixel and channel: c = radiance + (1 − A)·background (the sky), mapped by
// 1 − e^{−exposure·c} and sRGB-encoded to 8 bits; alpha 255. `rgba8` is resized to
// 4 · width · height, row 0 the top row.
void toneMapForDisplay(const render::Image& image, const glm::vec3& background, float exposure,
                       std::vector<std::uint8_t>& rgba8);

}  // namespace cloudlut::view
