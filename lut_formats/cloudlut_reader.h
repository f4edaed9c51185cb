// cloudlut_reader.h — a dependency-free, header-only reader of cloudlut LUTs for engines.
//
// C++17, standard library only. Reads the binary LUT format and manifest.json described in
// lut_formats/FORMAT.md; EXR files are left to the engine's own EXR loader.
//
//   cloudlut_reader::Lut lut = cloudlut_reader::readLut("luts/optical_depth.bin");
//   // lut.payload is ready for glTexImage3D(GL_TEXTURE_3D, 0, internalFormat,
//   //     lut.textureWidth(), lut.textureHeight(), lut.textureDepth(), 0,
//   //     lut.channelCount() == 1 ? GL_RED : ..., lut.glType() ..., lut.payload.data());
//   float v[4];
//   lut.sample(x0, x1, x2, x3, v);  // quadrilinear at axis fractions in [0, 1]
//
//   cloudlut_reader::Manifest m = cloudlut_reader::readManifest("luts");
//   for (const auto& t : m.tables) { ... t.name, t.binFile, t.exrFile, t.dims ... }
//
// Every error is a std::runtime_error whose message starts with the file name.
#ifndef CLOUDLUT_READER_H
#define CLOUDLUT_READER_H

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

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
};

// A loaded table. Layout of `payload` and `values`: axis 0 fastest, then 1, 2, 3; channels
// interleaved — a 3D texture of width dims[0], height dims[1], depth dims[2]·dims[3].
struct Lut {
  std::string name;
  std::array<std::uint32_t, 4> dims{};
  std::array<Axis, 4> axes;
  std::vector<std::string> channels;
  SampleType sampleType = SampleType::Float;
  std::string description;            // the header's JSON description (may be empty)
  std::vector<std::uint8_t> payload;  // the samples as stored (little-endian)
  std::vector<float> values;          // the samples decoded to float

  std::size_t channelCount() const { return channels.size(); }
  std::uint32_t textureWidth() const { return dims[0]; }
  std::uint32_t textureHeight() const { return dims[1]; }
  std::uint32_t textureDepth() const { return dims[2] * dims[3]; }
  // Bytes per stored sample: 1, 2 or 4.
  std::size_t sampleBytes() const {
    return sampleType == SampleType::U8 ? 1u : sampleType == SampleType::Half ? 2u : 4u;
  }

  // Index of node (i0, i1, i2, i3); multiply by channelCount() for the first value.
  std::size_t index(std::uint32_t i0, std::uint32_t i1, std::uint32_t i2, std::uint32_t i3) const {
    return ((static_cast<std::size_t>(i3) * dims[2] + i2) * dims[1] + i1) * dims[0] + i0;
  }
  float value(std::uint32_t i0, std::uint32_t i1, std::uint32_t i2, std::uint32_t i3,
              std::size_t channel) const {
    return values[index(i0, i1, i2, i3) * channelCount() + channel];
  }

  // Quadrilinear interpolation at axis fractions x ∈ [0, 1] (clamped); node i of n sits at
  // i / (n - 1). Writes channelCount() values to out.
  void sample(float x0, float x1, float x2, float x3, float* out) const;
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

// A JSON value: just enough JSON for manifest.json and the header description.
struct Json {
  enum class Type { Null, Bool, Number, String, Array, Object };
  Type type = Type::Null;
  bool boolean = false;
  double number = 0.0;
  std::string string;
  std::vector<Json> items;        // array elements, or object values
  std::vector<std::string> keys;  // object keys, parallel to items

