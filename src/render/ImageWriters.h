#pragma once
// Writing rendered images. Both writers write a temporary file beside the destination and
// rename it over the final name (a final name holds either nothing or a complete image); a
// directory that does not exist or cannot be written raises UsageError.
#include <cstdint>
#include <filesystem>
#include <optional>

#include <glm/vec3.hpp>

#include "render/RenderTypes.h"

namespace cloudlut::render {

// 8-bit sRGB PNG of the image composited over a uniform background of radiance `background`
// (the sky colour): c = radiance + (1 − A)·background, tone-mapped by 1 − e^{−exposure·c}
// per channel, then sRGB-encoded. Opaque (RGB, no alpha).
void writePng(const Image& image, const std::filesystem::path& path, const glm::vec3& background,
              float exposure);

// 8-bit sRGB PNG of an image already composited under the atmosphere (render/SkyPass.h; its RGB
// is the whole pixel's radiance): c · exposure mapped by the filmic curve filmicToneCurve, then
// sRGB-encoded. Without an exposure, automaticExposure(image).
void writeFilmicPng(const Image& image, const std::filesystem::path& path, std::optional<float> exposure);

// The ACES filmic fit of Narkowicz (2015), x(2.51x + 0.03) / (x(2.43x + 0.59) + 0.14), clamped to [0, 1].
float filmicToneCurve(float x);

// 0.18 over the log-average luminance of the image (Reinhard et al. 2002, eq. 1: exp of the
// mean of log(δ + Y), δ = 1e-6, Y the Rec. 709 luminance), so that the average scene maps to
// middle grey.
float automaticExposure(const Image& image);

// OpenEXR, FLOAT channels: R, G, B linear radiance (not premultiplied further: it is the light
// the particles send toward the camera), A = 1 − transmittance, Z = distance to the closest
// cloud (+infinity where there is none). ZIP compression.
void writeExr(const Image& image, const std::filesystem::path& path);

// sRGB encoding of a linear value in [0, 1].
float linearToSrgb(float linear);

// The 8-bit display value of one channel: radiance composited over the background,
// c = radiance + (1 − alpha)·background, tone-mapped by 1 − e^{−exposure·c}, sRGB-encoded
// (non-finite values show as 0). writePng and the viewer use it.
std::uint8_t displayValue(float radiance, float alpha, float background, float exposure);

}  // namespace cloudlut::render
