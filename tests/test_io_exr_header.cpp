// EXR header validation: attribute values the reader checks by content before OpenEXR parses
// them (io/ExrLut.cpp). Each damaged file starts as a valid LUT from the project's own writer.
#include <OpenEXR/ImfBoxAttribute.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfDoubleAttribute.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfMatrixAttribute.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfPreviewImageAttribute.h>
#include <OpenEXR/ImfStandardAttributes.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfVecAttribute.h>
#include <catch2/catch.hpp>

#include <functional>
#include <map>

#include "core/Errors.h"
#include "io/LittleEndian.h"
#include "io/LutIo.h"
#include "support/Checks.h"
#include "support/Files.h"
#include "support/SmallTables.h"
#include "support/TempDir.h"

using cloudlut::io::SampleType;
using namespace cloudlut::test;

namespace {

// The message of the FileError reading `path` throws.
std::string readError(const std::filesystem::path& path) {
  return fileErrorOf([&] { cloudlut::io::readLut(path); });
}

std::string int32Bytes(std::int32_t v) {
  std::string out;
  cloudlut::io::putU32(out, static_cast<std::uint32_t>(v));
  return out;
}

// Where attribute `name` of type `type` keeps its declared size (the value follows it).
std::size_t sizeFieldOf(const std::string& file, const std::string& name, const std::string& type) {
  const std::string key = name + '\0' + type + '\0';
  const std::size_t at = file.find(key);
  REQUIRE(at != std::string::npos);
  return at + key.size();
}

std::string valueOf(const std::string& file, const std::string& name, const std::string& type) {
  const std::size_t field = sizeFieldOf(file, name, type);
  return file.substr(field + 4, cloudlut::io::getU32(file.data() + field));
}

// `file` with the value of one attribute replaced by `value`, its declared size set to the new
// value's size (so the attribute list stays well formed and everything after it moves along).
std::string withValue(const std::string& file, const std::string& name, const std::string& type,
                      const std::string& value) {
  const std::size_t field = sizeFieldOf(file, name, type);
  const std::size_t oldSize = cloudlut::io::getU32(file.data() + field);
  return file.substr(0, field) + int32Bytes(static_cast<std::int32_t>(value.size())) + value +
         file.substr(field + 4 + oldSize);
}

// One channel-list entry: name, pixel type, pLinear and reserved bytes, x and y sampling.
std::string channelEntry(const std::string& name, std::int32_t pixelType = 2, std::int32_t xSampling = 1,
                         std::int32_t ySampling = 1) {
  return name + '\0' + int32Bytes(pixelType) + std::string(4, '\0') + int32Bytes(xSampling) + int32Bytes(ySampling);
}

// Re-encodes the LUT at `from` to `to` through OpenEXR with its header edited by `edit`; the
// pixels go through float, which keeps half and float samples exactly.
void rewrite(const std::filesystem::path& from, const std::filesystem::path& to,
             const std::function<void(Imf::Header&)>& edit) {
  Imf::InputFile in(from.c_str());
  Imf::Header header = in.header();
  edit(header);
  const Imath::Box2i w = header.dataWindow();
  const std::size_t width = static_cast<std::size_t>(w.max.x - w.min.x + 1);
  const std::size_t height = static_cast<std::size_t>(w.max.y - w.min.y + 1);
  std::map<std::string, std::vector<float>> pixels;
  Imf::FrameBuffer frame;
  for (auto c = header.channels().begin(); c != header.channels().end(); ++c) {
    auto& plane = pixels[c.name()];
    plane.resize(width * height);
    frame.insert(c.name(), Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(plane.data()), sizeof(float),
                                      sizeof(float) * width));
  }
  in.setFrameBuffer(frame);
  in.readPixels(w.min.y, w.max.y);
  Imf::OutputFile out(to.c_str(), header);
  out.setFrameBuffer(frame);
  out.writePixels(static_cast<int>(height));
}

}  // namespace

