// cloudlut_lut.h — a dependency-free, header-only reader of cloudlut's binary tables (.bin).
//
// C++17, standard library only, no JSON: reads and checks the binary format of
// lut_formats/FORMAT.md section 2 and keeps the samples decoded to float (the stored bytes are
// not kept). manifest.json and the header's JSON description are read by the optional
// cloudlut_manifest.h; EXR files are left to the engine's own EXR loader.
//
//   cloudlut_reader::Lut lut = cloudlut_reader::readLut("luts/optical_depth.bin");
//   // lut.values is ready for glTexImage3D(GL_TEXTURE_3D, 0, internalFormat,
//   //     lut.textureWidth(), lut.textureHeight(), lut.textureDepth(), 0,
//   //     GL_RED / GL_RG / GL_RGB / GL_RGBA (lut.channelCount()), GL_FLOAT, lut.values.data())
//   // with internalFormat GL_R8 / GL_R16F / GL_R32F ... as lut.sampleType says: the driver's
//   // conversion restores the stored samples exactly.
//   float v[4];
//   lut.sample(x0, x1, x2, x3, v);  // quadrilinear at axis fractions in [0, 1]
//
// Every error is a std::runtime_error whose message starts with the file name.
#ifndef CLOUDLUT_LUT_H
#define CLOUDLUT_LUT_H

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cloudlut_quadrilinear.h"

namespace cloudlut_reader {

enum class SampleType : std::uint32_t { U8 = 0, Half = 1, Float = 2 };

// One axis: `size` nodes from `min` (node 0) to `max` (node size-1).
struct Axis {
  std::string name;
  std::string unit;
  double min = 0.0;
  double max = 1.0;
  std::uint32_t size = 1;
  bool periodic = false;
  // Node concentration about the middle (concentratedFraction in cloudlut_geometry.glsl):
  // node i sits at the axis fraction i/(size-1), at the value
  // min + (max - min) * concentratedFraction(i/(size-1), warp). 0 = uniform nodes.
  float warp = 0.0f;
  // Version 3. Folded: the quantity is mirror-symmetric about `max` and only [min, max] is
  // stored (the scattering tables' φv over [0, π]: sample at mirroredAzimuth(φv)).
  // linearInExp2: a log2 axis interpolated linearly in 2^value between neighbouring nodes (the
  // scattering tables' density: densityAxisLinearInRho). scatteringAxes() in
  // cloudlut_geometry.glsl takes both as its layout flags (scatteringAxesRecord below).
  bool folded = false;
  bool linearInExp2 = false;
};

// A loaded table. Layout of `values`: axis 0 fastest, then 1, 2, 3; channels interleaved — a
// 3D texture of width dims[0], height dims[1], depth dims[2]·dims[3].
struct Lut {
  std::string name;
  std::array<std::uint32_t, 4> dims{};
  std::array<Axis, 4> axes;
  std::vector<std::string> channels;
  SampleType sampleType = SampleType::Float;  // how the file stores the samples
  std::string description;                    // the header's JSON description (may be empty)
  std::uint32_t version = 0;                  // the file's format version
  std::vector<float> values;                  // the samples decoded to float (u8 as byte/255)

  std::size_t channelCount() const { return channels.size(); }
  std::uint32_t textureWidth() const { return dims[0]; }
  std::uint32_t textureHeight() const { return dims[1]; }
  std::uint32_t textureDepth() const { return dims[2] * dims[3]; }
  // Bytes per stored sample in the file: 1, 2 or 4.
  std::size_t sampleBytes() const {
    return sampleType == SampleType::U8 ? 1u : sampleType == SampleType::Half ? 2u : 4u;
  }

  // For a scattering table (θS, φv, θv, log2 ρ): the axes record scatteringAxes() in
  // cloudlut_geometry.glsl takes, (log2 ρ at the first and last density node, θS warp, layout),
  // layout = 1 if φv is folded + 2 if the density axis is interpolated linearly in ρ. Pass
  // dims[3] as its density node count.
  std::array<float, 4> scatteringAxesRecord() const {
    const float layout = (axes[1].folded ? 1.0f : 0.0f) + (axes[3].linearInExp2 ? 2.0f : 0.0f);
    return {static_cast<float>(axes[3].min), static_cast<float>(axes[3].max), axes[0].warp, layout};
  }

