// The header-only engine reader (lut_formats/cloudlut_lut.h and cloudlut_manifest.h) against
// the io library. The table reader is included first, before any project header, to show that
// it stands alone without JSON.
#include "cloudlut_lut.h"
#include "cloudlut_manifest.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdlib>
#include <cstring>

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

// The next of a fixed linear-congruential sequence of axis fractions in [−0.2, 1.2] (the ends
// exercise the clamping).
float nextFraction(std::uint32_t& state) {
  state = state * 1664525u + 1013904223u;
  return -0.2f + 1.4f * static_cast<float>(state >> 8) / 16777216.0f;
}

}  // namespace

TEST_CASE("io: header-only reader agrees with the io reader value for value", "[io]") {
  TempDir dir;
  for (SampleType type : {SampleType::U8, SampleType::Half, SampleType::Float}) {
    for (int channels : {1, 2, 4}) {
      const cloudlut::Table4D table = makeTable({5, 4, 3, 2}, channels, -0.5f, 1.5f);
      cloudlut::io::writeBinaryLut(table, type, dir / "t.bin");
      const auto expected = cloudlut::io::readLut(dir / "t.bin");
      const cloudlut_reader::Lut lut = cloudlut_reader::readLut((dir / "t.bin").string());
      REQUIRE(lut.name == table.name());
      REQUIRE(static_cast<int>(lut.sampleType) == static_cast<int>(type));
      REQUIRE(lut.channelCount() == static_cast<std::size_t>(channels));
      REQUIRE(lut.textureWidth() == 5);
      REQUIRE(lut.textureHeight() == 4);
      REQUIRE(lut.textureDepth() == 6);
      for (std::size_t k = 0; k < 4; ++k) {
        REQUIRE(lut.dims[k] == static_cast<std::uint32_t>(table.dims()[k]));
        REQUIRE(lut.axes[k].name == table.axes()[k].name);
        REQUIRE(lut.axes[k].unit == table.axes()[k].unit);
        REQUIRE(lut.axes[k].min == table.axes()[k].min);
        REQUIRE(lut.axes[k].max == table.axes()[k].max);
        REQUIRE(lut.axes[k].periodic == table.axes()[k].periodic);
      }
      for (int c = 0; c < channels; ++c)
        REQUIRE(lut.channels[static_cast<std::size_t>(c)] == table.channels()[c].name);
      REQUIRE(lut.sampleBytes() == (type == SampleType::U8 ? 1u : type == SampleType::Half ? 2u : 4u));
      REQUIRE(lut.values.size() == expected.table.data().size());
      for (std::size_t k = 0; k < lut.values.size(); ++k)
        REQUIRE(sameBits(lut.values[k], expected.table.data()[k]));
      const auto description = nlohmann::json::parse(lut.description);
      REQUIRE(description == cloudlut::io::describeTable(table, type));
      // The kit's own JSON reads the same description.
      const cloudlut_reader::Json parsed = cloudlut_reader::parseDescription(lut);
      REQUIRE(parsed.find("parameters") != nullptr);
      REQUIRE(parsed.find("parameters")->find("radius")->number == 183.8);
    }
  }
}

TEST_CASE("io: header-only reader streams a payload larger than its buffer", "[io]") {
  // 64·32·32·5 floats = 1.25 MiB: the payload is checksummed and decoded in two pieces.
  TempDir dir;
  const cloudlut::Table4D table = makeTable({64, 32, 32, 5}, 1, -3.0f, 3.0f, 5);
  cloudlut::io::writeBinaryLut(table, SampleType::Float, dir / "big.bin");
  const cloudlut_reader::Lut lut = cloudlut_reader::readLut((dir / "big.bin").string());
  REQUIRE(lut.values.size() == table.data().size());
  for (std::size_t k = 0; k < lut.values.size(); ++k) REQUIRE(sameBits(lut.values[k], table.data()[k]));
  // A flipped byte past the first MiB of the payload is caught by the checksum.
  std::string bytes = readFile(dir / "big.bin");
  bytes[bytes.size() - 100] = static_cast<char>(bytes[bytes.size() - 100] ^ 0x10);
  writeFile(dir / "big.bin", bytes);
  REQUIRE_THAT(runtimeErrorOf([&] { cloudlut_reader::readLut((dir / "big.bin").string()); }),
               Catch::EndsWith("checksum mismatch"));
}

