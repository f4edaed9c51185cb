// The EXR atlas format: the 3D texture's depth slices laid out as tiles of one 2D image
// (layout and attributes: lut_formats/FORMAT.md).
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <cstring>

#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <Imath/half.h>

#include <climits>
#include <fstream>
#include <vector>

#include "core/Errors.h"
#include "io/Fnv1a.h"
#include "io/LutReaders.h"
#include "io/MemoryStreams.h"
#include "io/SampleCodec.h"
#include "io/TableDescription.h"

namespace cloudlut::io {

namespace {

constexpr int kExrFormatVersion = 1;
constexpr const char* kChannelNames[4] = {"R", "G", "B", "A"};

// Position in the interleaved atlas (x = i2·N0 + i0, y = i3·N1 + i1) of node (i0, i1, i2, i3),
// in units of pixels.
std::size_t atlasPixel(const std::array<int, 4>& d, int i0, int i1, int i2, int i3) {
  const std::size_t width = static_cast<std::size_t>(d[0]) * d[2];
  return (static_cast<std::size_t>(i3) * d[1] + i1) * width + static_cast<std::size_t>(i2) * d[0] +
         i0;
}

// Calls f(node, pixel) for every node of the table and its atlas pixel.
template <typename F>
void forEachNode(const std::array<int, 4>& d, F&& f) {
  std::size_t node = 0;
  for (int i3 = 0; i3 < d[3]; ++i3)
    for (int i2 = 0; i2 < d[2]; ++i2)
      for (int i1 = 0; i1 < d[1]; ++i1)
        for (int i0 = 0; i0 < d[0]; ++i0) f(node++, atlasPixel(d, i0, i1, i2, i3));
}

// Fills an interleaved atlas of element type T (half or float) and writes the EXR to `os`.
template <typename T>
void encodeAtlas(const Table4D& table, Imf::PixelType pixelType, Imf::Header& header,
                 Imf::OStream& os) {
  const auto d = table.dims();
  const int C = table.channelCount();
  const int width = d[0] * d[2];
  const int height = d[1] * d[3];
  std::vector<T> atlas(static_cast<std::size_t>(width) * height * C);
  forEachNode(d, [&](std::size_t node, std::size_t pixel) {
    for (int c = 0; c < C; ++c) atlas[pixel * C + c] = T(table.at(node, c));
  });
  Imf::FrameBuffer frame;
  const std::size_t xStride = sizeof(T) * C;
  for (int c = 0; c < C; ++c)
    frame.insert(kChannelNames[c],
                 Imf::Slice(pixelType, reinterpret_cast<char*>(atlas.data() + c), xStride,
                            xStride * width));
  Imf::OutputFile out(os, header);
  out.setFrameBuffer(frame);
  out.writePixels(height);
}

// The whole file as bytes; its size was checked by the caller against nothing but the disk.
std::string readWholeFile(const std::filesystem::path& path, std::uint64_t size) {
  std::ifstream in(path, std::ios::binary);
  std::string bytes(static_cast<std::size_t>(size), '\0');
  if (!in.read(bytes.data(), static_cast<std::streamsize>(size)))
    throw FileError(path.string(), "cannot be read");
  return bytes;
}

}  // namespace

// Checks that the table fits an EXR image, encodes the atlas in memory with lossless ZIP
// compression and the "cloudlut" / "cloudlutVersion" attributes, and writes it atomically.
void writeExrLut(const Table4D& table, SampleType type, const std::filesystem::path& path) {
  if (type == SampleType::U8)
    throw UsageError("EXR cannot store 8-bit samples; use --format bin or --precision half|float");
  if (table.channelCount() < 1 || table.channelCount() > 4)
    throw UsageError("EXR stores 1 to 4 channels, table '" + table.name() + "' has " +
                     std::to_string(table.channelCount()));
  const auto d = table.dims();
  const long long width = static_cast<long long>(d[0]) * d[2];
  const long long height = static_cast<long long>(d[1]) * d[3];
  if (width > INT_MAX / 4 || height > INT_MAX / 4)
    throw UsageError("table '" + table.name() + "' is too large for an EXR atlas");

  const std::string payload = encodePayload(table, type);
  const nlohmann::json description =
      describeTableWith(table, type, payload.size(), fnv1a64(payload));
  const Imf::PixelType pixelType = type == SampleType::Half ? Imf::HALF : Imf::FLOAT;
  Imf::Header header(static_cast<int>(width), static_cast<int>(height));
  header.compression() = Imf::ZIP_COMPRESSION;
  for (int c = 0; c < table.channelCount(); ++c)
    header.channels().insert(kChannelNames[c], Imf::Channel(pixelType));
  header.insert("cloudlut", Imf::StringAttribute(description.dump()));
  header.insert("cloudlutVersion", Imf::IntAttribute(kExrFormatVersion));

  MemoryOStream os(path.string());
  try {
    if (type == SampleType::Half) encodeAtlas<Imath::half>(table, pixelType, header, os);
    else encodeAtlas<float>(table, pixelType, header, os);
  } catch (const std::exception& e) {
    throw UsageError("cannot encode EXR '" + path.string() + "': " + e.what());
  }
  writeFileAtomically(path, os.bytes());
}

namespace {

// Largest atlas side and area a LUT can have (the default optical-depth atlas is 4096×1024).
// Checked on the header alone, before OpenEXR sizes its line-offset table and buffers from a
// possibly corrupt data window: a 774-byte file must not make the reader allocate gigabytes.
constexpr long long kMaxAtlasSide = 1 << 16;
constexpr long long kMaxAtlasPixels = 1LL << 30;

// Walks the attribute list of a single-part EXR header (name\0 type\0 int32 size, value;
// an empty name ends it) and rejects any attribute whose declared size exceeds the bytes left:
// OpenEXR would allocate that size before finding the file short.
void checkAttributeSizes(const std::string& name, const std::string& bytes) {
  if (bytes.size() < 8) throw FileError(name, "not a readable EXR file (too short)");
  std::uint32_t flags = 0;
  std::memcpy(&flags, bytes.data() + 4, sizeof flags);
  if (flags & 0x1000u) throw FileError(name, "not a cloudlut LUT (multi-part EXR)");
  std::size_t pos = 8;
  auto readString = [&](const char* what) {
    const std::size_t end = bytes.find('\0', pos);
    if (end == std::string::npos || end - pos > 255)
      throw FileError(name, std::string("not a readable EXR file (corrupt header: attribute ") + what + ")");
    std::string text = bytes.substr(pos, end - pos);
    pos = end + 1;
    return text;
  };
  for (int attributes = 0; attributes < 10000; ++attributes) {
    if (readString("name").empty()) return;
    readString("type");
    if (bytes.size() - pos < 4) throw FileError(name, "not a readable EXR file (corrupt header: truncated)");
    std::int32_t size = 0;
    std::memcpy(&size, bytes.data() + pos, sizeof size);
    pos += 4;
    if (size < 0 || static_cast<std::size_t>(size) > bytes.size() - pos)
      throw FileError(name, "not a readable EXR file (corrupt header: an attribute claims " + std::to_string(size) +
                                " bytes, " + std::to_string(bytes.size() - pos) + " remain)");
    pos += static_cast<std::size_t>(size);
  }
  throw FileError(name, "not a readable EXR file (corrupt header: too many attributes)");
}

void checkHeaderBeforeDecoding(const std::string& name, const std::string& bytes) {
  checkAttributeSizes(name, bytes);
  MemoryIStream probe(name, bytes);
  char magicAndVersion[8];
  probe.read(magicAndVersion, 8);
  int version = 0;
  std::memcpy(&version, magicAndVersion + 4, sizeof version);  // little-endian on every supported host
  Imf::Header header;
  header.readFrom(probe, version);
  const Imath::Box2i w = header.dataWindow();
  const long long width = static_cast<long long>(w.max.x) - w.min.x + 1;
  const long long height = static_cast<long long>(w.max.y) - w.min.y + 1;
  if (width < 1 || height < 1 || width > kMaxAtlasSide || height > kMaxAtlasSide || width * height > kMaxAtlasPixels)
    throw FileError(name, "not a cloudlut LUT (EXR data window " + std::to_string(width) + "x" +
                              std::to_string(height) + " is outside any LUT atlas)");
}

// Decodes an EXR held in memory; OpenEXR's exceptions pass through to the caller.
LoadedTable decodeExr(const std::filesystem::path& path, const std::string& bytes) {
  const std::string name = path.string();
  checkHeaderBeforeDecoding(name, bytes);
  MemoryIStream is(name, bytes);
  Imf::InputFile file(is);
  const Imf::Header& header = file.header();
  const auto* attribute = header.findTypedAttribute<Imf::StringAttribute>("cloudlut");
  const auto* version = header.findTypedAttribute<Imf::IntAttribute>("cloudlutVersion");
  if (attribute == nullptr || version == nullptr)
    throw FileError(name, "not a cloudlut LUT (EXR without the \"cloudlut\" attributes)");
  if (version->value() != kExrFormatVersion)
    throw FileError(name, "unsupported format version " + std::to_string(version->value()) +
                              " (this build reads " + std::to_string(kExrFormatVersion) + ")");
  const nlohmann::json description = nlohmann::json::parse(attribute->value(), nullptr, false);
  if (description.is_discarded() || !description.is_object())
    throw FileError(name, "corrupt \"cloudlut\" attribute (not a JSON object)");

  Table4D table = tableFromDescription(description, path);  // checks the size it claims
  const auto d = table.dims();
  const int C = table.channelCount();
  const long long width = static_cast<long long>(d[0]) * d[2];
  const long long height = static_cast<long long>(d[1]) * d[3];
  const Imath::Box2i window = header.dataWindow();
  if (static_cast<long long>(window.max.x) - window.min.x + 1 != width ||
      static_cast<long long>(window.max.y) - window.min.y + 1 != height)
    throw FileError(name, "the image size does not match the dimensions in its description");

  std::optional<Imf::PixelType> pixelType;
  for (int c = 0; c < C; ++c) {
    const Imf::Channel* channel = header.channels().findChannel(kChannelNames[c]);
    if (channel == nullptr)
      throw FileError(name, std::string("channel ") + kChannelNames[c] + " is missing");
    if (channel->xSampling != 1 || channel->ySampling != 1 ||
        (channel->type != Imf::HALF && channel->type != Imf::FLOAT) ||
        (pixelType && *pixelType != channel->type))
      throw FileError(name, std::string("channel ") + kChannelNames[c] +
                                " is not full-resolution half or float like the others");
    pixelType = channel->type;
  }
  const SampleType type = *pixelType == Imf::HALF ? SampleType::Half : SampleType::Float;
  if (!description.contains("sample_type") || !description["sample_type"].is_string() ||
      description["sample_type"].get<std::string>() != toString(type))
    throw FileError(name, "the description's sample type does not match the channels");
  std::uint64_t expected = 0;
  if (!description.contains("payload_fnv1a64") || !description["payload_fnv1a64"].is_string() ||
      !parseChecksumHex(description["payload_fnv1a64"].get<std::string>(), expected))
    throw FileError(name, "the description lacks its checksum");

  std::vector<float> atlas(static_cast<std::size_t>(width) * height * C);
  Imf::FrameBuffer frame;
  const std::size_t xStride = sizeof(float) * C;
  for (int c = 0; c < C; ++c)
    frame.insert(kChannelNames[c], Imf::Slice::Make(Imf::FLOAT, atlas.data() + c, window, xStride,
                                                    xStride * static_cast<std::size_t>(width)));
  file.setFrameBuffer(frame);
  file.readPixels(window.min.y, window.max.y);

  forEachNode(d, [&](std::size_t node, std::size_t pixel) {
    for (int c = 0; c < C; ++c) table.at(node, c) = atlas[pixel * C + c];
  });
  if (fnv1a64(encodePayload(table, type)) != expected) throw FileError(name, "checksum mismatch");
  return LoadedTable{std::move(table), type, true, path};
}

}  // namespace

// Reads the file into memory (its size is real, so nothing is allocated on a header's word),
// decodes it, and turns any OpenEXR exception into FileError.
LoadedTable readExrLut(const std::filesystem::path& path) {
  const std::string bytes = readWholeFile(path, existingFileSize(path));
  try {
    return decodeExr(path, bytes);
  } catch (const FileError&) {
    throw;
  } catch (const std::exception& e) {
    throw FileError(path.string(), std::string("not a readable EXR file (") + e.what() + ")");
  }
}

}  // namespace cloudlut::io
