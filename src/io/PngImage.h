#pragma once
// 8-bit RGB PNG files (stb_image_write), written atomically through writeFileAtomically.
#include <cstdint>
#include <filesystem>
#include <vector>

namespace cloudlut::io {

// Writes width·height RGB pixels, rows top first, 3 bytes per pixel. A directory that does not
// exist or cannot be written raises UsageError.
void writePng(const std::filesystem::path& path, int width, int height, const std::vector<std::uint8_t>& rgb);

}  // namespace cloudlut::io
