#include "render/ImageWriters.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "io/ExrImage.h"
#include "io/PngImage.h"

namespace cloudlut::render {

float linearToSrgb(float linear) {
  const float c = std::clamp(linear, 0.0f, 1.0f);
  return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

std::uint8_t displayValue(float radiance, float alpha, float background, float exposure) {
  float v = radiance + (1.0f - alpha) * background;
  if (!std::isfinite(v)) v = 0.0f;
  const float mapped = 1.0f - std::exp(-exposure * std::max(v, 0.0f));
  return static_cast<std::uint8_t>(std::lround(255.0f * linearToSrgb(mapped)));
}

void writePng(const Image& image, const std::filesystem::path& path, const glm::vec3& background,
              float exposure) {
  const std::size_t pixels = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
  std::vector<std::uint8_t> rgb(pixels * 3);
  for (std::size_t i = 0; i < pixels; ++i) {
    const float* p = &image.rgba[4 * i];
    for (int c = 0; c < 3; ++c) rgb[3 * i + c] = displayValue(p[c], p[3], background[c], exposure);
  }
  io::writePng(path, image.width, image.height, rgb);
}

float filmicToneCurve(float x) {
  x = std::max(x, 0.0f);
  return std::clamp(x * (2.51f * x + 0.03f) / (x * (2.43f * x + 0.59f) + 0.14f), 0.0f, 1.0f);
}

float automaticExposure(const Image& image) {
  const std::size_t pixels = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < pixels; ++i) {
    const float* p = &image.rgba[4 * i];
    const double y = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
    if (!std::isfinite(y)) continue;
    sum += std::log(1e-6 + std::max(y, 0.0));
    ++n;
  }
  return n == 0 ? 1.0f : static_cast<float>(0.18 / std::exp(sum / static_cast<double>(n)));
}

void writeFilmicPng(const Image& image, const std::filesystem::path& path, std::optional<float> exposure) {
  const float k = exposure ? *exposure : automaticExposure(image);
  const std::size_t pixels = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
  std::vector<std::uint8_t> rgb(pixels * 3);
  for (std::size_t i = 0; i < pixels; ++i)
    for (std::size_t c = 0; c < 3; ++c) {
      float v = image.rgba[4 * i + c] * k;
      if (!std::isfinite(v)) v = 0.0f;
      rgb[3 * i + c] = static_cast<std::uint8_t>(std::lround(255.0f * linearToSrgb(filmicToneCurve(v))));
    }
  io::writePng(path, image.width, image.height, rgb);
}

void writeExr(const Image& image, const std::filesystem::path& path) {
  io::ExrImage out(image.width, image.height);
  const std::size_t pixels = out.pixelCount();
  const char* names[4] = {"R", "G", "B", "A"};
  for (int c = 0; c < 4; ++c) {
    std::vector<float>& channel = out.channel(names[c]);
    for (std::size_t i = 0; i < pixels; ++i) channel[i] = image.rgba[4 * i + static_cast<std::size_t>(c)];
  }
  out.channel("Z").assign(image.distance.begin(), image.distance.begin() + static_cast<std::ptrdiff_t>(pixels));
  io::writeExrImage(out, path);
}

}  // namespace cloudlut::render
