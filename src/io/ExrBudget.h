#pragma once
// How much decoded pixel data an EXR file may claim, checked on its parsed header before any
// pixel buffer is allocated (compare's reader, io/ExrImage, and the LUT reader, io/ExrLut).
// A data window is only a claim: a 25 KB file can declare a 16384² window. The pixels a file can
// hold are bounded by its size and the best ratio of its compression (deflate, the best of
// OpenEXR's lossless codecs, stays below 1032:1; kMaxCompressionRatio leaves a margin), so a
// file claiming more raw bytes than kMaxCompressionRatio × its size is refused before decoding.
#include <cstdint>
#include <string>

#include <OpenEXR/ImfHeader.h>

namespace cloudlut::io {

inline constexpr double kMaxCompressionRatio = 1100.0;

// FileError(file, ...) naming what is claimed when the header's channels exceed `maxChannels`,
// when its data window times its channels exceeds `maxSamples` samples, or when the raw pixel
// bytes it claims (width · height · Σ bytes per channel sample) exceed kMaxCompressionRatio ·
// fileBytes.
void checkExrPixelBudget(const std::string& file, const Imf::Header& header, std::uint64_t fileBytes,
                         int maxChannels, std::uint64_t maxSamples);

}  // namespace cloudlut::io
