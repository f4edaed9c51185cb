// io/ManifestSchema.h: the manifest a writer builds passes the checks its readers make, and a
// writer cannot build one they would refuse.
#include <catch2/catch.hpp>

#include <filesystem>
#include <random>

#include "core/Errors.h"
#include "io/LutIo.h"
#include "io/ManifestSchema.h"

using namespace cloudlut;

namespace {

Table4D smallTable(const std::string& name) {
  const std::array<Axis, 4> axes{Axis{"a", "rad", 0.0, 1.0, 3, false}, Axis{"b", "rad", 0.0, 1.0, 2, false},
                                 Axis{"c", "rad", 0.0, 1.0, 2, false}, Axis{"d", "log2", -1.0, 1.0, 2, false}};
  Table4D t(name, axes, {Channel{"value", "test"}});
  for (std::size_t n = 0; n < t.nodeCount(); ++n) t.at(n, 0) = 0.125f * static_cast<float>(n % 7);
  return t;
}

}  // namespace

TEST_CASE("manifest schema: written entries and documents read back", "[io][manifest]") {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("cloudlut-schema-" + std::to_string(std::random_device{}()));
  std::filesystem::create_directories(dir);
  const Table4D table = smallTable("optical_depth");
  const nlohmann::json entry = io::writeTableFiles(table, io::SampleType::U8, dir, {});
  CHECK(entry["files"]["bin"] == "optical_depth.bin");
  CHECK(entry["files"]["exr"] == "optical_depth.exr");
  CHECK(entry["exr_sample_type"] == "half");  // EXR holds no 8-bit samples
  CHECK(entry["sample_type"] == "u8");
  const nlohmann::json manifest = io::makeManifest("cloudlut tests", {{"optical_depth", entry}});
  CHECK(manifest["format"] == io::kManifestFormat);
  CHECK(manifest["version"] == io::kFormatVersion);
  io::writeManifest(dir, manifest);
  const io::LutSet set = io::readLutSet(dir);
  REQUIRE(set.tables.count("optical_depth") == 1);
  CHECK(set.tables.at("optical_depth").sampleType == io::SampleType::U8);
  CHECK(set.tables.at("optical_depth").table.dims() == table.dims());
  std::filesystem::remove_all(dir);
}

TEST_CASE("manifest schema: a writer cannot build what readers refuse", "[io][manifest]") {
  const nlohmann::json good = {{"dims", {3, 2, 2, 2}}, {"files", {{"bin", "t.bin"}}}};
  CHECK_NOTHROW(io::makeManifest("g", {{"t", good}}));
  nlohmann::json noFiles = good;
  noFiles.erase("files");
  CHECK_THROWS_WITH(io::makeManifest("g", {{"t", noFiles}}), Catch::Contains("table 't' has no \"files\" object"));
  nlohmann::json outside = good;
  outside["files"]["bin"] = "../t.bin";
  CHECK_THROWS_WITH(io::makeManifest("g", {{"t", outside}}), Catch::Contains("outside the LUT directory"));
  nlohmann::json badDims = good;
  badDims["dims"] = {3, 2, 2};
  CHECK_THROWS_WITH(io::makeManifest("g", {{"t", badDims}}), Catch::Contains("gives no \"dims\" for table 't'"));
  CHECK_THROWS_AS(io::makeManifest("g", nlohmann::json::array()), FileError);
  CHECK_THROWS_WITH(io::checkManifest({{"format", "x"}}, "m.json"), Catch::Contains("m.json: not a cloudlut manifest"));
  CHECK_THROWS_WITH(io::checkManifest({{"format", io::kManifestFormat}, {"version", 99}, {"tables", nlohmann::json::object()}}, "m.json"),
                    Catch::Contains("unsupported manifest version 99"));
}