  // The member named `key` of an object, or nullptr.
  const Json* find(const std::string& key) const {
    if (type != Type::Object) return nullptr;
    for (std::size_t k = 0; k < keys.size(); ++k)
      if (keys[k] == key) return &items[k];
    return nullptr;
  }
};

// Parses a complete JSON text; throws std::runtime_error naming `name` and the offset.
Json parseJson(const std::string& text, const std::string& name = "json");

struct ManifestTable {
  std::string name;
  std::array<std::uint32_t, 4> dims{};
  std::string sampleType;  // "u8", "half" or "float" as described, may be empty
  std::vector<std::string> channels;
  std::string binFile;  // relative to the LUT directory, empty if absent
  std::string exrFile;
};

struct Manifest {
  int version = 0;
  std::string generator;
  std::vector<ManifestTable> tables;  // in document order
  Json document;
};

// Reads dir/manifest.json.
Manifest readManifest(const std::string& dir);

// ---------------------------------------------------------------------------------------------
// Implementation.

namespace detail {

[[noreturn]] inline void fail(const std::string& name, const std::string& problem) {
  throw std::runtime_error(name + ": " + problem);
}

// FNV-1a 64-bit of n bytes.
inline std::uint64_t fnv1a64(const std::uint8_t* p, std::size_t n) {
  std::uint64_t h = 14695981039346656037ull;
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
constexpr std::size_t kJsonOffset = 380;
constexpr std::size_t kMaxHeaderBytes = (16u << 20) + kMinHeaderBytes;

// Header size for a description of n bytes: 380 + n padded to a multiple of 8, + 8.
inline std::size_t headerBytesFor(std::size_t n) { return (kJsonOffset + n + 7) / 8 * 8 + 8; }

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
  if (version < 1 || version > 2)
    fail(name, "unsupported format version " + std::to_string(version) + " (this build reads 1 to 2)");
  const std::uint32_t headerBytes = le32(p + 12);
  if (headerBytes < kMinHeaderBytes || headerBytes > kMaxHeaderBytes || headerBytes % 8 != 0)
    fail(name, "corrupt header (header size " + std::to_string(headerBytes) + ")");
  if (headerBytes > fileBytes)
    fail(name, "truncated: expected a header of " + std::to_string(headerBytes) +
                   " bytes, found " + std::to_string(fileBytes));
  return headerBytes;
}

// Decodes a verified header into `lut` (everything but payload and values); returns the
// payload size and checksum the header promises.
inline void parseHeader(const std::uint8_t* p, std::size_t headerBytes, const std::string& name,
                        Lut& lut, std::uint64_t& payloadBytes, std::uint64_t& payloadChecksum) {
  if (fnv1a64(p, headerBytes - 8) != le(p + headerBytes - 8, 8))
    fail(name, "header checksum mismatch");
  const std::uint32_t version = le32(p + 8);
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
    axis.periodic = (le32(a + 40) & 1u) != 0;
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
  lut.description.assign(reinterpret_cast<const char*>(p + kJsonOffset), jsonBytes);
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

// Checks the payload's size and checksum, keeps it and decodes it into lut.values.
inline void takePayload(const std::uint8_t* p, std::uint64_t found, std::uint64_t payloadBytes,
                        std::uint64_t payloadChecksum, const std::string& name, Lut& lut) {
  checkPayloadSize(found, payloadBytes, name);
  const std::size_t n = static_cast<std::size_t>(payloadBytes);
  if (fnv1a64(p, n) != payloadChecksum) fail(name, "checksum mismatch");
  lut.payload.assign(p, p + n);
  const std::size_t count = n / lut.sampleBytes();
  lut.values.resize(count);
  for (std::size_t k = 0; k < count; ++k) {
    switch (lut.sampleType) {
      case SampleType::U8: lut.values[k] = static_cast<float>(p[k]) / 255.0f; break;
      case SampleType::Half:
        lut.values[k] = halfToFloat(static_cast<std::uint16_t>(le(p + 2 * k, 2)));
        break;
      case SampleType::Float: lut.values[k] = bitsToFloat(le32(p + 4 * k)); break;
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
  detail::takePayload(bytes.data() + headerBytes, bytes.size() - headerBytes, payloadBytes,
                      checksum, name, lut);
  return lut;
}

// Reads the header first and checks the payload size it claims against the real file size
// before reading (or allocating) the payload.
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
  const std::uint64_t found = fileBytes - headerBytes;
  detail::checkPayloadSize(found, payloadBytes, path);
  std::vector<std::uint8_t> payload(static_cast<std::size_t>(payloadBytes));
  in.read(reinterpret_cast<char*>(payload.data()), static_cast<std::streamsize>(payloadBytes));
  if (static_cast<std::uint64_t>(in.gcount()) != payloadBytes)
    detail::fail(path, "read error in the payload");
  detail::takePayload(payload.data(), found, payloadBytes, checksum, path, lut);
  return lut;
}

// The same arithmetic as the library's Table4D::sample, in the same order.
inline void Lut::sample(float x0, float x1, float x2, float x3, float* out) const {
  const float x[4] = {x0, x1, x2, x3};
  std::uint32_t i[4];
  float f[4];
  for (std::size_t k = 0; k < 4; ++k) {
    const std::uint32_t n = dims[k];
    const float p = std::min(std::max(x[k], 0.0f), 1.0f) * static_cast<float>(n - 1);
    i[k] = std::min(static_cast<std::uint32_t>(p), n >= 2 ? n - 2 : 0u);
    f[k] = n > 1 ? p - static_cast<float>(i[k]) : 0.0f;
  }
  const std::size_t C = channelCount();
  for (std::size_t c = 0; c < C; ++c) out[c] = 0.0f;
  for (int corner = 0; corner < 16; ++corner) {
    float w = 1.0f;
    std::uint32_t j[4] = {0, 0, 0, 0};
    for (std::size_t k = 0; k < 4; ++k) {
      const bool hi = ((corner >> k) & 1) != 0;
      if (hi && dims[k] < 2) {
        w = 0.0f;
        break;
      }
      j[k] = i[k] + (hi ? 1u : 0u);
      w *= hi ? f[k] : 1.0f - f[k];
    }
    if (w == 0.0f) continue;
    const std::size_t base = index(j[0], j[1], j[2], j[3]) * C;
    for (std::size_t c = 0; c < C; ++c) out[c] += w * values[base + c];
  }
}

namespace detail {

// A recursive-descent JSON parser with a nesting limit.
class JsonParser {
 public:
  JsonParser(const std::string& text, const std::string& name) : s_(text), name_(name) {}

  Json document() {
    Json v = value(0);
    skipSpace();
    if (pos_ != s_.size()) error("trailing characters");
    return v;
  }

 private:
  [[noreturn]] void error(const std::string& what) const {
    fail(name_, "invalid JSON at offset " + std::to_string(pos_) + " (" + what + ")");
  }
  void skipSpace() {
    while (pos_ < s_.size() &&
           (s_[pos_] == ' ' || s_[pos_] == '\t' || s_[pos_] == '\n' || s_[pos_] == '\r'))
      ++pos_;
  }
  bool consume(const char* word) {
    const std::size_t n = std::strlen(word);
    if (s_.compare(pos_, n, word) != 0) return false;
    pos_ += n;
    return true;
  }
  Json value(int depth) {
    if (depth > 64) error("nested too deeply");
    skipSpace();
    if (pos_ >= s_.size()) error("unexpected end");
    Json v;
    const char c = s_[pos_];
    if (c == '{') {
      v.type = Json::Type::Object;
      ++pos_;
      skipSpace();
      if (pos_ < s_.size() && s_[pos_] == '}') {
        ++pos_;
        return v;
      }
      for (;;) {
        skipSpace();
        if (pos_ >= s_.size() || s_[pos_] != '"') error("expected a key");
        v.keys.push_back(string());
        skipSpace();
        if (pos_ >= s_.size() || s_[pos_] != ':') error("expected ':'");
        ++pos_;
        v.items.push_back(value(depth + 1));
        skipSpace();
        if (pos_ < s_.size() && s_[pos_] == ',') { ++pos_; continue; }
        if (pos_ < s_.size() && s_[pos_] == '}') { ++pos_; return v; }
        error("expected ',' or '}'");
      }
    }
    if (c == '[') {
      v.type = Json::Type::Array;
      ++pos_;
      skipSpace();
      if (pos_ < s_.size() && s_[pos_] == ']') {
        ++pos_;
        return v;
      }
      for (;;) {
        v.items.push_back(value(depth + 1));
        skipSpace();
        if (pos_ < s_.size() && s_[pos_] == ',') { ++pos_; continue; }
        if (pos_ < s_.size() && s_[pos_] == ']') { ++pos_; return v; }
        error("expected ',' or ']'");
      }
    }
    if (c == '"') {
      v.type = Json::Type::String;
      v.string = string();
      return v;
    }
    if (consume("true")) { v.type = Json::Type::Bool; v.boolean = true; return v; }
    if (consume("false")) { v.type = Json::Type::Bool; return v; }
    if (consume("null")) return v;
    v.type = Json::Type::Number;
    v.number = number();
    return v;
  }
  // A number per the JSON grammar, converted with strtod.
  double number() {
    const std::size_t start = pos_;
    if (pos_ < s_.size() && s_[pos_] == '-') ++pos_;
    const std::size_t digits = pos_;
    while (pos_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[pos_]))) ++pos_;
    if (pos_ == digits) error("expected a value");
    if (pos_ < s_.size() && s_[pos_] == '.') {
      ++pos_;
      while (pos_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[pos_]))) ++pos_;
    }
    if (pos_ < s_.size() && (s_[pos_] == 'e' || s_[pos_] == 'E')) {
      ++pos_;
      if (pos_ < s_.size() && (s_[pos_] == '+' || s_[pos_] == '-')) ++pos_;
      while (pos_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[pos_]))) ++pos_;
    }
    const std::string token = s_.substr(start, pos_ - start);
    return std::strtod(token.c_str(), nullptr);
  }
  // Four hex digits of a \u escape.
  std::uint32_t hex4() {
    if (pos_ + 4 > s_.size()) error("short \\u escape");
    std::uint32_t v = 0;
    for (int k = 0; k < 4; ++k) {
      const char c = s_[pos_++];
      v <<= 4;
      if (c >= '0' && c <= '9') v |= static_cast<std::uint32_t>(c - '0');
      else if (c >= 'a' && c <= 'f') v |= static_cast<std::uint32_t>(c - 'a' + 10);
      else if (c >= 'A' && c <= 'F') v |= static_cast<std::uint32_t>(c - 'A' + 10);
      else error("bad \\u escape");
    }
    return v;
  }
  static void appendUtf8(std::string& out, std::uint32_t cp) {
    if (cp < 0x80) {
      out += static_cast<char>(cp);
    } else if (cp < 0x800) {
      out += static_cast<char>(0xc0 | (cp >> 6));
      out += static_cast<char>(0x80 | (cp & 0x3f));
    } else if (cp < 0x10000) {
      out += static_cast<char>(0xe0 | (cp >> 12));
      out += static_cast<char>(0x80 | ((cp >> 6) & 0x3f));
      out += static_cast<char>(0x80 | (cp & 0x3f));
    } else {
      out += static_cast<char>(0xf0 | (cp >> 18));
      out += static_cast<char>(0x80 | ((cp >> 12) & 0x3f));
      out += static_cast<char>(0x80 | ((cp >> 6) & 0x3f));
      out += static_cast<char>(0x80 | (cp & 0x3f));
    }
  }
  // A string starting at the opening quote, escapes resolved, UTF-8 kept as is.
  std::string string() {
    ++pos_;
    std::string out;
    for (;;) {
      if (pos_ >= s_.size()) error("unterminated string");
      const char c = s_[pos_++];
      if (c == '"') return out;
      if (static_cast<unsigned char>(c) < 0x20) error("control character in a string");
      if (c != '\\') {
        out += c;
        continue;
      }
      if (pos_ >= s_.size()) error("unterminated string");
      const char e = s_[pos_++];
      switch (e) {
        case '"': out += '"'; break;
        case '\\': out += '\\'; break;
        case '/': out += '/'; break;
        case 'b': out += '\b'; break;
        case 'f': out += '\f'; break;
        case 'n': out += '\n'; break;
        case 'r': out += '\r'; break;
        case 't': out += '\t'; break;
        case 'u': {
          std::uint32_t cp = hex4();
          if (cp >= 0xd800 && cp < 0xdc00 && s_.compare(pos_, 2, "\\u") == 0) {
            pos_ += 2;
            const std::uint32_t low = hex4();
            if (low < 0xdc00 || low > 0xdfff) error("bad surrogate pair");
            cp = 0x10000 + ((cp - 0xd800) << 10) + (low - 0xdc00);
          }
          appendUtf8(out, cp);
          break;
        }
        default: error("bad escape");
      }
    }
  }

  const std::string& s_;
  const std::string& name_;
  std::size_t pos_ = 0;
};

}  // namespace detail

