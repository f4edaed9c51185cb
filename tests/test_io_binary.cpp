// Binary LUT format: round trips, documented byte layout, sample encodings.
#include <Imath/half.h>
#include <catch2/catch.hpp>

#include <cstring>
#include <limits>

#include "core/Errors.h"
#include "io/Fnv1a.h"
#include "io/LittleEndian.h"
#include "io/LutIo.h"
#include "io/SampleCodec.h"
#include "support/Checks.h"
#include "support/Files.h"
#include "support/SmallTables.h"
#include "support/TempDir.h"

using cloudlut::io::SampleType;
using namespace cloudlut::test;

namespace {

void requireSameDescription(const cloudlut::Table4D& a, const cloudlut::Table4D& b) {
  REQUIRE(a.name() == b.name());
  REQUIRE(a.dims() == b.dims());
  for (int k = 0; k < 4; ++k) {
    REQUIRE(a.axes()[k].name == b.axes()[k].name);
    REQUIRE(a.axes()[k].unit == b.axes()[k].unit);
    REQUIRE(a.axes()[k].min == b.axes()[k].min);
    REQUIRE(a.axes()[k].max == b.axes()[k].max);
    REQUIRE(a.axes()[k].periodic == b.axes()[k].periodic);
    REQUIRE(a.axes()[k].warp == b.axes()[k].warp);
  }
  REQUIRE(a.channelCount() == b.channelCount());
  for (int c = 0; c < a.channelCount(); ++c) {
    REQUIRE(a.channels()[c].name == b.channels()[c].name);
    REQUIRE(a.channels()[c].meaning == b.channels()[c].meaning);
  }
  REQUIRE(a.parameters() == b.parameters());
}

}  // namespace

TEST_CASE("io: binary float round trip is bit for bit", "[io]") {
  TempDir dir;
  cloudlut::Table4D table = makeTable({5, 4, 3, 2}, 2, -1e3f, 1e3f);
  {
    auto axes = table.axes();  // a concentrated axis survives the round trip (format version 2)
    axes[1].warp = 6.5;
    cloudlut::Table4D warped(table.name(), axes, table.channels());
    warped.data() = table.data();
    warped.parameters() = table.parameters();
    table = std::move(warped);
  }
  table.data()[0] = std::numeric_limits<float>::denorm_min();
  table.data()[1] = -0.0f;
  table.data()[2] = std::numeric_limits<float>::infinity();
  table.data()[3] = std::numeric_limits<float>::quiet_NaN();
  cloudlut::io::writeBinaryLut(table, SampleType::Float, dir / "t.bin");
  const auto loaded = cloudlut::io::readLut(dir / "t.bin");
  REQUIRE(loaded.sampleType == SampleType::Float);
  REQUIRE(loaded.checksumOk);
  requireSameDescription(table, loaded.table);
  REQUIRE(loaded.table.data().size() == table.data().size());
  for (std::size_t k = 0; k < table.data().size(); ++k)
    REQUIRE(sameBits(loaded.table.data()[k], table.data()[k]));
  REQUIRE(listDir(dir.path()) == std::vector<std::string>{"t.bin"});
}

TEST_CASE("io: binary half stores exactly the half values", "[io]") {
  TempDir dir;
  cloudlut::Table4D table = makeTable({3, 5, 2, 4}, 1, -70000.0f, 70000.0f);
  table.data()[0] = 1e-7f;  // a half subnormal
  table.data()[1] = 0.1f;
  cloudlut::io::writeBinaryLut(table, SampleType::Half, dir / "t.bin");
  const auto loaded = cloudlut::io::readLut(dir / "t.bin");
  REQUIRE(loaded.sampleType == SampleType::Half);
  for (std::size_t k = 0; k < table.data().size(); ++k)
    REQUIRE(sameBits(loaded.table.data()[k], static_cast<float>(Imath::half(table.data()[k]))));
}

TEST_CASE("io: binary u8 stores clamped codes rounded to nearest", "[io]") {
  REQUIRE(cloudlut::io::encodeU8(-1.0f) == 0);
  REQUIRE(cloudlut::io::encodeU8(std::numeric_limits<float>::quiet_NaN()) == 0);
  REQUIRE(cloudlut::io::encodeU8(2.0f) == 255);
  REQUIRE(cloudlut::io::encodeU8(0.5f) == 128);
  REQUIRE(cloudlut::io::encodeU8(0.2f) == 51);
  REQUIRE(cloudlut::io::encodeU8(1.0f / 255.0f) == 1);

  TempDir dir;
  const cloudlut::Table4D table = makeTable({4, 4, 3, 3}, 2);
  cloudlut::io::writeBinaryLut(table, SampleType::U8, dir / "t.bin");
  const auto loaded = cloudlut::io::readLut(dir / "t.bin");
  REQUIRE(loaded.sampleType == SampleType::U8);
  const std::string bytes = readFile(dir / "t.bin");
  const std::size_t payload = bytes.size() - table.data().size();
  for (std::size_t k = 0; k < table.data().size(); ++k) {
    const std::uint8_t code = cloudlut::io::encodeU8(table.data()[k]);
    REQUIRE(static_cast<std::uint8_t>(bytes[payload + k]) == code);
    REQUIRE(loaded.table.data()[k] == static_cast<float>(code) / 255.0f);
  }
}