TEST_CASE("quadrilinear sampling reproduces multilinear functions of the axis fractions", "[io][parameterization]") {
  // f(x) = 1 + 2 x0 − x1 + 0.5 x2 x3 + 3 x0 x1 x2 x3 is linear in each axis fraction, so the
  // interpolation between the nodes must give it exactly (up to float rounding) everywhere,
  // clamped outside [0, 1]; an axis of one node is constant.
  const auto f = [](const std::array<float, 4>& x) {
    double y[4];
    for (int k = 0; k < 4; ++k) y[k] = std::clamp(static_cast<double>(x[k]), 0.0, 1.0);
    return 1.0 + 2.0 * y[0] - y[1] + 0.5 * y[2] * y[3] + 3.0 * y[0] * y[1] * y[2] * y[3];
  };
  for (const std::array<int, 4>& dims : {std::array<int, 4>{6, 5, 4, 3}, std::array<int, 4>{3, 2, 1, 4}}) {
    cloudlut::Table4D table = makeTable(dims, 1);
    for (int i3 = 0; i3 < dims[3]; ++i3)
      for (int i2 = 0; i2 < dims[2]; ++i2)
        for (int i1 = 0; i1 < dims[1]; ++i1)
          for (int i0 = 0; i0 < dims[0]; ++i0) {
            const int i[4] = {i0, i1, i2, i3};
            std::array<float, 4> x{};
            for (int k = 0; k < 4; ++k) x[k] = dims[k] > 1 ? static_cast<float>(i[k]) / static_cast<float>(dims[k] - 1) : 0.0f;
            table.at(table.index(i0, i1, i2, i3), 0) = static_cast<float>(f(x));
          }
    TempDir dir;
    cloudlut::io::writeBinaryLut(table, SampleType::Float, dir / "t.bin");
    const cloudlut_reader::Lut lut = cloudlut_reader::readLut((dir / "t.bin").string());
    std::uint32_t state = 7;
    const auto next = [&] { return nextFraction(state); };
    for (int trial = 0; trial < 500; ++trial) {
      std::array<float, 4> x = {next(), next(), next(), next()};
      for (int k = 0; k < 4; ++k)
        if (dims[k] == 1) x[k] = 0.0f;  // a one-node axis holds f at fraction 0 only
      float fromTable = 0.0f, fromLut = 0.0f;
      table.sample(x, &fromTable);
      lut.sample(x[0], x[1], x[2], x[3], &fromLut);
      REQUIRE(fromTable == Approx(f(x)).epsilon(1e-5));
      REQUIRE(fromLut == Approx(f(x)).epsilon(1e-5));
    }
  }
}

TEST_CASE("io: header-only reader samples like Table4D::sample", "[io]") {
  // Both call sampleQuadrilinear: this checks that the reader's decoded values sit in the
  // table's layout (axis order, channel interleaving), bit for bit.
  TempDir dir;
  const cloudlut::Table4D table = makeTable({6, 5, 4, 3}, 2, 0.0f, 10.0f);
  cloudlut::io::writeBinaryLut(table, SampleType::Float, dir / "t.bin");
  const cloudlut_reader::Lut lut = cloudlut_reader::readLut((dir / "t.bin").string());
  std::uint32_t state = 99;
  const auto next = [&] { return nextFraction(state); };
  for (int trial = 0; trial < 2000; ++trial) {
    const std::array<float, 4> x = {next(), next(), next(), next()};
    float expected[2], got[2];
    table.sample(x, expected);
    lut.sample(x[0], x[1], x[2], x[3], got);
    REQUIRE(got[0] == expected[0]);
    REQUIRE(got[1] == expected[1]);
  }
  // At nodes the samples are the stored values.
  const std::vector<float> v = lut.sample(1.0f / 5.0f, 1.0f, 0.0f, 0.5f);
  REQUIRE(v[0] == Approx(table.at(table.index(1, 4, 0, 1), 0)).epsilon(1e-6));
  REQUIRE(v[1] == Approx(lut.value(1, 4, 0, 1, 1)).epsilon(1e-6));
}

