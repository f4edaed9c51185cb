#include "render/RenderTypes.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>

#include "core/Errors.h"

namespace cloudlut::render {

namespace {
// Bytes per pixel the render needs at its peak: the float framebuffer (20; 20/downscale² when
// upscaled), the upscale's output buffers (20, kept between frames), the Image (20) and an
// encoder's copy (≤ 24).
constexpr long double kBytesPerPixel = 84.0L;
}  // namespace

BlendMode parseBlendMode(const std::string& text) {
  if (text == "alpha") return BlendMode::Alpha;
  if (text == "volume") return BlendMode::Volume;
  throw UsageError("--blend: expected alpha or volume, got '" + text + "'");
}

VolumeTilePlan parseVolumeTilePlan(const std::string& text) {
  if (text == "auto") return VolumeTilePlan::Auto;
  if (text == "counted") return VolumeTilePlan::Counted;
  if (text == "expected") return VolumeTilePlan::Expected;
  throw UsageError("--tile-plan: expected auto, counted or expected, got '" + text + "'");
}

const char* toString(BlendMode mode) { return mode == BlendMode::Volume ? "volume" : "alpha"; }

LightingModel parseLighting(const std::string& text, const std::string& option) {
  if (text == "seed") return LightingModel::Seed;
  if (text == "cloud") return LightingModel::Cloud;
  throw UsageError(option + ": expected seed or cloud, got '" + text + "'");
}

SunlightModel parseSunlight(const std::string& text, const std::string& option) {
  if (text == "particle") return SunlightModel::Particle;
  if (text == "volume") return SunlightModel::Volume;
  throw UsageError(option + ": expected particle or volume, got '" + text + "'");
}

const char* toString(LightingModel lighting) { return lighting == LightingModel::Seed ? "seed" : "cloud"; }
const char* toString(SunlightModel sunlight) { return sunlight == SunlightModel::Volume ? "volume" : "particle"; }

std::size_t Image::nonFiniteCount() const {
  return static_cast<std::size_t>(
      std::count_if(rgba.begin(), rgba.end(), [](float v) { return !std::isfinite(v); }));
}

void checkImageSize(long long width, long long height) {
  if (width < 1 || height < 1)
    throw UsageError("image size " + std::to_string(width) + "x" + std::to_string(height) +
                     ": width and height must be at least 1");
  if (width > kMaxImageSide || height > kMaxImageSide)
    throw UsageError("image size " + std::to_string(width) + "x" + std::to_string(height) +
                     ": width and height must be at most " + std::to_string(kMaxImageSide));
  const long double need = kBytesPerPixel * static_cast<long double>(width) * static_cast<long double>(height);
  const long double pages = static_cast<long double>(sysconf(_SC_PHYS_PAGES));
  const long double pageSize = static_cast<long double>(sysconf(_SC_PAGESIZE));
  const long double budget = pages > 0 && pageSize > 0 ? 0.5L * pages * pageSize : 2.0e9L;
  if (need > budget)
    throw UsageError("image size " + std::to_string(width) + "x" + std::to_string(height) + " would need " +
                     std::to_string(static_cast<long long>(need / 1048576.0L)) + " MiB, more than the " +
                     std::to_string(static_cast<long long>(budget / 1048576.0L)) +
                     " MiB this machine can spare");
}

}  // namespace cloudlut::render
