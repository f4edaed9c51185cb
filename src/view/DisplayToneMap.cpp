#include "view/DisplayToneMap.h"

#include <algorithm>
#include <cmath>

#include "render/ImageWriters.h"

namespace cloudlut::view {

void toneMapForDisplay(const render::Image& image, const glm::vec3& background, float exposure,
                       std::vector<std::uint8_t>& rgba8) {
  const std::size_t pixels = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
  rgba8.resize(4 * pixels);
  for (std::size_t i = 0; i < pixels; ++i) {
    const float* p = &image.rgba[4 * i];
    for (int c = 0; c < 3; ++c) {
      float v = p[c] + (1.0f - p[3]) * background[c];
      if (!std::isfinite(v)) v = 0.0f;
      const float mapped = 1.0f - std::exp(-exposure * std::max(v, 0.0f));
      rgba8[4 * i + static_cast<std::size_t>(c)] =
          static_cast<std::uint8_t>(std::lround(255.0f * render::linearToSrgb(mapped)));
    }
    rgba8[4 * i + 3] = 255;
  }
}

}  // namespace cloudlut::view