inline Json parseJson(const std::string& text, const std::string& name) {
  return detail::JsonParser(text, name).document();
}

// Reads dir/manifest.json, checks its format and version, and lists its tables.
inline Manifest readManifest(const std::string& dir) {
  const std::string path = (dir.empty() ? std::string(".") : dir) + "/manifest.json";
  std::ifstream in(path, std::ios::binary);
  if (!in) detail::fail(path, "missing or unreadable");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  Manifest m;
  m.document = parseJson(text, path);
  const Json* format = m.document.find("format");
  if (format == nullptr || format->type != Json::Type::String || format->string != "cloudlut-lut-set")
    detail::fail(path, "not a cloudlut manifest (\"format\" is not \"cloudlut-lut-set\")");
  const Json* version = m.document.find("version");
  if (version == nullptr || version->type != Json::Type::Number)
    detail::fail(path, "manifest has no \"version\"");
  if (version->number != 1.0 && version->number != 2.0)
    detail::fail(path, "unsupported manifest version " + std::to_string(version->number) +
                           " (this reader reads 1 to 2)");
  m.version = static_cast<int>(version->number);
  if (const Json* g = m.document.find("generator"); g && g->type == Json::Type::String)
    m.generator = g->string;
  const Json* tables = m.document.find("tables");
  if (tables == nullptr || tables->type != Json::Type::Object)
    detail::fail(path, "manifest has no \"tables\" object");
  for (std::size_t k = 0; k < tables->keys.size(); ++k) {
    const Json& entry = tables->items[k];
    ManifestTable t;
    t.name = tables->keys[k];
    const Json* dims = entry.find("dims");
    if (dims == nullptr || dims->type != Json::Type::Array || dims->items.size() != 4)
      detail::fail(path, "table '" + t.name + "' has no \"dims\"");
    for (std::size_t d = 0; d < 4; ++d) {
      const double n = dims->items[d].number;
      if (dims->items[d].type != Json::Type::Number || !(n >= 1.0) || n > 4294967295.0)
        detail::fail(path, "table '" + t.name + "' has bad \"dims\"");
      t.dims[d] = static_cast<std::uint32_t>(n);
    }
    if (const Json* s = entry.find("sample_type"); s && s->type == Json::Type::String)
      t.sampleType = s->string;
    if (const Json* channels = entry.find("channels"); channels && channels->type == Json::Type::Array)
      for (const Json& c : channels->items)
        if (const Json* n = c.find("name"); n && n->type == Json::Type::String)
          t.channels.push_back(n->string);
    const Json* files = entry.find("files");
    if (files == nullptr || files->type != Json::Type::Object)
      detail::fail(path, "table '" + t.name + "' has no \"files\" object");
    if (const Json* b = files->find("bin"); b && b->type == Json::Type::String) t.binFile = b->string;
    if (const Json* e = files->find("exr"); e && e->type == Json::Type::String) t.exrFile = e->string;
    if (t.binFile.empty() && t.exrFile.empty())
      detail::fail(path, "table '" + t.name + "' lists no file");
    m.tables.push_back(std::move(t));
  }
  return m;
}

}  // namespace cloudlut_reader

#endif  // CLOUDLUT_READER_H