  // Index of node (i0, i1, i2, i3); multiply by channelCount() for the first value.
  std::size_t index(std::uint32_t i0, std::uint32_t i1, std::uint32_t i2, std::uint32_t i3) const {
    return nodeIndex(dims.data(), i0, i1, i2, i3);
  }
  float value(std::uint32_t i0, std::uint32_t i1, std::uint32_t i2, std::uint32_t i3,
              std::size_t channel) const {
    return values[index(i0, i1, i2, i3) * channelCount() + channel];
  }

  // Quadrilinear interpolation at axis fractions x ∈ [0, 1] (clamped); node i of n sits at
  // i / (n - 1) (sampleQuadrilinear). Writes channelCount() values to out.
  void sample(float x0, float x1, float x2, float x3, float* out) const {
    const float x[4] = {x0, x1, x2, x3};
    sampleQuadrilinear(values.data(), dims.data(), channelCount(), x, out);
  }
  std::vector<float> sample(float x0, float x1, float x2, float x3) const {
    std::vector<float> out(channelCount());
    sample(x0, x1, x2, x3, out.data());
    return out;
  }
};

// Reads and validates a binary LUT file.
Lut readLut(const std::string& path);
// Parses a binary LUT held in memory; `name` only labels error messages.
Lut parseLut(const std::vector<std::uint8_t>& bytes, const std::string& name);

// ---------------------------------------------------------------------------------------------
// Implementation.

namespace detail {

[[noreturn]] inline void fail(const std::string& name, const std::string& problem) {
  throw std::runtime_error(name + ": " + problem);
}

// FNV-1a 64-bit of n bytes, continuing from the running value h (FORMAT.md section 2.2).
constexpr std::uint64_t kFnvOffset = 14695981039346656037ull;
inline std::uint64_t fnv1a64(const std::uint8_t* p, std::size_t n, std::uint64_t h = kFnvOffset) {
  for (std::size_t k = 0; k < n; ++k) {
    h ^= p[k];
    h *= 1099511628211ull;
  }
  return h;
}

// The unsigned integer stored little-endian in `bytes` bytes at p.
inline std::uint64_t le(const std::uint8_t* p, int bytes) {
  std::uint64_t v = 0;
  for (int k = 0; k < bytes; ++k) v |= static_cast<std::uint64_t>(p[k]) << (8 * k);
  return v;
}
inline std::uint32_t le32(const std::uint8_t* p) { return static_cast<std::uint32_t>(le(p, 4)); }

inline double leF64(const std::uint8_t* p) {
  const std::uint64_t bits = le(p, 8);
  double d;
  std::memcpy(&d, &bits, sizeof d);
  return d;
}

inline float bitsToFloat(std::uint32_t bits) {
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

// IEEE half → float, exact for every value (subnormals, infinities and NaNs included).
inline float halfToFloat(std::uint16_t h) {
  const std::uint32_t sign = static_cast<std::uint32_t>(h & 0x8000u) << 16;
  const std::uint32_t exponent = (h >> 10) & 0x1fu;
  const std::uint32_t mantissa = h & 0x3ffu;
  if (exponent == 0) {
    const float magnitude = std::ldexp(static_cast<float>(mantissa), -24);
    return sign ? -magnitude : magnitude;
  }
  if (exponent == 31) return bitsToFloat(sign | 0x7f800000u | (mantissa << 13));
  return bitsToFloat(sign | ((exponent + 112u) << 23) | (mantissa << 13));
}

// The text of a NUL-padded field; fails if it holds no NUL.
inline std::string fixedString(const std::uint8_t* p, std::size_t size, const std::string& name,
                               const char* what) {
  const void* nul = std::memchr(p, 0, size);
  if (nul == nullptr) fail(name, std::string("corrupt header (") + what + ")");
  return std::string(reinterpret_cast<const char*>(p),
                     static_cast<std::size_t>(static_cast<const std::uint8_t*>(nul) - p));
}

constexpr std::size_t kMinHeaderBytes = 392;
constexpr std::size_t kDescriptionOffset = 380;
constexpr std::size_t kMaxHeaderBytes = (16u << 20) + kMinHeaderBytes;

// Header size for a description of n bytes: 380 + n padded to a multiple of 8, + 8.
inline std::size_t headerBytesFor(std::size_t n) { return (kDescriptionOffset + n + 7) / 8 * 8 + 8; }

// Checks magic, version and header size of the first 16 bytes; returns the header size.
inline std::size_t checkPrefix(const std::uint8_t* p, std::size_t available,
                               std::uint64_t fileBytes, const std::string& name) {
  if (available < 8 || std::memcmp(p, "CLOUDLUT", 8) != 0) {
    if (available < 8 && std::memcmp(p, "CLOUDLUT", available) == 0)
      fail(name, "truncated: expected a header of at least 392 bytes, found " +
                     std::to_string(fileBytes));
    fail(name, "not a cloudlut LUT (bad magic)");
  }
  if (available < 16)
    fail(name, "truncated: expected a header of at least 392 bytes, found " +
                   std::to_string(fileBytes));
  const std::uint32_t version = le32(p + 8);
  if (version < 1 || version > 3)
    fail(name, "unsupported format version " + std::to_string(version) + " (this build reads 1 to 3)");
  const std::uint32_t headerBytes = le32(p + 12);
  if (headerBytes < kMinHeaderBytes || headerBytes > kMaxHeaderBytes || headerBytes % 8 != 0)
    fail(name, "corrupt header (header size " + std::to_string(headerBytes) + ")");
  if (headerBytes > fileBytes)
    fail(name, "truncated: expected a header of " + std::to_string(headerBytes) +
                   " bytes, found " + std::to_string(fileBytes));
  return headerBytes;
}

// Decodes a verified header into `lut` (everything but the values); returns the payload size
// and checksum the header promises.
inline void parseHeader(const std::uint8_t* p, std::size_t headerBytes, const std::string& name,
                        Lut& lut, std::uint64_t& payloadBytes, std::uint64_t& payloadChecksum) {
  if (fnv1a64(p, headerBytes - 8) != le(p + headerBytes - 8, 8))
    fail(name, "header checksum mismatch");
  const std::uint32_t version = le32(p + 8);
  lut.version = version;
  for (std::size_t k = 0; k < 4; ++k) lut.dims[k] = le32(p + 16 + 4 * k);
  const std::uint32_t channels = le32(p + 32);
  const std::uint32_t type = le32(p + 36);
  payloadBytes = le(p + 40, 8);
  payloadChecksum = le(p + 48, 8);
  if (type > 2) fail(name, "corrupt header (unknown sample type " + std::to_string(type) + ")");
  lut.sampleType = static_cast<SampleType>(type);
  if (channels < 1 || channels > 4)
    fail(name, "corrupt header (" + std::to_string(channels) + " channels, expected 1 to 4)");
  lut.name = fixedString(p + 56, 32, name, "table name");
  for (std::size_t k = 0; k < 4; ++k) {
    const std::uint8_t* a = p + 88 + 48 * k;
    Axis& axis = lut.axes[k];
    axis.name = fixedString(a, 16, name, "axis name");
    axis.unit = fixedString(a + 16, 8, name, "axis unit");
    axis.min = leF64(a + 24);
    axis.max = leF64(a + 32);
    const std::uint32_t flags = le32(a + 40);
    // bit 0 periodic; version 3: bit 1 folded, bit 2 interpolated linearly in 2^value
    if ((flags & ~(version >= 3 ? 7u : 1u)) != 0 || (flags & 3u) == 3u)
      fail(name, "corrupt header (axis flags)");
    axis.periodic = (flags & 1u) != 0;
    axis.folded = (flags & 2u) != 0;
    axis.linearInExp2 = (flags & 4u) != 0;
    const std::uint32_t warpBits = le32(a + 44);
    std::memcpy(&axis.warp, &warpBits, sizeof axis.warp);
    if (!(axis.warp >= 0.0f && axis.warp <= 20.0f) || (version < 2 && warpBits != 0))
      fail(name, "corrupt header (axis node concentration)");
    axis.size = lut.dims[k];
    if (axis.size < 1) fail(name, "corrupt header (an axis has no nodes)");
  }
  lut.channels.clear();
  for (std::size_t c = 0; c < channels; ++c)
    lut.channels.push_back(fixedString(p + 280 + 24 * c, 24, name, "channel name"));
  const std::uint32_t jsonBytes = le32(p + 376);
  if (headerBytesFor(jsonBytes) > headerBytes) fail(name, "corrupt header (description length)");
  lut.description.assign(reinterpret_cast<const char*>(p + kDescriptionOffset), jsonBytes);
  // dims × channels × sample size must equal the payload size, without overflowing.
  std::uint64_t expected = lut.sampleBytes() * channels;
  for (const std::uint32_t d : lut.dims) {
    if (expected > UINT64_MAX / d) fail(name, "corrupt header (payload size overflows)");
    expected *= d;
  }
  if (expected != payloadBytes)
    fail(name, "corrupt header (payload size does not match the dimensions)");
}

// Fails unless the file holds exactly the payload the header promises.
inline void checkPayloadSize(std::uint64_t found, std::uint64_t payloadBytes,
                             const std::string& name) {
  if (found < payloadBytes)
    fail(name, "truncated: expected " + std::to_string(payloadBytes) +
                   " bytes of payload, found " + std::to_string(found));
  if (found > payloadBytes)
    fail(name, "corrupt: expected " + std::to_string(payloadBytes) +
                   " bytes of payload, found " + std::to_string(found));
}

// Decodes `count` stored samples at p into out (u8 → byte/255, half and float exactly).
inline void decodeSamples(const std::uint8_t* p, std::size_t count, SampleType type, float* out) {
  for (std::size_t k = 0; k < count; ++k) {
    switch (type) {
      case SampleType::U8: out[k] = static_cast<float>(p[k]) / 255.0f; break;
      case SampleType::Half: out[k] = halfToFloat(static_cast<std::uint16_t>(le(p + 2 * k, 2))); break;
      case SampleType::Float: out[k] = bitsToFloat(le32(p + 4 * k)); break;
    }
  }
}

}  // namespace detail

inline Lut parseLut(const std::vector<std::uint8_t>& bytes, const std::string& name) {
  if (bytes.empty()) detail::fail(name, "not a cloudlut LUT (empty file)");
  const std::size_t headerBytes =
      detail::checkPrefix(bytes.data(), bytes.size(), bytes.size(), name);
  Lut lut;
  std::uint64_t payloadBytes = 0, checksum = 0;
  detail::parseHeader(bytes.data(), headerBytes, name, lut, payloadBytes, checksum);
  const std::uint8_t* payload = bytes.data() + headerBytes;
  detail::checkPayloadSize(bytes.size() - headerBytes, payloadBytes, name);
  const std::size_t n = static_cast<std::size_t>(payloadBytes);
  if (detail::fnv1a64(payload, n) != checksum) detail::fail(name, "checksum mismatch");
  lut.values.resize(n / lut.sampleBytes());
  detail::decodeSamples(payload, lut.values.size(), lut.sampleType, lut.values.data());
  return lut;
}

// Reads the header first and checks the payload size it claims against the real file size
// before allocating anything of that size; then streams the payload through a small buffer,
// checksumming and decoding it, so that only the decoded values are ever held whole.
inline Lut readLut(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) detail::fail(path, "missing or unreadable");
  in.seekg(0, std::ios::end);
  const std::streamoff end = in.tellg();
  if (end < 0) detail::fail(path, "cannot be read");
  const auto fileBytes = static_cast<std::uint64_t>(end);
  in.seekg(0, std::ios::beg);
  if (fileBytes == 0) detail::fail(path, "not a cloudlut LUT (empty file)");

