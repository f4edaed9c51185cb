// The EXR atlas format: the 3D texture's depth slices laid out as tiles of one 2D image
// (layout and attributes: lut_formats/FORMAT.md).
#include <OpenEXR/ImfAttribute.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfCompression.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfLineOrder.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfPixelType.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <Imath/half.h>

#include <algorithm>
#include <climits>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string_view>
#include <vector>

#include "core/Errors.h"
#include "io/ExrBudget.h"
#include "io/Fnv1a.h"
#include "io/LutReaders.h"
#include "io/MemoryStreams.h"
#include "io/SampleCodec.h"
#include "io/TableDescription.h"

namespace cloudlut::io {

namespace {

constexpr const char* kChannelNames[4] = {"R", "G", "B", "A"};
constexpr int kMaxChannels = static_cast<int>(std::size(kChannelNames));

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
  header.insert("cloudlutVersion", Imf::IntAttribute(kFormatVersion));

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
// Longest string attribute, and longest "cloudlut" description (about 1 KB in practice), so
// that a large file cannot make the reader hold a large string either.
constexpr std::size_t kMaxStringBytes = 1 << 20;
constexpr std::size_t kMaxDescriptionBytes = 1 << 16;
// Longest attribute, type or channel name OpenEXR reads (Imf::Name::MAX_LENGTH).
constexpr std::size_t kMaxNameBytes = 255;

// Header validation, before OpenEXR parses anything. OpenEXR's header parser reads each
// attribute's declared size, but it parses the value of a type it knows by content: a fixed-size
// type reads its own size, a channel list reads entries up to its terminating NUL. A value whose
// content does not fill exactly its declared size shifts every later attribute, and OpenEXR then
// allocates whatever size the shifted bytes claim (up to 2 GiB) before it finds the file short.
// So each attribute of a type OpenEXR knows is checked here by content, within its declared size;
// a type it does not know is read as opaque bytes of the declared size, which must fit the file.

// One attribute as it sits in the header: the bytes its declared size covers.
struct HeaderAttribute {
  std::string name;
  std::string type;
  std::string_view value;
};

std::int32_t int32At(std::string_view bytes, std::size_t pos) {
  std::int32_t v = 0;
  std::memcpy(&v, bytes.data() + pos, sizeof v);  // little-endian on every supported host
  return v;
}

[[noreturn]] void corruptHeader(const std::string& file, const std::string& why) {
  throw FileError(file, "not a readable EXR file (corrupt header: " + why + ")");
}

// The data window and every other box2i: a window the size of a LUT atlas, no larger.
void checkWindow(const std::string& file, const HeaderAttribute& a, const ExrHeaderLimits& limits) {
  const long long width = static_cast<long long>(int32At(a.value, 8)) - int32At(a.value, 0) + 1;
  const long long height = static_cast<long long>(int32At(a.value, 12)) - int32At(a.value, 4) + 1;
  if (width < 1 || height < 1 || width > kMaxAtlasSide || height > kMaxAtlasSide || width * height > kMaxAtlasPixels)
    throw FileError(file, std::string("not a ") + limits.kind + " (EXR " + a.name + " " + std::to_string(width) + "x" +
                              std::to_string(height) + " is outside any LUT atlas)");
}

// chlist: 1 to 4 entries (the writer's R, G, B, A), each a name of 1 to 255 bytes and its NUL,
// int32 pixel type (UINT, HALF or FLOAT), uint8 pLinear, 3 reserved bytes, int32 x and y
// sampling (1: LUT channels are full resolution), then a NUL that must be the value's last byte.
void checkChannelList(const std::string& file, const HeaderAttribute& a, const ExrHeaderLimits& limits) {
  constexpr std::size_t kEntryFields = 16;
  std::size_t pos = 0;
  for (int channels = 0;; ++channels) {
    const std::size_t end = a.value.find('\0', pos);
    if (end == std::string_view::npos) corruptHeader(file, "channel list \"" + a.name + "\" is not terminated");
    if (end == pos) {
      if (channels == 0) corruptHeader(file, "channel list \"" + a.name + "\" is empty");
      if (end + 1 != a.value.size())
        corruptHeader(file, "channel list \"" + a.name + "\" ends " + std::to_string(a.value.size() - end - 1) +
                                " bytes before its declared size");
      return;
    }
    if (end - pos > kMaxNameBytes) corruptHeader(file, "channel name longer than 255 bytes");
    if (channels == static_cast<int>(limits.maxChannels))
      throw FileError(file, std::string("not a ") + limits.kind + " (more than " + std::to_string(limits.maxChannels) + " channels)");
    const std::string channel(a.value.substr(pos, end - pos));
    pos = end + 1;
    if (a.value.size() - pos < kEntryFields) corruptHeader(file, "channel " + channel + " runs past its list");
    const std::int32_t pixelType = int32At(a.value, pos);
    if (pixelType < Imf::UINT || pixelType > Imf::FLOAT)
      corruptHeader(file, "channel " + channel + " has pixel type " + std::to_string(pixelType));
    if (int32At(a.value, pos + 8) != 1 || int32At(a.value, pos + 12) != 1)
      throw FileError(file, std::string("not a ") + limits.kind + " (channel " + channel + " is subsampled)");
    pos += kEntryFields;
  }
}

void checkCompression(const std::string& file, const HeaderAttribute& a, const ExrHeaderLimits&) {
  if (static_cast<unsigned char>(a.value[0]) >= Imf::NUM_COMPRESSION_METHODS)
    corruptHeader(file, "unknown compression " + std::to_string(static_cast<unsigned char>(a.value[0])));
}

void checkLineOrder(const std::string& file, const HeaderAttribute& a, const ExrHeaderLimits&) {
  if (static_cast<unsigned char>(a.value[0]) >= Imf::NUM_LINEORDERS)
    corruptHeader(file, "unknown line order " + std::to_string(static_cast<unsigned char>(a.value[0])));
}

// OpenEXR reads a string attribute as exactly its declared size; only its length is bounded.
void checkString(const std::string& file, const HeaderAttribute& a, const ExrHeaderLimits&) {
  const std::size_t limit = a.name == "cloudlut" ? kMaxDescriptionBytes : kMaxStringBytes;
  if (a.value.size() > limit)
    corruptHeader(file, "string \"" + a.name + "\" of " + std::to_string(a.value.size()) + " bytes, more than " +
                            std::to_string(limit));
}

// What each accepted attribute type must be: its exact size (-1: any size) and a content check.
struct AttributeRule {
  const char* type;
  int size;
  void (*check)(const std::string& file, const HeaderAttribute& a, const ExrHeaderLimits& limits);
};
constexpr AttributeRule kAttributeRules[] = {
    // The types a cloudlut LUT's header has (ImfHeader's standard attributes, plus ours).
    {"chlist", -1, checkChannelList},
    {"box2i", 16, checkWindow},
    {"compression", 1, checkCompression},
    {"lineOrder", 1, checkLineOrder},
    {"int", 4, nullptr},
    {"float", 4, nullptr},
    {"v2f", 8, nullptr},
    {"string", -1, checkString},
    // Fixed-size types other tools add when they re-save an image (chromaticities, say):
    // OpenEXR reads exactly this many bytes of each.
    {"double", 8, nullptr},
    {"v2i", 8, nullptr},
    {"v2d", 16, nullptr},
    {"v3i", 12, nullptr},
    {"v3f", 12, nullptr},
    {"v3d", 24, nullptr},
    {"box2f", 16, nullptr},
    {"m33f", 36, nullptr},
    {"m33d", 72, nullptr},
    {"m44f", 64, nullptr},
    {"m44d", 128, nullptr},
    {"chromaticities", 32, nullptr},
    {"rational", 8, nullptr},
    {"timecode", 8, nullptr},
    {"keycode", 28, nullptr},
    {"envmap", 1, nullptr},
};

// Checks one attribute against its type's rule. A type OpenEXR knows but the table does not
// list (preview, stringvector, floatvector, idmanifest, tiledesc, ...) is parsed by OpenEXR from
// its content, which is not checked here, and no LUT needs one: it is rejected.
void checkAttribute(const std::string& file, const HeaderAttribute& a, const ExrHeaderLimits& limits) {
  for (const AttributeRule& rule : kAttributeRules) {
    if (a.type != rule.type) continue;
    if (rule.size >= 0 && a.value.size() != static_cast<std::size_t>(rule.size))
      corruptHeader(file, "attribute \"" + a.name + "\" of type " + a.type + " has " + std::to_string(a.value.size()) +
                              " bytes, not " + std::to_string(rule.size));
    if (rule.check != nullptr) rule.check(file, a, limits);
    return;
  }
  if (Imf::Attribute::knownType(a.type.c_str()))
    throw FileError(file, std::string("not a ") + limits.kind + " (EXR attribute \"" + a.name + "\" of type " + a.type + ")");
}

// Checks the magic number and version word of a single-part scanline EXR, then walks its
// attribute list (name\0 type\0 int32 size, value; an empty name ends it): every declared size
// must fit in the bytes left, and every value must pass checkAttribute. After this, OpenEXR's
// header parser reads the same attributes in the same places, and allocates nothing larger
// than the file, the atlas limits or the string limits allow.
}  // namespace

void checkExrHeaderBeforeDecoding(const std::string& file, const std::string& bytes, const ExrHeaderLimits& limits) {
  if (bytes.size() < 8) throw FileError(file, "not a readable EXR file (too short)");
  if (int32At(bytes, 0) != 20000630) throw FileError(file, "not a readable EXR file (no EXR magic number)");
  const auto version = static_cast<std::uint32_t>(int32At(bytes, 4));
  if ((version & 0xffu) != 2)
    throw FileError(file, "not a readable EXR file (EXR version " + std::to_string(version & 0xffu) + ")");
  // Flags: 0x200 tiled, 0x800 deep, 0x1000 multi-part; 0x400 (long names) is harmless.
  if ((version & ~0x4ffu) != 0) throw FileError(file, std::string("not a ") + limits.kind + " (tiled, deep or multi-part EXR)");
  Imf::staticInitialize();  // registers the attribute types Imf::Attribute::knownType knows
  std::size_t pos = 8;
  auto readName = [&](const char* what) {
    const std::size_t end = bytes.find('\0', pos);
    if (end == std::string::npos || end - pos > kMaxNameBytes) corruptHeader(file, std::string("attribute ") + what);
    std::string text = bytes.substr(pos, end - pos);
    pos = end + 1;
    return text;
  };
  for (int attributes = 0; attributes < 10000; ++attributes) {
    HeaderAttribute a;
    a.name = readName("name");
    if (a.name.empty()) return;
    a.type = readName("type");
    if (bytes.size() - pos < 4) corruptHeader(file, "truncated");
    const std::int32_t size = int32At(bytes, pos);
    pos += 4;
    if (size < 0 || static_cast<std::size_t>(size) > bytes.size() - pos)
      corruptHeader(file, "an attribute claims " + std::to_string(size) + " bytes, " +
                              std::to_string(bytes.size() - pos) + " remain");
    a.value = std::string_view(bytes).substr(pos, static_cast<std::size_t>(size));
    checkAttribute(file, a, limits);
    pos += static_cast<std::size_t>(size);
  }
  corruptHeader(file, "too many attributes");
}

namespace {

// Decodes an EXR held in memory; OpenEXR's exceptions pass through to the caller.
LoadedTable decodeExr(const std::filesystem::path& path, const std::string& bytes) {
  const std::string name = path.string();
  checkExrHeaderBeforeDecoding(name, bytes, ExrHeaderLimits{"cloudlut LUT", static_cast<std::size_t>(kMaxChannels)});
  MemoryIStream is(name, bytes);
  Imf::InputFile file(is);
  const Imf::Header& header = file.header();
  const auto* attribute = header.findTypedAttribute<Imf::StringAttribute>("cloudlut");
  const auto* version = header.findTypedAttribute<Imf::IntAttribute>("cloudlutVersion");
  if (attribute == nullptr || version == nullptr)
    throw FileError(name, "not a cloudlut LUT (EXR without the \"cloudlut\" attributes)");
  if (version->value() < kOldestFormatVersion || version->value() > kFormatVersion)
    throw FileError(name, "unsupported format version " + std::to_string(version->value()) + " (this build reads " +
                              std::to_string(kOldestFormatVersion) + " to " + std::to_string(kFormatVersion) + ")");
  const nlohmann::json description = nlohmann::json::parse(attribute->value(), nullptr, false);
  if (description.is_discarded() || !description.is_object())
    throw FileError(name, "corrupt \"cloudlut\" attribute (not a JSON object)");

  // the pixels the header claims must fit in the file (io/ExrBudget.h) before the table and its
  // atlas are allocated: a 26 KB file must not claim a 128^4 table
  checkExrPixelBudget(name, header, bytes.size(), 4, static_cast<std::uint64_t>(kMaxAtlasPixels) * 4);
  // the description's table must fit in the pixels the header declares (and the budget above
  // has bounded) before it is allocated; the exact match of dims and window follows
  const Imath::Box2i window = header.dataWindow();
  const long long windowWidth = static_cast<long long>(window.max.x) - window.min.x + 1;
  const long long windowHeight = static_cast<long long>(window.max.y) - window.min.y + 1;
  std::uint64_t windowChannels = 0;
  for (auto c = header.channels().begin(); c != header.channels().end(); ++c) ++windowChannels;
  const std::uint64_t windowSamples = windowChannels * static_cast<std::uint64_t>(std::max(0LL, windowWidth)) *
                                      static_cast<std::uint64_t>(std::max(0LL, windowHeight));
  Table4D table = tableFromDescription(description, path, windowSamples);
  const auto d = table.dims();
  const int C = table.channelCount();
  const long long width = static_cast<long long>(d[0]) * d[2];
  const long long height = static_cast<long long>(d[1]) * d[3];
  if (windowWidth != width || windowHeight != height)
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
