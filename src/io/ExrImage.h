#pragma once
// Linear images with any named FLOAT channels, read from and written to OpenEXR (scanline,
// ZIP). Used by `cloudlut reference scene` (R, G, B, A and the standard-error channels) and by
// `cloudlut compare`. Rows are stored top first, channels planar.
//
// Writing goes through writeFileAtomically (a final name holds nothing or a complete image); a
// directory that does not exist or cannot be written raises UsageError. Reading raises
// FileError naming the file for anything that is not a readable EXR image.
#include <cstddef>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace cloudlut::io {

struct ExrImage {
  int width = 0;
  int height = 0;
  // Channel name → width·height samples, row 0 at the top. Any pixel type in the file is
  // decoded to float.
  std::map<std::string, std::vector<float>> channels;
  // String attributes to store in (or read from) the header, e.g. the settings of a render.
  std::map<std::string, std::string> attributes;

  ExrImage() = default;
  ExrImage(int w, int h) : width(w), height(h) {}

  std::size_t pixelCount() const { return static_cast<std::size_t>(width) * static_cast<std::size_t>(height); }
  bool has(const std::string& name) const { return channels.count(name) > 0; }
  // The channel's samples, created (zero-filled) when absent.
  std::vector<float>& channel(const std::string& name);
  // The channel's samples; FileError-free: throws std::out_of_range when absent.
  const std::vector<float>& channel(const std::string& name) const { return channels.at(name); }
};

// Writes every channel as FLOAT with ZIP compression, and every attribute as a string.
void writeExrImage(const ExrImage& image, const std::filesystem::path& path);

// Reads every channel of the file's data window (decoded to float) and its string attributes.
// At most 64 channels and 2^28 samples, and no more raw pixel data than the file's size can
// hold (io/ExrBudget.h): checked on the header, before anything is allocated.
ExrImage readExrImage(const std::filesystem::path& path);

}  // namespace cloudlut::io
