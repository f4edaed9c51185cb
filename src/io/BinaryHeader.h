#pragma once
// The header of the binary LUT format (byte layout: lut_formats/FORMAT.md).
#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "io/LutIo.h"

namespace cloudlut::io::binary {

inline constexpr char kMagic[8] = {'C', 'L', 'O', 'U', 'D', 'L', 'U', 'T'};
// Version 2 stores each axis's node concentration (Axis::warp) as a float32 in the axis
// record's last 4 bytes (zero, "reserved", in version 1, which is still read).
inline constexpr std::uint32_t kVersion = kFormatVersion;
inline constexpr std::uint32_t kOldestVersion = kOldestFormatVersion;

// Field sizes and offsets, in bytes from the start of the file.
inline constexpr std::size_t kTableNameBytes = 32;
inline constexpr std::size_t kAxisNameBytes = 16;
inline constexpr std::size_t kAxisUnitBytes = 8;
inline constexpr std::size_t kAxisRecordBytes = 48;  // name, unit, min, max, flags, warp
inline constexpr std::size_t kChannelNameBytes = 24;
inline constexpr std::size_t kMaxChannels = 4;
inline constexpr std::size_t kPrefixBytes = 16;       // magic, version, header size
inline constexpr std::size_t kAxesOffset = 88;
inline constexpr std::size_t kChannelsOffset = 280;
inline constexpr std::size_t kJsonLengthOffset = 376;
inline constexpr std::size_t kJsonOffset = 380;
inline constexpr std::size_t kMinHeaderBytes = 392;   // no JSON: 380 → padded 384, + checksum
inline constexpr std::size_t kMaxJsonBytes = 16u << 20;  // sanity bound for readers
inline constexpr std::uint32_t kAxisPeriodic = 1u;
inline constexpr std::uint32_t kAxisFolded = 2u;        // version 3: Axis::folded
inline constexpr std::uint32_t kAxisLinearInExp2 = 4u;  // version 3: Axis::linearInExp2
// The flag bits a reader of each version accepts (others: corrupt header).
inline constexpr std::uint32_t axisFlagsOf(std::uint32_t version) {
  return version >= 3 ? kAxisPeriodic | kAxisFolded | kAxisLinearInExp2 : kAxisPeriodic;
}
inline constexpr float kMaxAxisWarp = 20.0f;  // readers reject larger node concentrations

// The header size for a JSON text of `jsonBytes` bytes: 380 + JSON, padded with zero bytes
// to a multiple of 8, plus the 8-byte header checksum.
std::size_t headerBytesFor(std::size_t jsonBytes);

struct AxisRecord {
  std::string name, unit;
  double min = 0.0, max = 1.0;
  std::uint32_t flags = 0;
  float warp = 0.0f;
};

// The decoded header fields.
struct Header {
  std::uint32_t version = kVersion;
  std::uint32_t headerBytes = 0;
  std::array<std::uint32_t, 4> dims{};
  std::uint32_t channelCount = 0;
  SampleType sampleType = SampleType::Float;
  std::uint64_t payloadBytes = 0;
  std::uint64_t payloadChecksum = 0;
  std::string tableName;
  std::array<AxisRecord, 4> axes;
  std::vector<std::string> channelNames;
  std::string json;  // the table's description (describeTable); may be empty
};

// The complete header bytes of `table` stored as `type`, for a payload of the given size and
// checksum. Throws UsageError if a name does not fit its field or the channel count is not 1–4.
std::string encodeHeader(const Table4D& table, SampleType type, std::uint64_t payloadBytes,
                         std::uint64_t payloadChecksum);

// Version and header size from the first 16 bytes; the caller has checked the magic.
void parsePrefix(std::string_view prefix, std::uint32_t& version, std::uint32_t& headerBytes);

// Decodes and validates a complete header (its checksum, field ranges, NUL-terminated names,
// payload size consistent with dims, channels and sample type). Throws FileError(path, ...).
Header parseHeader(std::string_view bytes, const std::filesystem::path& path);

}  // namespace cloudlut::io::binary
