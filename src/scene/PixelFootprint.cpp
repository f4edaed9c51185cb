#include "scene/PixelFootprint.h"

#include <algorithm>
#include <cmath>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace cloudlut::scene {

std::size_t pixelFootprintBound(const Particle& p, const CameraFrame& frame) {
  const std::size_t w = static_cast<std::size_t>(frame.width()), h = static_cast<std::size_t>(frame.height());
  const double r = std::max({p.radii.x, p.radii.y, p.radii.z});
  const glm::dvec3 c(frame.toCamera(p.center));
  if (c.z + r <= 0.0) return 0;  // wholly behind the eye: no ray ahead meets it
  const double den = c.z * c.z - r * r;
  if (!(c.z > r && den > 1e-6 * c.z * c.z)) return w * h;  // reaches the eye's plane
  // The planes through the eye and the image's y (then x) axis that touch the sphere: in the
  // plane of that axis's normal and the view, lines t·z through the eye at distance r from the
  // centre (a, c.z), (a − t·c.z)² = r²(1 + t²), so t = (a·c.z ± r·√(a² + c.z² − r²)) / (c.z² − r²):
  // the exact range of x/z (y/z) over the sphere.
  const auto range = [&](double a) {
    const double root = r * std::sqrt(std::max(a * a + den, 0.0));
    return glm::dvec2((a * c.z - root) / den, (a * c.z + root) / den);
  };
  const glm::dvec2 tx = range(c.x), ty = range(c.y);
  const float txLo = static_cast<float>(tx.x), txHi = static_cast<float>(tx.y);
  const float tyLo = static_cast<float>(ty.x), tyHi = static_cast<float>(ty.y);
  // image y grows downward: ty's high end is the rectangle's top
  const glm::vec2 a = frame.imagePoint(txLo, tyHi), b = frame.imagePoint(txHi, tyLo);
  const auto span = [](double lo, double hi, double size) {
    const double first = std::max(std::floor(lo) - 1.0, 0.0), end = std::min(std::ceil(hi) + 1.0, size);
    return end > first ? static_cast<std::size_t>(end - first) : std::size_t{0};
  };
  return span(a.x, b.x, static_cast<double>(w)) * span(a.y, b.y, static_cast<double>(h));
}

std::size_t pixelFootprintBound(const std::vector<Particle>& particles, const CameraFrame& frame) {
  std::size_t sum = 0;
  for (const Particle& p : particles) sum += pixelFootprintBound(p, frame);
  return sum;
}

}  // namespace cloudlut::scene
