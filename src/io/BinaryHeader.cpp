#include "io/BinaryHeader.h"

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "core/Errors.h"
#include "io/Fnv1a.h"
#include "io/LittleEndian.h"
#include "io/SampleCodec.h"
#include "io/TableDescription.h"

namespace cloudlut::io::binary {

std::size_t headerBytesFor(std::size_t jsonBytes) {
  return (kJsonOffset + jsonBytes + 7) / 8 * 8 + 8;
}

namespace {

// Throws UsageError unless `text` fits a NUL-padded field of `size` bytes with a NUL to spare.
void checkFits(const std::string& text, std::size_t size, const std::string& what) {
  if (text.size() >= size)
    throw UsageError(what + " '" + text + "' is longer than the binary format's " +
                     std::to_string(size - 1) + " bytes");
  if (text.find('\0') != std::string::npos)
    throw UsageError(what + " '" + text + "' contains a NUL byte");
}

// The text of a NUL-padded field, or false if the field holds no NUL.
bool readFixedString(const char* p, std::size_t size, std::string& out) {
  const void* nul = std::memchr(p, 0, size);
  if (nul == nullptr) return false;
  out.assign(p, static_cast<const char*>(nul));
  return true;
}

}  // namespace

std::string encodeHeader(const Table4D& table, SampleType type, std::uint64_t payloadBytes,
                         std::uint64_t payloadChecksum) {
  const auto& channels = table.channels();
  if (channels.empty() || channels.size() > kMaxChannels)
    throw UsageError("the binary format stores 1 to 4 channels, table '" + table.name() +
                     "' has " + std::to_string(channels.size()));
  checkFits(table.name(), kTableNameBytes, "table name");
  for (const Axis& a : table.axes()) {
    checkFits(a.name, kAxisNameBytes, "axis name");
    checkFits(a.unit, kAxisUnitBytes, "axis unit");
  }
  for (const Channel& c : channels) checkFits(c.name, kChannelNameBytes, "channel name");

  const std::string json =
      describeTableWith(table, type, payloadBytes, payloadChecksum).dump();
  std::string h;
  h.reserve(headerBytesFor(json.size()));
  h.append(kMagic, sizeof kMagic);
  putU32(h, kVersion);
  putU32(h, static_cast<std::uint32_t>(headerBytesFor(json.size())));
  for (const int d : table.dims()) putU32(h, static_cast<std::uint32_t>(d));
  putU32(h, static_cast<std::uint32_t>(channels.size()));
  putU32(h, static_cast<std::uint32_t>(type));
  putU64(h, payloadBytes);
  putU64(h, payloadChecksum);
  putFixedString(h, table.name(), kTableNameBytes);
  for (const Axis& a : table.axes()) {
    putFixedString(h, a.name, kAxisNameBytes);
    putFixedString(h, a.unit, kAxisUnitBytes);
    putF64(h, a.min);
    putF64(h, a.max);
    putU32(h, (a.periodic ? kAxisPeriodic : 0u) | (a.folded ? kAxisFolded : 0u) |
                  (a.linearInExp2 ? kAxisLinearInExp2 : 0u));
    putU32(h, std::bit_cast<std::uint32_t>(static_cast<float>(a.warp)));
  }
  for (std::size_t c = 0; c < kMaxChannels; ++c)
    putFixedString(h, c < channels.size() ? channels[c].name : std::string(), kChannelNameBytes);
  putU32(h, static_cast<std::uint32_t>(json.size()));
  h += json;
  h.append(headerBytesFor(json.size()) - 8 - h.size(), '\0');
  putU64(h, fnv1a64(h));
  return h;
}

// Reads version (offset 8) and header size (offset 12).
void parsePrefix(std::string_view prefix, std::uint32_t& version, std::uint32_t& headerBytes) {
  version = getU32(prefix.data() + 8);
  headerBytes = getU32(prefix.data() + 12);
}

// Decodes every field and checks what a reader must be able to trust before it allocates.
Header parseHeader(std::string_view bytes, const std::filesystem::path& path) {
  const auto fail = [&](const std::string& problem) {
    throw FileError(path.string(), problem);
  };
  if (bytes.size() < kMinHeaderBytes) fail("corrupt header (too short)");
  const char* p = bytes.data();
  const std::uint64_t stored = getU64(p + bytes.size() - 8);
  if (fnv1a64(bytes.substr(0, bytes.size() - 8)) != stored) fail("header checksum mismatch");

  Header h;
  parsePrefix(bytes, h.version, h.headerBytes);
  for (int k = 0; k < 4; ++k) h.dims[k] = getU32(p + 16 + 4 * k);
  h.channelCount = getU32(p + 32);
  const std::uint32_t type = getU32(p + 36);
  h.payloadBytes = getU64(p + 40);
  h.payloadChecksum = getU64(p + 48);
  if (type > 2) fail("corrupt header (unknown sample type " + std::to_string(type) + ")");
  h.sampleType = static_cast<SampleType>(type);
  if (h.channelCount < 1 || h.channelCount > kMaxChannels)
    fail("corrupt header (" + std::to_string(h.channelCount) + " channels, expected 1 to 4)");
  if (!readFixedString(p + 56, kTableNameBytes, h.tableName)) fail("corrupt header (table name)");
  for (std::size_t k = 0; k < 4; ++k) {
    const char* a = p + kAxesOffset + k * kAxisRecordBytes;
    AxisRecord& r = h.axes[k];
    if (!readFixedString(a, kAxisNameBytes, r.name) ||
        !readFixedString(a + kAxisNameBytes, kAxisUnitBytes, r.unit))
      fail("corrupt header (axis " + std::to_string(k) + " name or unit)");
    r.min = getF64(a + 24);
    r.max = getF64(a + 32);
    r.flags = getU32(a + 40);
    r.warp = std::bit_cast<float>(getU32(a + 44));
    if (!std::isfinite(r.min) || !std::isfinite(r.max) || !(r.min <= r.max))
      fail("corrupt header (axis " + std::to_string(k) + " range [" + std::to_string(r.min) + ", " +
           std::to_string(r.max) + "] is not a finite interval)");
    if (!(r.warp >= 0.0f && r.warp <= kMaxAxisWarp) || (h.version < 2 && r.warp != 0.0f))
      fail("corrupt header (axis " + std::to_string(k) + " node concentration)");
    if ((r.flags & ~axisFlagsOf(h.version)) != 0)
      fail("corrupt header (axis " + std::to_string(k) + " has flag bits reserved in version " +
           std::to_string(h.version) + " set: " + std::to_string(r.flags) + "; see lut_formats/FORMAT.md)");
    if ((r.flags & kAxisPeriodic) && (r.flags & kAxisFolded))
      fail("corrupt header (axis " + std::to_string(k) + " is both periodic and folded: flags " +
           std::to_string(r.flags) + ")");
    if (h.dims[k] < 1) fail("corrupt header (axis " + std::to_string(k) + " has no nodes)");
  }
  for (std::size_t c = 0; c < h.channelCount; ++c) {
    std::string name;
    if (!readFixedString(p + kChannelsOffset + c * kChannelNameBytes, kChannelNameBytes, name))
      fail("corrupt header (channel " + std::to_string(c) + " name)");
    h.channelNames.push_back(name);
  }
  const std::uint32_t jsonBytes = getU32(p + kJsonLengthOffset);
  if (jsonBytes > bytes.size() || headerBytesFor(jsonBytes) > bytes.size())
    fail("corrupt header (description of " + std::to_string(jsonBytes) + " bytes)");
  h.json.assign(p + kJsonOffset, jsonBytes);

  // dims × channels × sample size, refusing anything that overflows 64 bits.
  std::uint64_t expected = sampleBytes(h.sampleType) * h.channelCount;
  bool overflow = false;
  for (const std::uint32_t d : h.dims) {
    if (expected > UINT64_MAX / d) overflow = true;
    else expected *= d;
  }
  if (overflow || expected != h.payloadBytes)
    fail("corrupt header (payload of " + std::to_string(h.payloadBytes) +
         " bytes does not match the dimensions, channels and sample type)");
  return h;
}

}  // namespace cloudlut::io::binary
