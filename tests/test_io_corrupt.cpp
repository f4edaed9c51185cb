// Damaged, foreign and hostile binary files: every one gives FileError, none crashes.
#include <catch2/catch.hpp>

#include "core/Errors.h"
#include "io/Fnv1a.h"
#include "io/LittleEndian.h"
#include "io/LutIo.h"
#include "support/Checks.h"
#include "support/Files.h"
#include "support/SmallTables.h"
#include "support/TempDir.h"

using cloudlut::io::SampleType;
using namespace cloudlut::test;

namespace {

// readLut's error message for a file holding `bytes`.
std::string errorFor(const TempDir& dir, const std::string& bytes) {
  const auto path = dir / "bad.bin";
  writeFile(path, bytes);
  return fileErrorOf([&] { cloudlut::io::readLut(path); });
}

// A valid file's bytes.
std::string goodFile(const TempDir& dir, SampleType type = SampleType::Half) {
  cloudlut::io::writeBinaryLut(makeTable({4, 3, 3, 2}, 2), type, dir / "good.bin");
  return readFile(dir / "good.bin");
}

// Overwrites a little-endian integer field and recomputes the header checksum, so that only
// the field itself is wrong.
void patchField(std::string& bytes, std::size_t offset, std::uint64_t value, int size) {
  const std::uint32_t headerBytes = cloudlut::io::getU32(bytes.data() + 12);
  std::string field;
  cloudlut::io::putLe(field, value, size);
  bytes.replace(offset, static_cast<std::size_t>(size), field);
  std::string sum;
  cloudlut::io::putU64(sum, cloudlut::io::fnv1a64(std::string_view(bytes).substr(0, headerBytes - 8)));
  bytes.replace(headerBytes - 8, 8, sum);
}

}  // namespace

TEST_CASE("io: truncated binary payload is reported with sizes", "[io]") {
  TempDir dir;
  const std::string good = goodFile(dir);
  const std::uint32_t headerBytes = cloudlut::io::getU32(good.data() + 12);
  const std::size_t payload = good.size() - headerBytes;
  const std::string message = errorFor(dir, good.substr(0, good.size() - 10));
  REQUIRE_THAT(message, Catch::Contains("truncated: expected " + std::to_string(payload) +
                                        " bytes of payload, found " +
                                        std::to_string(payload - 10)));
  REQUIRE_THAT(message, Catch::Contains("bad.bin"));
  REQUIRE_THAT(errorFor(dir, good.substr(0, 100)), Catch::Contains("truncated"));
  REQUIRE_THAT(errorFor(dir, good.substr(0, 5)), Catch::Contains("truncated"));
}

TEST_CASE("io: every truncation and every header byte flip gives FileError", "[io]") {
  TempDir dir;
  const std::string good = goodFile(dir, SampleType::U8);
  for (std::size_t n = 1; n < good.size(); ++n) errorFor(dir, good.substr(0, n));
  const std::uint32_t headerBytes = cloudlut::io::getU32(good.data() + 12);
  for (std::size_t k = 0; k < headerBytes; ++k) {
    std::string bad = good;
    bad[k] = static_cast<char>(bad[k] ^ 0x01);
    errorFor(dir, bad);
  }
  errorFor(dir, good + "x");  // trailing bytes
}

TEST_CASE("io: a flipped payload byte is a checksum mismatch", "[io]") {
  TempDir dir;
  std::string bad = goodFile(dir);
  bad[bad.size() - 3] = static_cast<char>(bad[bad.size() - 3] ^ 0x10);
  REQUIRE_THAT(errorFor(dir, bad), Catch::EndsWith(": checksum mismatch"));
  std::string badHeader = goodFile(dir);
  badHeader[60] = static_cast<char>(badHeader[60] ^ 0x10);  // inside the table name
  REQUIRE_THAT(errorFor(dir, badHeader), Catch::Contains("header checksum mismatch"));
}

TEST_CASE("io: an unsupported format version is named", "[io]") {
  TempDir dir;
  std::string bad = goodFile(dir);
  bad[8] = 7;
  REQUIRE_THAT(errorFor(dir, bad),
               Catch::EndsWith("unsupported format version 7 (this build reads 1 to 3)"));
}

TEST_CASE("io: empty, missing and foreign files are not LUTs", "[io]") {
  TempDir dir;
  REQUIRE_THAT(errorFor(dir, ""), Catch::Contains("not a cloudlut LUT"));
  REQUIRE_THAT(errorFor(dir, "P6\n2 2\n255\n0123456789ab"),
               Catch::EndsWith("not a cloudlut LUT (bad magic)"));
  REQUIRE_THAT(fileErrorOf([&] { cloudlut::io::readLut(dir / "nothing.bin"); }),
               Catch::EndsWith("missing"));
  REQUIRE_THAT(fileErrorOf([&] { cloudlut::io::readLut(dir.path()); }),
               Catch::Contains("not a regular file"));
  // Random garbage, alone and behind each magic.
  std::uint32_t state = 12345;
  for (int trial = 0; trial < 200; ++trial) {
    std::string junk(static_cast<std::size_t>(trial * 7 + 1), '\0');
    for (char& c : junk) {
      state = state * 1664525u + 1013904223u;
      c = static_cast<char>(state >> 24);
    }
    errorFor(dir, junk);
    errorFor(dir, "CLOUDLUT" + junk);
    errorFor(dir, std::string("CLOUDLUT\x01\0\0\0\x88\x01\0\0", 16) + junk);
    errorFor(dir, std::string("\x76\x2f\x31\x01", 4) + junk);
  }
}

TEST_CASE("io: a header claiming a huge payload is checked against the file size", "[io]") {
  TempDir dir;
  std::string bad = goodFile(dir, SampleType::U8);
  // 10000 × 10000 × 100 × 100 one-byte samples of one channel: 10^12 bytes, consistently.
  patchField(bad, 16, 10000, 4);
  patchField(bad, 20, 10000, 4);
  patchField(bad, 24, 100, 4);
  patchField(bad, 28, 100, 4);
  patchField(bad, 32, 1, 4);
  patchField(bad, 40, 1000000000000ull, 8);
  REQUIRE_THAT(errorFor(dir, bad),
               Catch::Contains("truncated: expected 1000000000000 bytes of payload, found"));
  // Dimensions whose product overflows 64 bits.
  patchField(bad, 16, 0xffffffffu, 4);
  patchField(bad, 20, 0xffffffffu, 4);
  patchField(bad, 24, 0xffffffffu, 4);
  REQUIRE_THAT(errorFor(dir, bad), Catch::Contains("corrupt header"));
  // A header size larger than any header.
  std::string hugeHeader = goodFile(dir);
  patchField(hugeHeader, 12, 0xfffffff8u, 4);
  REQUIRE_THAT(errorFor(dir, hugeHeader), Catch::Contains("corrupt header"));
  // A description length larger than the header.
  std::string hugeJson = goodFile(dir);
  patchField(hugeJson, 376, 0xffffffffu, 4);
  REQUIRE_THAT(errorFor(dir, hugeJson), Catch::Contains("corrupt header"));
  // Inconsistent payload size, sample type, channel count, zero-sized axis.
  for (const auto& [offset, value] : std::vector<std::pair<std::size_t, std::uint32_t>>{
           {40, 12345}, {36, 9}, {32, 0}, {32, 5}, {16, 0}}) {
    std::string b = goodFile(dir);
    patchField(b, offset, value, offset == 40 ? 8 : 4);
    REQUIRE_THAT(errorFor(dir, b), Catch::Contains("corrupt header"));
  }
}