TEST_CASE("io: header-only reader rejects damaged files with the file name", "[io]") {
  TempDir dir;
  cloudlut::io::writeBinaryLut(makeTable({4, 3, 3, 2}, 2), SampleType::Half,
                               dir / "good.bin");
  const std::string good = readFile(dir / "good.bin");
  const auto bad = dir / "bad.bin";
  const auto errorFor = [&](const std::string& bytes) {
    writeFile(bad, bytes);
    const std::string message =
        runtimeErrorOf([&] { cloudlut_reader::readLut(bad.string()); });
    REQUIRE_THAT(message, Catch::StartsWith(bad.string() + ": "));
    // parseLut on the same bytes fails the same way.
    const std::vector<std::uint8_t> v(bytes.begin(), bytes.end());
    runtimeErrorOf([&] { cloudlut_reader::parseLut(v, "mem"); });
    return message;
  };
  REQUIRE_THAT(errorFor(""), Catch::Contains("empty"));
  REQUIRE_THAT(errorFor("hello world, not a lut"), Catch::Contains("bad magic"));
  REQUIRE_THAT(errorFor(good.substr(0, good.size() - 4)),
               Catch::Contains("truncated: expected"));
  std::string flipped = good;
  flipped.back() = static_cast<char>(flipped.back() ^ 1);
  REQUIRE_THAT(errorFor(flipped), Catch::EndsWith("checksum mismatch"));
  std::string version = good;
  version[8] = 7;
  REQUIRE_THAT(errorFor(version), Catch::EndsWith("unsupported format version 7 (this build reads 1 to 3)"));
  for (std::size_t n = 1; n < good.size(); n += 3) errorFor(good.substr(0, n));
  const std::uint32_t headerBytes = cloudlut::io::getU32(good.data() + 12);
  for (std::size_t k = 0; k < headerBytes; ++k) {
    std::string b = good;
    b[k] = static_cast<char>(b[k] ^ 0x40);
    errorFor(b);
  }
  REQUIRE_THAT(runtimeErrorOf([&] { cloudlut_reader::readLut((dir / "none.bin").string()); }),
               Catch::Contains("none.bin"));
}

TEST_CASE("io: header-only reader lists the manifest's tables", "[io]") {
  TempDir dir;
  const cloudlut::Table4D od = makeTable({5, 4, 3, 2}, 2);
  nlohmann::json entry = cloudlut::io::describeTable(od, SampleType::U8);
  entry["files"] = {{"bin", "optical_depth.bin"}, {"exr", "optical_depth.exr"}};
  nlohmann::json ms = cloudlut::io::describeTable(
      makeTable({4, 3, 3, 8}, 1, 0, 1, 1, "multiple_scattering"), SampleType::Half);
  ms["files"] = {{"exr", "multiple_scattering.exr"}};
  cloudlut::io::writeManifest(dir.path(), {{"format", "cloudlut-lut-set"},
                                           {"version", 1},
                                           {"generator", "cloudlut 0.1.0 \u00e9\t\"q\""},
                                           {"parameters", {{"g", {0.9, 0.7}}, {"x", nullptr}}},
                                           {"tables", {{"optical_depth", entry},
                                                       {"multiple_scattering", ms}}}});
  const cloudlut_reader::Manifest m = cloudlut_reader::readManifest(dir.path().string());
  REQUIRE(m.version == 1);
  REQUIRE(m.generator == "cloudlut 0.1.0 \u00e9\t\"q\"");
  REQUIRE(m.tables.size() == 2);
  const auto& t = m.tables[1].name == "optical_depth" ? m.tables[1] : m.tables[0];
  REQUIRE(t.name == "optical_depth");
  REQUIRE(t.dims == std::array<std::uint32_t, 4>{5, 4, 3, 2});
  REQUIRE(t.sampleType == "u8");
  REQUIRE(t.binFile == "optical_depth.bin");
  REQUIRE(t.exrFile == "optical_depth.exr");
  REQUIRE(t.channels == std::vector<std::string>{"mean_density", "first_matter"});
  const auto& u = m.tables[1].name == "optical_depth" ? m.tables[0] : m.tables[1];
  REQUIRE(u.binFile.empty());
  REQUIRE(u.exrFile == "multiple_scattering.exr");

  writeFile(dir / "manifest.json", "{\"format\":\"cloudlut-lut-set\",\"version\":4,\"tables\":{}}");
  REQUIRE_THAT(runtimeErrorOf([&] { cloudlut_reader::readManifest(dir.path().string()); }),
               Catch::Contains("unsupported manifest version"));
  writeFile(dir / "manifest.json", "{\"format\":\"cloudlut-lut-set\",");
  REQUIRE_THAT(runtimeErrorOf([&] { cloudlut_reader::readManifest(dir.path().string()); }),
               Catch::Contains("invalid JSON"));
}