TEST_CASE("io: EXR channel lists are checked by content, within their declared size", "[io][fuzz]") {
  TempDir dir;
  cloudlut::io::writeExrLut(makeTable({4, 3, 2, 2}, 2), SampleType::Half, dir / "t.exr");
  const std::string good = readFile(dir / "t.exr");
  const std::string list = valueOf(good, "channels", "chlist");
  REQUIRE(list == channelEntry("G", 1) + channelEntry("R", 1) + '\0');  // the writer's list
  const auto bad = dir / "bad.exr";

  SECTION("an attribute hidden after the list's end") {
    // The case that made OpenEXR allocate 2 GiB: the declared size covers the list and, after
    // its terminating NUL, a string attribute claiming 2 GiB. OpenEXR parses the list by
    // content, stops at the NUL and reads the hidden attribute next; the declared sizes alone
    // all fit the file.
    writeFile(bad, withValue(good, "channels", "chlist",
                                      list + "x" + '\0' + "string" + '\0' + int32Bytes(0x7ffffff0)));
    const std::string message = readError(bad);
    REQUIRE_THAT(message, Catch::Contains("channel list \"channels\" ends 13 bytes before its declared size"));
    REQUIRE_THAT(message, Catch::Contains("bad.exr"));
  }
  SECTION("a list running past its declared size") {
    // Without its terminating NUL, OpenEXR would read the next attribute as channel entries.
    writeFile(bad, withValue(good, "channels", "chlist", list.substr(0, list.size() - 1)));
    REQUIRE_THAT(readError(bad), Catch::Contains("channel list \"channels\" is not terminated"));
    writeFile(bad, withValue(good, "channels", "chlist", list.substr(0, list.size() - 6) + '\0'));
    REQUIRE_THAT(readError(bad), Catch::Contains("channel R runs past its list"));
  }
  SECTION("an empty list") {
    writeFile(bad, withValue(good, "channels", "chlist", std::string(1, '\0')));
    REQUIRE_THAT(readError(bad), Catch::Contains("channel list \"channels\" is empty"));
  }
  SECTION("more channels than a LUT has") {
    std::string five;
    for (const char* name : {"A", "B", "G", "R", "Z"}) five += channelEntry(name, 1);
    writeFile(bad, withValue(good, "channels", "chlist", five + '\0'));
    REQUIRE_THAT(readError(bad), Catch::Contains("not a cloudlut LUT (more than 4 channels)"));
  }
  SECTION("a bad pixel type, subsampling, an overlong name") {
    writeFile(bad, withValue(good, "channels", "chlist", channelEntry("G", 7) + channelEntry("R", 1) + '\0'));
    REQUIRE_THAT(readError(bad), Catch::Contains("channel G has pixel type 7"));
    writeFile(bad, withValue(good, "channels", "chlist", channelEntry("G", 1) + channelEntry("R", -1) + '\0'));
    REQUIRE_THAT(readError(bad), Catch::Contains("channel R has pixel type -1"));
    writeFile(bad, withValue(good, "channels", "chlist", channelEntry("G", 1, 1, 2) + '\0'));
    REQUIRE_THAT(readError(bad), Catch::Contains("channel G is subsampled"));
    writeFile(bad, withValue(good, "channels", "chlist", channelEntry(std::string(256, 'G'), 1) + '\0'));
    REQUIRE_THAT(readError(bad), Catch::Contains("channel name longer than 255 bytes"));
  }
  SECTION("the untouched file still reads") {
    writeFile(bad, withValue(good, "channels", "chlist", list));
    REQUIRE(cloudlut::io::readLut(bad).table.channelCount() == 2);
  }
}

