#include "io/PngImage.h"

#include <string>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#include <stb/stb_image_write.h>

#include "core/Errors.h"
#include "io/LutIo.h"

namespace cloudlut::io {

namespace {
void appendBytes(void* context, void* data, int size) {
  static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
}
}  // namespace

void writePng(const std::filesystem::path& path, int width, int height, const std::vector<std::uint8_t>& rgb) {
  if (width <= 0 || height <= 0 || rgb.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3)
    throw UsageError("cannot encode '" + path.string() + "' as PNG: bad image size");
  std::string bytes;
  if (!stbi_write_png_to_func(appendBytes, &bytes, width, height, 3, rgb.data(), width * 3))
    throw UsageError("cannot encode '" + path.string() + "' as PNG");
  writeFileAtomically(path, bytes);
}

}  // namespace cloudlut::io
