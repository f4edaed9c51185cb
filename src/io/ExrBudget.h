#pragma once
// How much decoded pixel data an EXR file may claim, checked on its parsed header before any
// pixel buffer is allocated (compare's reader, io/ExrImage, and the LUT reader, io/ExrLut).
// A data window is only a claim: a 25 KB file can declare a 16384² window. The pixels a file can
// hold are bounded by its size and the best ratio of its compression (deflate, the best of
// OpenEXR's lossless codecs, stays below 1032:1; kMaxCompressionRatio leaves a margin), so a
// file claiming more raw bytes than kMaxCompressionRatio × its size is refused before decoding.
#include <cstddef>
#include <cstdint>
#include <string>

#include <OpenEXR/ImfHeader.h>

namespace cloudlut::io {

inline constexpr double kMaxCompressionRatio = 1100.0;

// What a reader accepts in a header: its name for messages ("cloudlut LUT") and its channels.
struct ExrHeaderLimits {
  const char* kind;
  std::size_t maxChannels;
};

// The header walk before OpenEXR parses anything (io/ExrLut.cpp): magic, version, a single-part
// scanline file, every attribute's declared size within the bytes left and every value of a type
// OpenEXR parses by content checked by content (a channel list of at most limits.maxChannels
// full-resolution channels, data windows within 65536² and 2^30 pixels, strings within 1 MiB);
// a type OpenEXR knows but no reader needs (preview, stringvector, ...) is refused. After it,
// OpenEXR's header parser allocates nothing larger than the file. FileError naming the file.
void checkExrHeaderBeforeDecoding(const std::string& file, const std::string& bytes, const ExrHeaderLimits& limits);

// FileError(file, ...) naming what is claimed when the header's channels exceed `maxChannels`,
// when its data window times its channels exceeds `maxSamples` samples, or when the raw pixel
// bytes it claims (width · height · Σ bytes per channel sample) exceed kMaxCompressionRatio ·
// fileBytes.
void checkExrPixelBudget(const std::string& file, const Imf::Header& header, std::uint64_t fileBytes,
                         int maxChannels, std::uint64_t maxSamples);

}  // namespace cloudlut::io
