// manifest.json round trips and errors; atomic writes into missing or unwritable directories.
#include <unistd.h>

#include <catch2/catch.hpp>

#include "core/Errors.h"
#include "io/LutIo.h"
#include "support/Checks.h"
#include "support/Files.h"
#include "support/SmallTables.h"
#include "support/TempDir.h"

using cloudlut::io::SampleType;
using namespace cloudlut::test;

namespace {

// A LUT set of two tables: optical_depth in bin (u8) and exr (half), single_scattering in exr.
nlohmann::json writeSet(const std::filesystem::path& dir) {
  using namespace cloudlut::io;
  const cloudlut::Table4D od = makeTable({5, 4, 3, 2}, 2);
  const cloudlut::Table4D ss =
      makeTable({4, 3, 3, 2}, 1, 0.0f, 5.0f, 7, "single_scattering");
  writeBinaryLut(od, SampleType::U8, dir / "optical_depth.bin");
  writeExrLut(od, SampleType::Half, dir / "optical_depth.exr");
  writeExrLut(ss, SampleType::Float, dir / "single_scattering.exr");
  nlohmann::json odEntry = describeTable(od, SampleType::U8);
  odEntry["files"] = {{"bin", "optical_depth.bin"}, {"exr", "optical_depth.exr"}};
  nlohmann::json ssEntry = describeTable(ss, SampleType::Float);
  ssEntry["files"] = {{"exr", "single_scattering.exr"}};
  const nlohmann::json manifest = {
      {"format", "cloudlut-lut-set"},
      {"version", 1},
      {"generator", "cloudlut tests"},
      {"parameters", {{"extinction", 0.07}}},
      {"tables", {{"optical_depth", odEntry}, {"single_scattering", ssEntry}}}};
  writeManifest(dir, manifest);
  return manifest;
}

}  // namespace

TEST_CASE("io: manifest round trip loads every table, preferring bin", "[io]") {
  TempDir dir;
  const nlohmann::json manifest = writeSet(dir.path());
  const cloudlut::io::LutSet set = cloudlut::io::readLutSet(dir.path());
  REQUIRE(set.dir == dir.path());
  REQUIRE(set.manifest == manifest);
  REQUIRE(set.tables.size() == 2);
  const auto& od = set.tables.at("optical_depth");
  REQUIRE(od.sampleType == SampleType::U8);
  REQUIRE(od.path == dir / "optical_depth.bin");
  REQUIRE(od.table.dims() == std::array<int, 4>{5, 4, 3, 2});
  const auto& ss = set.tables.at("single_scattering");
  REQUIRE(ss.sampleType == SampleType::Float);
  REQUIRE(ss.table.data() ==
          makeTable({4, 3, 3, 2}, 1, 0.0f, 5.0f, 7, "single_scattering").data());
  // No temporary files are left behind.
  for (const std::string& name : listDir(dir.path()))
    REQUIRE(name.find(".tmp.") == std::string::npos);
}

