#include "view/DisplayToneMap.h"

#include "render/ImageWriters.h"

namespace cloudlut::view {

void toneMapForDisplay(const render::Image& image, const glm::vec3& background, float exposure,
                       std::vector<std::uint8_t>& rgba8) {
  const std::size_t pixels = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
  rgba8.resize(4 * pixels);
  for (std::size_t i = 0; i < pixels; ++i) {
    const float* p = &image.rgba[4 * i];
    for (int c = 0; c < 3; ++c)
      rgba8[4 * i + static_cast<std::size_t>(c)] = render::displayValue(p[c], p[3], background[c], exposure);
    rgba8[4 * i + 3] = 255;
  }
}

}  // namespace cloudlut::view
