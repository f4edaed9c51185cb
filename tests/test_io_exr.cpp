// EXR atlas format: round trips, atlas layout and attributes, rejection of u8 and non-LUT EXRs.
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <Imath/half.h>
#include <catch2/catch.hpp>

#include <cstring>

#include "core/Errors.h"
#include "io/LutIo.h"
#include "support/Checks.h"
#include "support/Files.h"
#include "support/SmallTables.h"
#include "support/TempDir.h"

using cloudlut::io::SampleType;
using namespace cloudlut::test;

TEST_CASE("io: EXR float round trip is bit for bit", "[io]") {
  TempDir dir;
  for (int channels = 1; channels <= 4; ++channels) {
    const cloudlut::Table4D table = makeTable({5, 4, 3, 2}, channels, -1e5f, 1e5f);
    cloudlut::io::writeExrLut(table, SampleType::Float, dir / "t.exr");
    const auto loaded = cloudlut::io::readLut(dir / "t.exr");
    REQUIRE(loaded.sampleType == SampleType::Float);
    REQUIRE(loaded.table.name() == table.name());
    REQUIRE(loaded.table.dims() == table.dims());
    REQUIRE(loaded.table.channelCount() == channels);
    REQUIRE(loaded.table.parameters() == table.parameters());
    REQUIRE(loaded.table.channels()[0].meaning == table.channels()[0].meaning);
    REQUIRE(loaded.table.axes()[2].periodic);
    REQUIRE(loaded.table.axes()[3].max == table.axes()[3].max);
    for (std::size_t k = 0; k < table.data().size(); ++k)
      REQUIRE(sameBits(loaded.table.data()[k], table.data()[k]));
  }
  REQUIRE(listDir(dir.path()) == std::vector<std::string>{"t.exr"});
}

TEST_CASE("io: EXR half stores exactly the half values", "[io]") {
  TempDir dir;
  const cloudlut::Table4D table = makeTable({4, 3, 5, 2}, 2, -2.0f, 3.0f);
  cloudlut::io::writeExrLut(table, SampleType::Half, dir / "t.exr");
  const auto loaded = cloudlut::io::readLut(dir / "t.exr");
  REQUIRE(loaded.sampleType == SampleType::Half);
  for (std::size_t k = 0; k < table.data().size(); ++k)
    REQUIRE(sameBits(loaded.table.data()[k], static_cast<float>(Imath::half(table.data()[k]))));
}

TEST_CASE("io: EXR atlas layout and attributes", "[io]") {
  TempDir dir;
  const std::array<int, 4> d = {5, 4, 3, 2};
  const cloudlut::Table4D table = makeTable(d, 2);
  cloudlut::io::writeExrLut(table, SampleType::Float, dir / "t.exr");

  Imf::InputFile file((dir / "t.exr").c_str());
  const Imath::Box2i w = file.header().dataWindow();
  REQUIRE(w.min.x == 0);
  REQUIRE(w.min.y == 0);
  REQUIRE(w.max.x + 1 == d[0] * d[2]);
  REQUIRE(w.max.y + 1 == d[1] * d[3]);
  REQUIRE(file.header().channels().findChannel("R") != nullptr);
  REQUIRE(file.header().channels().findChannel("G") != nullptr);
  REQUIRE(file.header().channels().findChannel("B") == nullptr);
  REQUIRE(file.header().channels().findChannel("R")->type == Imf::FLOAT);
  const auto* version = file.header().findTypedAttribute<Imf::IntAttribute>("cloudlutVersion");
  REQUIRE(version != nullptr);
  REQUIRE(version->value() == 3);
  const auto* json = file.header().findTypedAttribute<Imf::StringAttribute>("cloudlut");
  REQUIRE(json != nullptr);
  REQUIRE(nlohmann::json::parse(json->value()) ==
          cloudlut::io::describeTable(table, SampleType::Float));

  const int width = d[0] * d[2], height = d[1] * d[3];
  std::vector<float> r(static_cast<std::size_t>(width * height)), g(r.size());
  Imf::FrameBuffer frame;
  frame.insert("R", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(r.data()), sizeof(float),
                               sizeof(float) * static_cast<std::size_t>(width)));
  frame.insert("G", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(g.data()), sizeof(float),
                               sizeof(float) * static_cast<std::size_t>(width)));
  file.setFrameBuffer(frame);
  file.readPixels(0, height - 1);
  for (int i3 = 0; i3 < d[3]; ++i3)
    for (int i2 = 0; i2 < d[2]; ++i2)
      for (int i1 = 0; i1 < d[1]; ++i1)
        for (int i0 = 0; i0 < d[0]; ++i0) {
          const std::size_t pixel =
              static_cast<std::size_t>((i3 * d[1] + i1) * width + i2 * d[0] + i0);
          const std::size_t node = table.index(i0, i1, i2, i3);
          REQUIRE(r[pixel] == table.at(node, 0));
          REQUIRE(g[pixel] == table.at(node, 1));
        }
}