  std::vector<std::uint8_t> header(16);
  in.read(reinterpret_cast<char*>(header.data()), 16);
  const auto got = static_cast<std::size_t>(in.gcount());
  const std::size_t headerBytes = detail::checkPrefix(header.data(), got, fileBytes, path);
  header.resize(headerBytes);
  in.read(reinterpret_cast<char*>(header.data() + 16), static_cast<std::streamsize>(headerBytes - 16));
  if (static_cast<std::size_t>(in.gcount()) != headerBytes - 16)
    detail::fail(path, "read error in the header");
  Lut lut;
  std::uint64_t payloadBytes = 0, checksum = 0;
  detail::parseHeader(header.data(), headerBytes, path, lut, payloadBytes, checksum);
  detail::checkPayloadSize(fileBytes - headerBytes, payloadBytes, path);

  const std::size_t sampleBytes = lut.sampleBytes();
  lut.values.resize(static_cast<std::size_t>(payloadBytes) / sampleBytes);
  const std::size_t chunkSamples = (std::size_t(1) << 20) / sampleBytes;  // 1 MiB of the file at a time
  std::vector<std::uint8_t> chunk(std::min(lut.values.size(), chunkSamples) * sampleBytes);
  std::uint64_t h = detail::kFnvOffset;
  for (std::size_t done = 0; done < lut.values.size();) {
    const std::size_t count = std::min(chunkSamples, lut.values.size() - done);
    const std::size_t bytes = count * sampleBytes;
    in.read(reinterpret_cast<char*>(chunk.data()), static_cast<std::streamsize>(bytes));
    if (static_cast<std::size_t>(in.gcount()) != bytes) detail::fail(path, "read error in the payload");
    h = detail::fnv1a64(chunk.data(), bytes, h);
    detail::decodeSamples(chunk.data(), count, lut.sampleType, lut.values.data() + done);
    done += count;
  }
  if (h != checksum) detail::fail(path, "checksum mismatch");
  return lut;
}

}  // namespace cloudlut_reader

#endif  // CLOUDLUT_LUT_H
