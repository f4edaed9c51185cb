// The binary LUT format: writer and reader (layout: lut_formats/FORMAT.md).
#include <fstream>

#include "core/Errors.h"
#include "io/BinaryHeader.h"
#include "io/Fnv1a.h"
#include "io/LutReaders.h"
#include "io/SampleCodec.h"
#include "io/TableDescription.h"

namespace cloudlut::io {

// Encodes the payload, then the header that describes and checksums it, and writes both
// through writeFileAtomically.
void writeBinaryLut(const Table4D& table, SampleType type, const std::filesystem::path& path) {
  const std::string payload = encodePayload(table, type);
  std::string bytes = binary::encodeHeader(table, type, payload.size(), fnv1a64(payload));
  bytes += payload;
  writeFileAtomically(path, bytes);
}

namespace {

// Reads `count` bytes at the stream's position; false if fewer were available.
bool readBytes(std::ifstream& in, std::string& out, std::uint64_t count) {
  out.resize(static_cast<std::size_t>(count));
  in.read(out.data(), static_cast<std::streamsize>(count));
  return static_cast<std::uint64_t>(in.gcount()) == count;
}

// Fills channel meanings and `parameters` from the header's JSON description, when it has them.
void applyDescription(const binary::Header& h, std::vector<Channel>& channels,
                      nlohmann::json& parameters, const std::filesystem::path& path) {
  if (h.json.empty()) return;
  const nlohmann::json d = nlohmann::json::parse(h.json, nullptr, false);
  if (d.is_discarded() || !d.is_object())
    throw FileError(path.string(), "corrupt header (table description is not valid JSON)");
  if (d.contains("parameters") && d["parameters"].is_object()) parameters = d["parameters"];
  if (!d.contains("channels") || !d["channels"].is_array()) return;
  const nlohmann::json& described = d["channels"];
  if (described.size() != channels.size()) return;
  for (std::size_t c = 0; c < channels.size(); ++c)
    if (described[c].is_object() && described[c].contains("meaning") &&
        described[c]["meaning"].is_string())
      channels[c].meaning = described[c]["meaning"].get<std::string>();
}

}  // namespace

// Checks, in order: magic, version, header size against the file size, header checksum and
// fields, payload size against the file size (before allocating it), payload checksum; then
// decodes the samples to float.
LoadedTable readBinaryLut(const std::filesystem::path& path) {
  const std::string name = path.string();
  const std::uint64_t fileBytes = existingFileSize(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw FileError(name, "cannot be opened");

  std::string prefix;
  if (!readBytes(in, prefix, binary::kPrefixBytes))
    throw FileError(name, "truncated: expected a header of at least " +
                              std::to_string(binary::kMinHeaderBytes) + " bytes, found " +
                              std::to_string(fileBytes));
  if (prefix.compare(0, 8, std::string_view(binary::kMagic, 8)) != 0)
    throw FileError(name, "not a cloudlut LUT (bad magic)");
  std::uint32_t version = 0, headerBytes = 0;
  binary::parsePrefix(prefix, version, headerBytes);
  if (version < binary::kOldestVersion || version > binary::kVersion)
    throw FileError(name, "unsupported format version " + std::to_string(version) +
                              " (this build reads " + std::to_string(binary::kOldestVersion) + " to " +
                              std::to_string(binary::kVersion) + ")");
  if (headerBytes < binary::kMinHeaderBytes ||
      headerBytes > binary::headerBytesFor(binary::kMaxJsonBytes) || headerBytes % 8 != 0)
    throw FileError(name, "corrupt header (header size " + std::to_string(headerBytes) + ")");
  if (headerBytes > fileBytes)
    throw FileError(name, "truncated: expected a header of " + std::to_string(headerBytes) +
                              " bytes, found " + std::to_string(fileBytes));
  std::string rest;
  if (!readBytes(in, rest, headerBytes - binary::kPrefixBytes))
    throw FileError(name, "read error in the header");
  const binary::Header h = binary::parseHeader(prefix + rest, path);

  const std::uint64_t found = fileBytes - headerBytes;
  if (found < h.payloadBytes)
    throw FileError(name, "truncated: expected " + std::to_string(h.payloadBytes) +
                              " bytes of payload, found " + std::to_string(found));
  if (found > h.payloadBytes)
    throw FileError(name, "corrupt: expected " + std::to_string(h.payloadBytes) +
                              " bytes of payload, found " + std::to_string(found));
  checkClaimedSize(h.dims, h.channelCount, path);

  std::string payload;
  if (!readBytes(in, payload, h.payloadBytes)) throw FileError(name, "read error in the payload");
  if (fnv1a64(payload) != h.payloadChecksum) throw FileError(name, "checksum mismatch");

  std::array<Axis, 4> axes;
  for (int k = 0; k < 4; ++k) {
    const binary::AxisRecord& r = h.axes[k];
    axes[k] = Axis{r.name, r.unit, r.min, r.max, static_cast<int>(h.dims[k]),
                   (r.flags & binary::kAxisPeriodic) != 0, static_cast<double>(r.warp),
                   (r.flags & binary::kAxisFolded) != 0, (r.flags & binary::kAxisLinearInExp2) != 0};
  }
  std::vector<Channel> channels;
  for (const std::string& c : h.channelNames) channels.push_back({c, ""});
  nlohmann::json parameters = nlohmann::json::object();
  applyDescription(h, channels, parameters, path);
  LoadedTable loaded{Table4D(h.tableName, axes, channels), h.sampleType, true, path};
  loaded.table.parameters() = std::move(parameters);
  decodeSamples(payload, h.sampleType, loaded.table.data().data());
  return loaded;
}

}  // namespace cloudlut::io
