#include "io/ExrImage.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>

#include <fstream>
#include <limits>
#include <sstream>

#include "core/Errors.h"
#include "io/ExrBudget.h"
#include "io/LutIo.h"
#include "io/MemoryStreams.h"

namespace cloudlut::io {

namespace {
// An image of compare's: a handful of channels (R, G, B, A, their standard errors, the lighting
// terms); 2^28 float samples = 1 GiB decoded at most.
constexpr std::size_t kMaxImageChannels = 64;
constexpr std::uint64_t kMaxImageSamples = 1ULL << 28;
}  // namespace

std::vector<float>& ExrImage::channel(const std::string& name) {
  auto& c = channels[name];
  if (c.size() != pixelCount()) c.assign(pixelCount(), 0.0f);
  return c;
}

void writeExrImage(const ExrImage& image, const std::filesystem::path& path) {
  if (image.width < 1 || image.height < 1) throw UsageError("cannot write '" + path.string() + "': empty image");
  std::string bytes;
  try {
    Imf::Header header(image.width, image.height);
    header.compression() = Imf::ZIP_COMPRESSION;
    for (const auto& [name, attr] : image.attributes) header.insert(name, Imf::StringAttribute(attr));
    Imf::FrameBuffer frame;
    for (const auto& [name, data] : image.channels) {
      if (data.size() != image.pixelCount())
        throw UsageError("cannot write '" + path.string() + "': channel " + name + " has the wrong size");
      header.channels().insert(name, Imf::Channel(Imf::FLOAT));
      frame.insert(name, Imf::Slice(Imf::FLOAT, const_cast<char*>(reinterpret_cast<const char*>(data.data())),
                                    sizeof(float), sizeof(float) * static_cast<std::size_t>(image.width)));
    }
    MemoryOStream os(path.string());
    {
      Imf::OutputFile out(os, header);
      out.setFrameBuffer(frame);
      out.writePixels(image.height);
    }
    bytes = os.bytes();
  } catch (const UsageError&) {
    throw;
  } catch (const std::exception& e) {
    throw UsageError("cannot encode '" + path.string() + "' as EXR: " + e.what());
  }
  writeFileAtomically(path, bytes);
}

ExrImage readExrImage(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw FileError(path.string(), "no such file");
  if (std::filesystem::is_directory(path, ec)) throw FileError(path.string(), "is a directory, not an EXR image");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw FileError(path.string(), "cannot open for reading");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string bytes = ss.str();
  if (bytes.size() < 4 || static_cast<unsigned char>(bytes[0]) != 0x76 || static_cast<unsigned char>(bytes[1]) != 0x2f ||
      static_cast<unsigned char>(bytes[2]) != 0x31 || static_cast<unsigned char>(bytes[3]) != 0x01)
    throw FileError(path.string(), "not an OpenEXR file");
  // the header by content before OpenEXR parses it: it would reserve what an attribute declares
  checkExrHeaderBeforeDecoding(path.string(), bytes, ExrHeaderLimits{"supported EXR image", kMaxImageChannels});
  try {
    MemoryIStream is(path.string(), bytes);
    Imf::InputFile file(is);
    const Imf::Header& header = file.header();
    const auto& dw = header.dataWindow();
    // before any buffer: the window times the channels against the file's size (io/ExrBudget.h)
    checkExrPixelBudget(path.string(), header, bytes.size(), static_cast<int>(kMaxImageChannels), kMaxImageSamples);
    const long long w = static_cast<long long>(dw.max.x) - dw.min.x + 1;
    const long long h = static_cast<long long>(dw.max.y) - dw.min.y + 1;
    ExrImage image(static_cast<int>(w), static_cast<int>(h));
    Imf::FrameBuffer frame;
    for (auto it = header.channels().begin(); it != header.channels().end(); ++it) {
      if (it.channel().xSampling != 1 || it.channel().ySampling != 1)
        throw FileError(path.string(), std::string("channel ") + it.name() + " is subsampled (unsupported)");
      std::vector<float>& data = image.channel(it.name());
      // The slice's base is the address of pixel (0, 0), which lies outside the buffer when
      // the data window does not start at the origin.
      char* base = reinterpret_cast<char*>(data.data()) -
                   (static_cast<std::ptrdiff_t>(dw.min.x) + static_cast<std::ptrdiff_t>(dw.min.y) * w) *
                       static_cast<std::ptrdiff_t>(sizeof(float));
      frame.insert(it.name(), Imf::Slice(Imf::FLOAT, base, sizeof(float), sizeof(float) * static_cast<std::size_t>(w),
                                         1, 1, std::numeric_limits<float>::quiet_NaN()));
    }
    for (auto it = header.begin(); it != header.end(); ++it)
      if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&it.attribute()))
        image.attributes[it.name()] = s->value();
    file.setFrameBuffer(frame);
    file.readPixels(dw.min.y, dw.max.y);
    return image;
  } catch (const FileError&) {
    throw;
  } catch (const std::exception& e) {
    throw FileError(path.string(), std::string("not a readable EXR image (") + e.what() + ")");
  }
}

}  // namespace cloudlut::io
