#pragma once
// Little-endian encoding of fixed-size integers and IEEE floats into byte strings, and back,
// independent of the host's byte order. The binary LUT format stores every number this way.
#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

namespace cloudlut::io {

// Appends the `bytes` least significant bytes of `value` to `out`, least significant first.
inline void putLe(std::string& out, std::uint64_t value, int bytes) {
  for (int k = 0; k < bytes; ++k) out.push_back(static_cast<char>((value >> (8 * k)) & 0xffu));
}

inline void putU16(std::string& out, std::uint16_t v) { putLe(out, v, 2); }
inline void putU32(std::string& out, std::uint32_t v) { putLe(out, v, 4); }
inline void putU64(std::string& out, std::uint64_t v) { putLe(out, v, 8); }
inline void putF32(std::string& out, float v) { putU32(out, std::bit_cast<std::uint32_t>(v)); }
inline void putF64(std::string& out, double v) { putU64(out, std::bit_cast<std::uint64_t>(v)); }

// Appends `text` in a field of exactly `size` bytes, padded with NUL bytes. The caller has
// checked that text.size() < size, so at least one NUL follows the text.
inline void putFixedString(std::string& out, std::string_view text, std::size_t size) {
  out.append(text.substr(0, size));
  out.append(size - std::min(text.size(), size), '\0');
}

// The unsigned integer stored little-endian in `bytes` bytes at `p`.
inline std::uint64_t getLe(const char* p, int bytes) {
  std::uint64_t v = 0;
  for (int k = 0; k < bytes; ++k)
    v |= static_cast<std::uint64_t>(static_cast<unsigned char>(p[k])) << (8 * k);
  return v;
}

inline std::uint16_t getU16(const char* p) { return static_cast<std::uint16_t>(getLe(p, 2)); }
inline std::uint32_t getU32(const char* p) { return static_cast<std::uint32_t>(getLe(p, 4)); }
inline std::uint64_t getU64(const char* p) { return getLe(p, 8); }
inline float getF32(const char* p) { return std::bit_cast<float>(getU32(p)); }
inline double getF64(const char* p) { return std::bit_cast<double>(getU64(p)); }

}  // namespace cloudlut::io