TEST_CASE("io: binary header follows the documented layout", "[io]") {
  using namespace cloudlut::io;
  TempDir dir;
  const cloudlut::Table4D plain = makeTable({6, 5, 4, 3}, 2);
  auto axes = plain.axes();
  axes[1].warp = 7.0;
  cloudlut::Table4D table(plain.name(), axes, plain.channels());
  table.data() = plain.data();
  table.parameters() = plain.parameters();
  writeBinaryLut(table, SampleType::Half, dir / "t.bin");
  const std::string b = readFile(dir / "t.bin");
  const char* p = b.data();
  REQUIRE(b.compare(0, 8, "CLOUDLUT") == 0);
  REQUIRE(getU32(p + 8) == 3);
  const std::uint32_t headerBytes = getU32(p + 12);
  REQUIRE(headerBytes % 8 == 0);
  REQUIRE(getU32(p + 16) == 6);
  REQUIRE(getU32(p + 20) == 5);
  REQUIRE(getU32(p + 24) == 4);
  REQUIRE(getU32(p + 28) == 3);
  REQUIRE(getU32(p + 32) == 2);
  REQUIRE(getU32(p + 36) == 1);
  const std::uint64_t payloadBytes = getU64(p + 40);
  REQUIRE(payloadBytes == 6u * 5 * 4 * 3 * 2 * 2);
  REQUIRE(b.size() == headerBytes + payloadBytes);
  REQUIRE(getU64(p + 48) == fnv1a64(std::string_view(b).substr(headerBytes)));
  REQUIRE(getU64(p + 48) == payloadChecksum(table, SampleType::Half));
  REQUIRE(std::string(p + 56) == "optical_depth");
  REQUIRE(std::string(p + 88) == "phi_s");        // axis 0 name
  REQUIRE(std::string(p + 88 + 16) == "rad");     // axis 0 unit
  REQUIRE(getF64(p + 88 + 32) == table.axes()[0].max);
  REQUIRE(getU32(p + 88 + 40) == 1);              // periodic
  REQUIRE(getU32(p + 88 + 48 + 40) == 0);         // theta_s is not
  REQUIRE(getU32(p + 88 + 44) == 0);              // axis 0: uniform nodes
  REQUIRE(getU32(p + 88 + 48 + 44) == 0x40e00000u); // axis 1: warp 7.0f
  REQUIRE(std::string(p + 280) == "mean_density");
  REQUIRE(std::string(p + 304) == "first_matter");
  REQUIRE(p[328] == 0);                           // unused channel slots are zero
  const std::uint32_t jsonBytes = getU32(p + 376);
  const auto json = nlohmann::json::parse(b.substr(380, jsonBytes));
  REQUIRE(json == describeTable(table, SampleType::Half));
  REQUIRE(headerBytes == (380 + jsonBytes + 7) / 8 * 8 + 8);
  REQUIRE(getU64(p + headerBytes - 8) ==
          fnv1a64(std::string_view(b).substr(0, headerBytes - 8)));
  // The first payload sample is node (0,0,0,0) channel 0, the second its channel 1.
  Imath::half h;
  h.setBits(getU16(p + headerBytes));
  REQUIRE(static_cast<float>(h) == static_cast<float>(Imath::half(table.at(0, 0))));
  h.setBits(getU16(p + headerBytes + 2));
  REQUIRE(static_cast<float>(h) == static_cast<float>(Imath::half(table.at(0, 1))));
}

TEST_CASE("io: sample type names and table description", "[io]") {
  using namespace cloudlut::io;
  REQUIRE(parseSampleType("u8") == SampleType::U8);
  REQUIRE(parseSampleType("half") == SampleType::Half);
  REQUIRE(parseSampleType("float") == SampleType::Float);
  REQUIRE_FALSE(parseSampleType("double"));
  for (SampleType t : {SampleType::U8, SampleType::Half, SampleType::Float})
    REQUIRE(parseSampleType(toString(t)) == t);
  const cloudlut::Table4D table = makeTable({4, 3, 2, 2}, 2);
  const auto d = describeTable(table, SampleType::Float);
  REQUIRE(d["name"] == "optical_depth");
  REQUIRE(d["dims"] == nlohmann::json({4, 3, 2, 2}));
  REQUIRE(d["texture_size"] == nlohmann::json({4, 3, 4}));
  REQUIRE(d["axes"][0]["periodic"] == true);
  REQUIRE(d["channels"][1]["name"] == "first_matter");
  REQUIRE(d["sample_type"] == "float");
  REQUIRE(d["payload_bytes"] == 4 * 3 * 2 * 2 * 2 * 4);
  REQUIRE(d["payload_fnv1a64"].get<std::string>().size() == 16);
  REQUIRE(d["parameters"]["model"] == "test");
}

TEST_CASE("io: binary writer rejects names that do not fit their fields", "[io]") {
  TempDir dir;
  const cloudlut::Table4D table =
      makeTable({2, 2, 2, 2}, 1, 0.0f, 1.0f, 1, std::string(40, 'x'));
  REQUIRE_THROWS_AS(cloudlut::io::writeBinaryLut(table, SampleType::Float, dir / "t.bin"),
                    cloudlut::UsageError);
  REQUIRE(listDir(dir.path()).empty());
}
