// Sample types: their names, and the encoding of table values as stored samples.
#include "io/SampleCodec.h"

#include <Imath/half.h>

#include <bit>
#include <cmath>

#include "io/Fnv1a.h"
#include "io/LittleEndian.h"

namespace cloudlut::io {

std::optional<SampleType> parseSampleType(std::string_view name) {
  if (name == "u8") return SampleType::U8;
  if (name == "half") return SampleType::Half;
  if (name == "float") return SampleType::Float;
  return std::nullopt;
}

std::string toString(SampleType type) {
  switch (type) {
    case SampleType::U8: return "u8";
    case SampleType::Half: return "half";
    case SampleType::Float: return "float";
  }
  return "float";
}

std::uint64_t payloadChecksum(const Table4D& table, SampleType type) {
  return fnv1a64(encodePayload(table, type));
}

std::size_t sampleBytes(SampleType type) {
  switch (type) {
    case SampleType::U8: return 1;
    case SampleType::Half: return 2;
    case SampleType::Float: return 4;
  }
  return 4;
}

std::uint8_t encodeU8(float v) {
  if (!(v > 0.0f)) return 0;  // negative, zero and NaN
  if (v >= 1.0f) return 255;
  return static_cast<std::uint8_t>(std::lround(v * 255.0f));
}

std::string encodeSamples(const float* values, std::size_t count, SampleType type) {
  // Written in place, little-endian byte by byte (the table of 10⁷ samples is encoded for each
  // file and the manifest's checksum: appending per byte cost 8% of an optical-depth bake).
  const std::size_t size = sampleBytes(type);
  std::string out(count * size, '\0');
  unsigned char* p = reinterpret_cast<unsigned char*>(out.data());
  for (std::size_t k = 0; k < count; ++k, p += size) {
    std::uint32_t bits = 0;
    switch (type) {
      case SampleType::U8: bits = encodeU8(values[k]); break;
      case SampleType::Half: bits = Imath::half(values[k]).bits(); break;
      case SampleType::Float: bits = std::bit_cast<std::uint32_t>(values[k]); break;
    }
    for (std::size_t b = 0; b < size; ++b) p[b] = static_cast<unsigned char>(bits >> (8 * b));
  }
  return out;
}

void decodeSamples(std::string_view bytes, SampleType type, float* out) {
  const std::size_t size = sampleBytes(type);
  const std::size_t count = bytes.size() / size;
  const char* p = bytes.data();
  for (std::size_t k = 0; k < count; ++k, p += size) {
    switch (type) {
      case SampleType::U8:
        out[k] = static_cast<float>(static_cast<unsigned char>(*p)) / 255.0f;
        break;
      case SampleType::Half: {
        Imath::half h;
        h.setBits(getU16(p));
        out[k] = static_cast<float>(h);
        break;
      }
      case SampleType::Float: out[k] = getF32(p); break;
    }
  }
}

std::string encodePayload(const Table4D& table, SampleType type) {
  return encodeSamples(table.data().data(), table.data().size(), type);
}

}  // namespace cloudlut::io