TEST_CASE("io: EXR rejects 8-bit samples and leaves nothing", "[io]") {
  TempDir dir;
  const cloudlut::Table4D table = makeTable({2, 2, 2, 2}, 1);
  try {
    cloudlut::io::writeExrLut(table, SampleType::U8, dir / "t.exr");
    FAIL("expected a UsageError");
  } catch (const cloudlut::UsageError& e) {
    REQUIRE(std::string(e.what()) ==
            "EXR cannot store 8-bit samples; use --format bin or --precision half|float");
  }
  REQUIRE(listDir(dir.path()).empty());
}

TEST_CASE("io: an EXR without the cloudlut attribute is not a LUT", "[io]") {
  TempDir dir;
  const auto path = dir / "plain.exr";
  {
    Imf::Header header(4, 3);
    header.channels().insert("R", Imf::Channel(Imf::HALF));
    std::vector<Imath::half> pixels(12, Imath::half(0.5f));
    Imf::FrameBuffer frame;
    frame.insert("R", Imf::Slice(Imf::HALF, reinterpret_cast<char*>(pixels.data()),
                                 sizeof(Imath::half), sizeof(Imath::half) * 4));
    Imf::OutputFile out(path.c_str(), header);
    out.setFrameBuffer(frame);
    out.writePixels(3);
  }
  const std::string message = fileErrorOf([&] { cloudlut::io::readLut(path); });
  REQUIRE_THAT(message, Catch::Contains("not a cloudlut LUT"));
  REQUIRE_THAT(message, Catch::Contains("plain.exr"));
}

TEST_CASE("io: damaged EXR files give FileError", "[io]") {
  TempDir dir;
  const cloudlut::Table4D table = makeTable({6, 5, 4, 3}, 2);
  cloudlut::io::writeExrLut(table, SampleType::Half, dir / "t.exr");
  const std::string good = readFile(dir / "t.exr");

  SECTION("every truncation") {
    for (std::size_t n = 1; n < good.size(); n += 7) {
      writeFile(dir / "cut.exr", good.substr(0, n));
      fileErrorOf([&] { cloudlut::io::readLut(dir / "cut.exr"); });
    }
  }
  SECTION("flipped bytes") {
    for (std::size_t k = 4; k < good.size(); k += 13) {
      std::string bad = good;
      bad[k] = static_cast<char>(bad[k] ^ 0x5a);
      writeFile(dir / "bad.exr", bad);
      try {
        cloudlut::io::readLut(dir / "bad.exr");  // a flip in padding may go unnoticed
      } catch (const cloudlut::FileError&) {
      }
    }
  }
  SECTION("wrong cloudlutVersion") {
    // Rewrite the file with cloudlutVersion 7, keeping everything else.
    Imf::InputFile in((dir / "t.exr").c_str());
    Imf::Header header = in.header();
    header.insert("cloudlutVersion", Imf::IntAttribute(7));
    const Imath::Box2i w = header.dataWindow();
    const int width = w.max.x + 1, height = w.max.y + 1;
    std::vector<Imath::half> px(static_cast<std::size_t>(width * height * 2));
    const std::size_t stride = 2 * sizeof(Imath::half);
    Imf::FrameBuffer frame;
    frame.insert("R", Imf::Slice(Imf::HALF, reinterpret_cast<char*>(px.data()), stride,
                                 stride * static_cast<std::size_t>(width)));
    frame.insert("G", Imf::Slice(Imf::HALF, reinterpret_cast<char*>(px.data() + 1), stride,
                                 stride * static_cast<std::size_t>(width)));
    in.setFrameBuffer(frame);
    in.readPixels(0, height - 1);
    {
      Imf::OutputFile out((dir / "v7.exr").c_str(), header);
      out.setFrameBuffer(frame);
      out.writePixels(height);
    }
    REQUIRE_THAT(fileErrorOf([&] { cloudlut::io::readLut(dir / "v7.exr"); }),
                 Catch::Contains("unsupported format version 7 (this build reads 1 to 3)"));
  }
}