TEST_CASE("io: EXR fixed-size and string attributes are checked by content", "[io][fuzz]") {
  TempDir dir;
  cloudlut::io::writeExrLut(makeTable({4, 3, 2, 2}, 1), SampleType::Float, dir / "t.exr");
  const std::string good = readFile(dir / "t.exr");
  const auto bad = dir / "bad.exr";
  auto errorWith = [&](const std::string& name, const std::string& type, const std::string& value) {
    writeFile(bad, withValue(good, name, type, value));
    return readError(bad);
  };

  // A fixed-size value longer or shorter than its type: OpenEXR would read its own size and
  // take what follows for the next attribute.
  REQUIRE_THAT(errorWith("cloudlutVersion", "int", int32Bytes(1) + int32Bytes(0x7ffffff0)),
               Catch::Contains("attribute \"cloudlutVersion\" of type int has 8 bytes, not 4"));
  REQUIRE_THAT(errorWith("dataWindow", "box2i", valueOf(good, "dataWindow", "box2i").substr(0, 12)),
               Catch::Contains("attribute \"dataWindow\" of type box2i has 12 bytes, not 16"));
  REQUIRE_THAT(errorWith("compression", "compression", std::string(2, '\3')),
               Catch::Contains("of type compression has 2 bytes, not 1"));
  REQUIRE_THAT(errorWith("pixelAspectRatio", "float", std::string(2, '\0')),
               Catch::Contains("of type float has 2 bytes, not 4"));
  REQUIRE_THAT(errorWith("screenWindowCenter", "v2f", std::string(12, '\0')),
               Catch::Contains("of type v2f has 12 bytes, not 8"));
  // Values outside the type.
  REQUIRE_THAT(errorWith("compression", "compression", "\x64"), Catch::Contains("unknown compression 100"));
  REQUIRE_THAT(errorWith("lineOrder", "lineOrder", "\x07"), Catch::Contains("unknown line order 7"));
  // Windows outside any atlas: the data window, and the display window the same way.
  const std::string huge = int32Bytes(0) + int32Bytes(0) + int32Bytes(0x7ffffff0) + int32Bytes(0);
  REQUIRE_THAT(errorWith("dataWindow", "box2i", huge),
               Catch::Contains("not a cloudlut LUT (EXR dataWindow 2147483633x1 is outside any LUT atlas)"));
  REQUIRE_THAT(errorWith("displayWindow", "box2i", int32Bytes(5) + int32Bytes(0) + int32Bytes(4) + int32Bytes(0)),
               Catch::Contains("EXR displayWindow 0x1 is outside any LUT atlas"));
  // A description padded past its bound with JSON whitespace (it would still parse).
  const std::string description = valueOf(good, "cloudlut", "string");
  REQUIRE_THAT(errorWith("cloudlut", "string", description + std::string(70000, ' ')),
               Catch::Contains("string \"cloudlut\" of " + std::to_string(description.size() + 70000) +
                               " bytes, more than 65536"));
  // Within the bound it reads (re-encoded: a patch in place would move the pixel data).
  rewrite(dir / "t.exr", dir / "padded.exr", [&](Imf::Header& h) {
    h.insert("cloudlut", Imf::StringAttribute(description + std::string(1000, ' ')));
  });
  REQUIRE(cloudlut::io::readLut(dir / "padded.exr").table.channelCount() == 1);
}

TEST_CASE("io: EXR header word and attribute types outside a scanline LUT", "[io][fuzz]") {
  TempDir dir;
  cloudlut::io::writeExrLut(makeTable({4, 3, 2, 2}, 2), SampleType::Float, dir / "t.exr");
  const std::string good = readFile(dir / "t.exr");
  const auto bad = dir / "bad.exr";

  std::string tiled = good;
  tiled[5] = static_cast<char>(tiled[5] | 0x02);  // version word flag 0x200
  writeFile(bad, tiled);
  REQUIRE_THAT(readError(bad), Catch::Contains("not a cloudlut LUT (tiled, deep or multi-part EXR)"));
  std::string version3 = good;
  version3[4] = 3;
  writeFile(bad, version3);
  REQUIRE_THAT(readError(bad), Catch::Contains("(EXR version 3)"));

  // Standard fixed-size attributes another tool may add keep the LUT readable.
  rewrite(dir / "t.exr", dir / "extra.exr", [](Imf::Header& h) {
    Imf::addChromaticities(h, Imf::Chromaticities());
    Imf::addWhiteLuminance(h, 100.0f);
    Imf::addEnvmap(h, Imf::ENVMAP_LATLONG);
    Imf::addWorldToCamera(h, Imath::M44f());
    Imf::addFramesPerSecond(h, Imf::Rational(24, 1));
    Imf::addTimeCode(h, Imf::TimeCode(1, 2, 3, 4));
    Imf::addKeyCode(h, Imf::KeyCode());
    Imf::addCapDate(h, "2026:01:01 00:00:00");
    h.insert("extra.v3f", Imf::V3fAttribute(Imath::V3f(1, 2, 3)));
    h.insert("extra.v2i", Imf::V2iAttribute(Imath::V2i(1, 2)));
    h.insert("extra.double", Imf::DoubleAttribute(0.5));
    h.insert("extra.m33f", Imf::M33fAttribute(Imath::M33f()));
    h.insert("extra.box2f", Imf::Box2fAttribute(Imath::Box2f(Imath::V2f(0, 0), Imath::V2f(1, 1))));
  });
  REQUIRE(cloudlut::io::readLut(dir / "extra.exr").table.channelCount() == 2);

  // A type OpenEXR sizes from its own content, which the reader does not check, is refused.
  rewrite(dir / "t.exr", dir / "preview.exr", [](Imf::Header& h) {
    h.insert("preview", Imf::PreviewImageAttribute(Imf::PreviewImage(2, 2)));
  });
  REQUIRE_THAT(readError(dir / "preview.exr"),
               Catch::Contains("not a cloudlut LUT (EXR attribute \"preview\" of type preview)"));
}
