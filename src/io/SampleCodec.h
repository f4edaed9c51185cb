#pragma once
// Encoding table values as stored samples (u8 unorm, half, float; little-endian) and back.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "io/LutIo.h"

namespace cloudlut::io {

// Bytes one stored sample of this type occupies: 1, 2 or 4.
std::size_t sampleBytes(SampleType type);

// The 8-bit code of v: clamp(v, 0, 1) · 255 rounded to nearest; NaN encodes as 0.
std::uint8_t encodeU8(float v);

// The stored bytes of `count` values, in the order given, as `type` (little-endian).
std::string encodeSamples(const float* values, std::size_t count, SampleType type);

// Decodes bytes.size() / sampleBytes(type) samples into `out` (u8 → code / 255, half and float
// exactly). The caller has checked that the size is a whole number of samples.
void decodeSamples(std::string_view bytes, SampleType type, float* out);

// The payload of the binary format: the table's values in Table4D layout, encoded as `type`.
std::string encodePayload(const Table4D& table, SampleType type);

}  // namespace cloudlut::io
