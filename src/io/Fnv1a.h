#pragma once
// FNV-1a, 64-bit: the checksum of the binary LUT format's header and payload (FORMAT.md).
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace cloudlut::io {

inline constexpr std::uint64_t kFnv1aOffsetBasis = 14695981039346656037ull;
inline constexpr std::uint64_t kFnv1aPrime = 1099511628211ull;

// FNV-1a 64 of `bytes`, continuing from `hash` (start from the offset basis): for each byte,
// xor it into the hash, then multiply by the FNV prime modulo 2^64.
inline std::uint64_t fnv1a64(std::string_view bytes, std::uint64_t hash = kFnv1aOffsetBasis) {
  for (const char c : bytes) {
    hash ^= static_cast<unsigned char>(c);
    hash *= kFnv1aPrime;
  }
  return hash;
}

}  // namespace cloudlut::io