TEST_CASE("io: header-only reader's JSON parser", "[io]") {
  using cloudlut_reader::Json;
  const Json j = cloudlut_reader::parseJson(
      " {\"a\": [1, -2.5e3, true, false, null, \"x\\u00e9\\ud83d\\ude00\\n\"], \"b\": {}} ");
  REQUIRE(j.type == Json::Type::Object);
  const Json* a = j.find("a");
  REQUIRE(a != nullptr);
  REQUIRE(a->items.size() == 6);
  REQUIRE(a->items[0].number == 1.0);
  REQUIRE(a->items[1].number == -2500.0);
  REQUIRE(a->items[2].boolean);
  REQUIRE(a->items[3].type == Json::Type::Bool);
  REQUIRE(a->items[4].type == Json::Type::Null);
  REQUIRE(a->items[5].string == "x\xc3\xa9\xf0\x9f\x98\x80\n");
  REQUIRE(j.find("b")->type == Json::Type::Object);
  REQUIRE(j.find("c") == nullptr);
  for (const char* bad : {"", "{", "[1,]", "{\"a\" 1}", "\"abc", "tru", "1 2", "{\"a\":-}",
                          "\"\\q\""})
    REQUIRE_THROWS_AS(cloudlut_reader::parseJson(bad), std::runtime_error);
  REQUIRE_THROWS_AS(cloudlut_reader::parseJson(std::string(1000, '[')), std::runtime_error);
}

TEST_CASE("io: each engine-kit header compiles alone as C++17", "[io]") {
  // Uses the system's c++ when there is one; the test TU above already includes the table
  // reader before anything else.
  if (std::system("command -v c++ >/dev/null 2>&1") != 0) {
    WARN("no c++ compiler on PATH; skipped");
    return;
  }
  TempDir dir;
  const struct {
    const char* header;
    const char* body;
  } units[] = {{"cloudlut_quadrilinear.h", "float v[1] = {2.0f}, x[4] = {0, 0, 0, 0}, o = 0; const std::uint32_t d[4] = {1, 1, 1, 1};\n"
                                           "cloudlut_reader::sampleQuadrilinear(v, d, 1, x, &o); return o == 2.0f ? 0 : 1;"},
               {"cloudlut_lut.h", "cloudlut_reader::Lut lut; return lut.channelCount() == 0 ? 0 : 1;"},
               {"cloudlut_manifest.h", "return cloudlut_reader::parseJson(\"[1]\").items.size() == 1 ? 0 : 1;"},
               {"cloudlut_reader.h", "return cloudlut_reader::parseJson(\"[1]\").items.size() == 1 ? 0 : 1;"}};
  // One compiler run, one translation unit per header.
  std::string command = std::string("c++ -std=c++17 -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Werror -I'") +
                        CLOUDLUT_SOURCE_DIR + "/lut_formats' -fsyntax-only";
  int n = 0;
  for (const auto& u : units) {
    const auto file = dir / ("alone" + std::to_string(n++) + ".cpp");
    writeFile(file, std::string("#include \"") + u.header + "\"\nint main() { " + u.body + " }\n");
    command += " '" + file.string() + "'";
  }
  REQUIRE(std::system(command.c_str()) == 0);
  // The table reader holds no JSON parser.
  const std::string lutHeader = readFile(std::string(CLOUDLUT_SOURCE_DIR) + "/lut_formats/cloudlut_lut.h");
  CHECK(lutHeader.find("Json") == std::string::npos);  // no JSON value type, no parser
}
