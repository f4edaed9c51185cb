// The pixel budget of an EXR file: channels, samples and raw bytes against its size.
#include "io/ExrBudget.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfHeader.h>

#include <cstdio>

#include "core/Errors.h"

namespace cloudlut::io {

void checkExrPixelBudget(const std::string& file, const Imf::Header& header, std::uint64_t fileBytes,
                         int maxChannels, std::uint64_t maxSamples) {
  const auto& dw = header.dataWindow();
  const long long w = static_cast<long long>(dw.max.x) - dw.min.x + 1;
  const long long h = static_cast<long long>(dw.max.y) - dw.min.y + 1;
  if (w < 1 || h < 1 || w > 65536 || h > 65536)
    throw FileError(file, "unsupported data window " + std::to_string(w) + "x" + std::to_string(h));
  int channels = 0;
  double bytesPerPixel = 0;
  for (auto it = header.channels().begin(); it != header.channels().end(); ++it) {
    ++channels;
    bytesPerPixel += it.channel().type == Imf::HALF ? 2.0 : 4.0;
  }
  if (channels > maxChannels)
    throw FileError(file, std::to_string(channels) + " channels, more than the " + std::to_string(maxChannels) +
                              " this reader accepts");
  const double pixels = static_cast<double>(w) * static_cast<double>(h);
  if (pixels * channels > static_cast<double>(maxSamples))
    throw FileError(file, "claims " + std::to_string(w) + "x" + std::to_string(h) + " pixels of " +
                              std::to_string(channels) + " channels, more than " + std::to_string(maxSamples) +
                              " samples");
  const double raw = pixels * bytesPerPixel;
  if (raw > kMaxCompressionRatio * static_cast<double>(fileBytes)) {
    char problem[256];
    std::snprintf(problem, sizeof problem,
                  "corrupt: its data window (%lldx%lld, %d channels) claims %.3g MB of pixels, more than a file of "
                  "%llu bytes can hold (compression ratio above %.0f:1)",
                  w, h, channels, raw / 1e6, static_cast<unsigned long long>(fileBytes), kMaxCompressionRatio);
    throw FileError(file, problem);
  }
}

}  // namespace cloudlut::io