TEST_CASE("io: readLutSet reports bad manifests", "[io]") {
  TempDir dir;
  const auto manifestPath = dir / "manifest.json";

  SECTION("missing manifest") {
    REQUIRE_THAT(fileErrorOf([&] { cloudlut::io::readLutSet(dir.path()); }),
                 Catch::Contains("manifest.json: missing"));
  }
  SECTION("invalid JSON") {
    writeFile(manifestPath, "{\"format\": \"cloudlut-lut-set\", ");
    REQUIRE_THAT(fileErrorOf([&] { cloudlut::io::readLutSet(dir.path()); }),
                 Catch::Contains("invalid JSON"));
  }
  SECTION("wrong format, wrong version, no tables") {
    nlohmann::json m = writeSet(dir.path());
    m["format"] = "something-else";
    cloudlut::io::writeManifest(dir.path(), m);
    REQUIRE_THAT(fileErrorOf([&] { cloudlut::io::readLutSet(dir.path()); }),
                 Catch::Contains("not a cloudlut manifest"));
    m["format"] = "cloudlut-lut-set";
    m["version"] = 4;
    cloudlut::io::writeManifest(dir.path(), m);
    REQUIRE_THAT(fileErrorOf([&] { cloudlut::io::readLutSet(dir.path()); }),
                 Catch::Contains("unsupported manifest version 4 (this build reads 1 to 3)"));
    m["version"] = 1;
    m.erase("tables");
    cloudlut::io::writeManifest(dir.path(), m);
    REQUIRE_THAT(fileErrorOf([&] { cloudlut::io::readLutSet(dir.path()); }),
                 Catch::Contains("no \"tables\""));
  }
  SECTION("missing table file") {
    writeSet(dir.path());
    std::filesystem::remove(dir / "single_scattering.exr");
    const std::string message = fileErrorOf([&] { cloudlut::io::readLutSet(dir.path()); });
    REQUIRE_THAT(message, Catch::Contains("single_scattering.exr: missing"));
  }
  SECTION("dims that do not match the file") {
    nlohmann::json m = writeSet(dir.path());
    m["tables"]["optical_depth"]["dims"] = {5, 4, 3, 3};
    cloudlut::io::writeManifest(dir.path(), m);
    REQUIRE_THAT(fileErrorOf([&] { cloudlut::io::readLutSet(dir.path()); }),
                 Catch::Contains("dimensions 5x4x3x2 do not match manifest.json's 5x4x3x3"));
  }
  SECTION("a file outside the directory, a table without files") {
    nlohmann::json m = writeSet(dir.path());
    m["tables"]["optical_depth"]["files"] = {{"bin", "../optical_depth.bin"}};
    cloudlut::io::writeManifest(dir.path(), m);
    REQUIRE_THAT(fileErrorOf([&] { cloudlut::io::readLutSet(dir.path()); }),
                 Catch::Contains("outside the LUT directory"));
    m["tables"]["optical_depth"]["files"] = nlohmann::json::object();
    cloudlut::io::writeManifest(dir.path(), m);
    REQUIRE_THAT(fileErrorOf([&] { cloudlut::io::readLutSet(dir.path()); }),
                 Catch::Contains("neither"));
  }
  SECTION("a damaged table file") {
    writeSet(dir.path());
    std::string bytes = readFile(dir / "optical_depth.bin");
    bytes.resize(bytes.size() - 1);
    writeFile(dir / "optical_depth.bin", bytes);
    REQUIRE_THAT(fileErrorOf([&] { cloudlut::io::readLutSet(dir.path()); }),
                 Catch::Contains("optical_depth.bin: truncated"));
  }
}

TEST_CASE("io: writing into a missing or unwritable directory is a usage error", "[io]") {
  TempDir dir;
  const cloudlut::Table4D table = makeTable({2, 2, 2, 2}, 1);
  const auto missing = dir / "no" / "such" / "dir";
  REQUIRE_THROWS_AS(cloudlut::io::writeBinaryLut(table, SampleType::Float, missing / "t.bin"),
                    cloudlut::UsageError);
  REQUIRE_THROWS_AS(cloudlut::io::writeExrLut(table, SampleType::Float, missing / "t.exr"),
                    cloudlut::UsageError);
  REQUIRE_THROWS_AS(cloudlut::io::writeManifest(missing, nlohmann::json::object()),
                    cloudlut::UsageError);
  try {
    cloudlut::io::writeFileAtomically(missing / "x", "abc");
    FAIL("expected a UsageError");
  } catch (const cloudlut::UsageError& e) {
    REQUIRE_THAT(e.what(), Catch::Contains(missing.string()));
  }
  // A parent that is a file, not a directory.
  writeFile(dir / "file", "x");
  REQUIRE_THROWS_AS(cloudlut::io::writeFileAtomically(dir / "file" / "x", "abc"),
                    cloudlut::UsageError);
  REQUIRE(listDir(dir.path()) == std::vector<std::string>{"file"});

  // A directory nobody can create files in, not even root.
  if (std::filesystem::is_directory("/proc/self")) {
    try {
      cloudlut::io::writeFileAtomically("/proc/self/cloudlut_io_test", "abc");
      FAIL("expected a UsageError");
    } catch (const cloudlut::UsageError& e) {
      REQUIRE_THAT(e.what(), Catch::Contains("/proc/self"));
    }
  }
  if (::geteuid() != 0) {  // root writes anywhere, so this part only runs for other users
    const auto locked = dir / "locked";
    std::filesystem::create_directory(locked);
    std::filesystem::permissions(locked, std::filesystem::perms::owner_read |
                                             std::filesystem::perms::owner_exec);
    try {
      cloudlut::io::writeFileAtomically(locked / "x", "abc");
      FAIL("expected a UsageError");
    } catch (const cloudlut::UsageError& e) {
      REQUIRE_THAT(e.what(), Catch::Contains(locked.string()));
    }
    std::filesystem::permissions(locked, std::filesystem::perms::owner_all);
    REQUIRE(listDir(locked).empty());
  }
}

TEST_CASE("io: atomic writes replace whole files", "[io]") {
  TempDir dir;
  cloudlut::io::writeFileAtomically(dir / "a.txt", "first version, longer");
  cloudlut::io::writeFileAtomically(dir / "a.txt", "second");
  REQUIRE(readFile(dir / "a.txt") == "second");
  REQUIRE(listDir(dir.path()) == std::vector<std::string>{"a.txt"});
}
