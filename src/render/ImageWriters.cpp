#include "render/ImageWriters.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#include <stb/stb_image_write.h>

#include "core/Errors.h"
#include "io/LutIo.h"

namespace cloudlut::render {

namespace {

void appendBytes(void* context, void* data, int size) {
  auto* out = static_cast<std::string*>(context);
  out->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
}

std::filesystem::path checkedTempPath(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw UsageError("cannot write '" + path.string() + "': directory '" + dir.string() + "' does not exist");
  if (access(dir.c_str(), W_OK) != 0)
    throw UsageError("cannot write '" + path.string() + "': directory '" + dir.string() + "' is not writable");
  return dir / (path.filename().string() + ".tmp." + std::to_string(static_cast<long>(::getpid())) + ".exr");
}

}  // namespace

float linearToSrgb(float linear) {
  const float c = std::clamp(linear, 0.0f, 1.0f);
  return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

void writePng(const Image& image, const std::filesystem::path& path, const glm::vec3& background,
              float exposure) {
  const std::size_t pixels = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
  std::vector<unsigned char> rgb(pixels * 3);
  for (std::size_t i = 0; i < pixels; ++i) {
    const float* p = &image.rgba[4 * i];
    for (int c = 0; c < 3; ++c) {
      float v = p[c] + (1.0f - p[3]) * background[c];
      if (!std::isfinite(v)) v = 0.0f;
      const float mapped = 1.0f - std::exp(-exposure * std::max(v, 0.0f));
      rgb[3 * i + c] = static_cast<unsigned char>(std::lround(255.0f * linearToSrgb(mapped)));
    }
  }
  std::string bytes;
  if (!stbi_write_png_to_func(appendBytes, &bytes, image.width, image.height, 3, rgb.data(), image.width * 3))
    throw UsageError("cannot encode '" + path.string() + "' as PNG");
  io::writeFileAtomically(path, bytes);
}

void writeExr(const Image& image, const std::filesystem::path& path) {
  const std::filesystem::path temp = checkedTempPath(path);
  const std::size_t pixels = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
  std::vector<float> z(image.distance.begin(), image.distance.begin() + static_cast<std::ptrdiff_t>(pixels));
  try {
    Imf::Header header(image.width, image.height);
    header.compression() = Imf::ZIP_COMPRESSION;
    const char* names[4] = {"R", "G", "B", "A"};
    for (const char* n : names) header.channels().insert(n, Imf::Channel(Imf::FLOAT));
    header.channels().insert("Z", Imf::Channel(Imf::FLOAT));
    Imf::FrameBuffer frame;
    const std::size_t xStride = 4 * sizeof(float);
    char* base = const_cast<char*>(reinterpret_cast<const char*>(image.rgba.data()));
    for (int c = 0; c < 4; ++c)
      frame.insert(names[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), xStride, xStride * image.width));
    frame.insert("Z", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(z.data()), sizeof(float),
                                 sizeof(float) * static_cast<std::size_t>(image.width)));
    {
      Imf::OutputFile out(temp.c_str(), header);
      out.setFrameBuffer(frame);
      out.writePixels(image.height);
    }
    std::filesystem::rename(temp, path);
  } catch (const std::exception& e) {
    std::error_code ec;
    std::filesystem::remove(temp, ec);
    throw UsageError("cannot write '" + path.string() + "': " + e.what());
  }
}

}  // namespace cloudlut::render
