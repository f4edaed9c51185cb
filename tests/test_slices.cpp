// `cloudlut slices`: a contact sheet is written for a LUT directory and for a single table
// file, non-finite values are counted and drawn, bad options are usage errors.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <limits>

#include "support/CliRunner.h"
#include "io/ContactSheet.h"
#include "io/LutIo.h"

using namespace cloudlut;
using namespace cloudlut::test;

namespace {
Table4D rampTable() {
  Table4D t("ramp", {Axis{"a", "", 0, 1, 5, false}, Axis{"b", "", 0, 1, 4, false}, Axis{"c", "", 0, 1, 3, false},
                     Axis{"d", "", 0, 1, 2, false}},
            {{"value", ""}});
  for (std::size_t n = 0; n < t.nodeCount(); ++n) t.at(n, 0) = static_cast<float>(n) / static_cast<float>(t.nodeCount());
  return t;
}
}  // namespace

TEST_CASE("contact sheet draws every slice and marks non-finite values magenta", "[slices]") {
  Table4D t = rampTable();
  t.at(t.index(2, 1, 1, 1), 0) = std::numeric_limits<float>::quiet_NaN();
  const io::RgbImage img = io::drawContactSheet(t, "ramp", {});
  REQUIRE(img.width > 0);
  REQUIRE(img.rgb.size() == static_cast<std::size_t>(img.width) * img.height * 3);
  std::size_t magenta = 0;
  for (std::size_t i = 0; i < img.rgb.size(); i += 3)
    if (img.rgb[i] == 255 && img.rgb[i + 1] == 0 && img.rgb[i + 2] == 255) ++magenta;
  // the NaN cell is drawn as a scale×scale magenta square (scale = 48 / min(5, 4) = 12), plus the
  // magenta "1 non-finite" legend text
  CHECK(magenta >= 12u * 12u);
}

TEST_CASE("slices verb writes a PNG for a directory and a file", "[slices][cli]") {
  TempDir tmp;
  REQUIRE(runCli("bake --tables optical-depth --res-od 8,4,8,4 --quiet --out '" + (tmp / "luts").string() + "'").exitCode == 0);
  const CliResult dir = runCli("slices '" + (tmp / "luts").string() + "' --out '" + (tmp / "a.png").string() + "'");
  CHECK(dir.exitCode == 0);
  CHECK(readFile(tmp / "a.png").substr(1, 3) == "PNG");
  const CliResult file = runCli("slices '" + (tmp / "luts" / "optical_depth.bin").string() + "' --channel 1 --out '" +
                                (tmp / "b.png").string() + "'");
  CHECK(file.exitCode == 0);
  CHECK(std::filesystem::exists(tmp / "b.png"));
  CHECK(runCli("slices '" + (tmp / "luts").string() + "' --channel 5 --out '" + (tmp / "c.png").string() + "'").exitCode == 2);
  CHECK(runCli("slices '" + (tmp / "luts").string() + "' --out '" + (tmp / "c.jpg").string() + "'").exitCode == 2);
  CHECK(runCli("slices '" + (tmp / "missing").string() + "' --out '" + (tmp / "c.png").string() + "'").exitCode == 1);
  CHECK_FALSE(std::filesystem::exists(tmp / "c.png"));
}
