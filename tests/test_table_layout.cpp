// The scattering tables' layout of format version 3: φv folded onto [0, π] by the sphere's
// mirror symmetry, the density axis interpolated linearly in ρ, the axis flags that say so in
// the files (binary, EXR, the engine kit's reader), and the readers of versions 1 and 2.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include <cloudlut_lut.h>

#include "bake/ScatteringBaker.h"
#include "core/Errors.h"
#include "core/Glsl.h"
#include "core/TableLookup.h"
#include "io/Fnv1a.h"
#include "io/LittleEndian.h"
#include "io/LutIo.h"
#include "support/TempDir.h"

using namespace cloudlut;

namespace {

constexpr double kPi = 3.14159265358979323846;

std::string readAll(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void writeAll(const std::filesystem::path& p, const std::string& bytes) {
  std::ofstream(p, std::ios::binary) << bytes;
}

// Rewrites the version word of a binary LUT and re-seals its header checksum, as an older
// writer would have sealed it.
void setBinaryVersion(const std::filesystem::path& p, std::uint32_t version) {
  std::string bytes = readAll(p);
  const std::uint32_t headerBytes = io::getU32(bytes.data() + 12);
  std::string v;
  io::putU32(v, version);
  bytes.replace(8, 4, v);
  std::string sum;
  io::putU64(sum, io::fnv1a64(std::string_view(bytes).substr(0, headerBytes - 8)));
  bytes.replace(headerBytes - 8, 8, sum);
  writeAll(p, bytes);
}

}  // namespace

TEST_CASE("An unfolded bake equals the folded table mirrored", "[scattering][layout]") {
  // Same φv nodes: 9 over [0, π] (folded) and 17 over [0, 2π] (unfolded), π/8 apart. The
  // unfolded bake computes both halves independently; the symmetry J(φv) = J(2π − φv) is what
  // makes the folded table complete.
  bake::ScatteringSettings s;
  s.dims = {9, 9, 5, 3};
  s.sMin = -3;
  s.sMax = 1;
  s.orders = 4;
  const bake::ScatteringResult folded = bake::bakeScattering(s);
  s.foldPhiV = false;
  s.dims[1] = 17;
  const bake::ScatteringResult full = bake::bakeScattering(s);
  REQUIRE(folded.single->axes()[1].folded);
  REQUIRE(folded.single->axes()[1].max == Approx(kPi));
  REQUIRE_FALSE(full.single->axes()[1].folded);
  REQUIRE(full.single->axes()[1].periodic);
  for (const auto& [a, b] : {std::pair{&*folded.single, &*full.single}, std::pair{&*folded.multiple, &*full.multiple}}) {
    double worst = 0.0;
    for (int k = 0; k < 3; ++k)
      for (int iV = 0; iV < 5; ++iV)
        for (int iP = 0; iP < 17; ++iP)
          for (int iS = 0; iS < 9; ++iS) {
            const float u = b->at(b->index(iS, iP, iV, k), 0);
            const float f = a->at(a->index(iS, iP <= 8 ? iP : 16 - iP, iV, k), 0);
            worst = std::max(worst, static_cast<double>(std::abs(u - f)) / std::max(1e-3, std::abs(static_cast<double>(u))));
          }
    INFO(a->name() << ": largest relative difference " << worst);
    CHECK(worst < 2e-5);
    // and the lookups agree at geometry in both halves of φv
    const glm::vec3 S(0.48f, 0.0f, 0.877f), l(0.0f, 0.0f, 1.0f);
    for (float y : {-0.5f, -0.1f, 0.2f, 0.6f}) {
      const glm::vec3 v = glm::normalize(glm::vec3(-0.7f, y, -0.4f));
      CHECK(sampleScattering(*a, S, v, l, 0.7f) == Approx(sampleScattering(*b, S, v, l, 0.7f)).epsilon(2e-3).margin(1e-5));
    }
  }
}

TEST_CASE("Version 3 files describe the folded axis and the density interpolation", "[io][layout]") {
  bake::ScatteringSettings s;
  s.dims = {5, 5, 3, 3};
  s.orders = 2;
  s.multiple = false;
  const Table4D t = *bake::bakeScattering(s).single;
  test::TempDir dir;
  io::writeBinaryLut(t, io::SampleType::Float, dir / "t.bin");
  io::writeExrLut(t, io::SampleType::Float, dir / "t.exr");
  for (const char* name : {"t.bin", "t.exr"}) {
    const io::LoadedTable r = io::readLut(dir / name);
    INFO(name);
    CHECK(r.table.axes()[1].folded);
    CHECK_FALSE(r.table.axes()[1].periodic);
    CHECK(r.table.axes()[3].linearInExp2);
    CHECK_FALSE(r.table.axes()[0].folded);
    CHECK_FALSE(r.table.axes()[2].linearInExp2);
    CHECK(scatteringAxesRecord(r.table).w == Approx(3.0f));
  }
  // the engine kit's reader sees the same flags and the same axes record
  const cloudlut_reader::Lut k = cloudlut_reader::readLut((dir / "t.bin").string());
  CHECK(k.version == 3);
  CHECK(k.axes[1].folded);
  CHECK(k.axes[3].linearInExp2);
  CHECK_FALSE(k.axes[1].periodic);
  const auto rec = k.scatteringAxesRecord();
  const glm::vec4 mine = scatteringAxesRecord(t);
  CHECK(rec[0] == mine.x);
  CHECK(rec[1] == mine.y);
  CHECK(rec[2] == mine.z);
  CHECK(rec[3] == mine.w);

  // An older version cannot carry the new flags: a version-2 header with them is corrupt.
  setBinaryVersion(dir / "t.bin", 2);
  CHECK_THROWS_WITH(io::readLut(dir / "t.bin"), Catch::Contains("axis 1 has flag bits reserved in version 2"));
  CHECK_THROWS_WITH(cloudlut_reader::readLut((dir / "t.bin").string()), Catch::Contains("axis flags"));
}

TEST_CASE("Version 2 scattering tables are still read and sampled the old way", "[io][layout]") {
  // A version-2 writer's table: φv over [0, 2π] periodic, density linear in log2 ρ.
  bake::ScatteringSettings s;
  s.dims = {5, 9, 3, 3};
  s.orders = 2;
  s.multiple = false;
  s.foldPhiV = false;
  Table4D t = *bake::bakeScattering(s).single;
  std::array<Axis, 4> axes = t.axes();
  axes[3].linearInExp2 = false;
  Table4D old(t.name(), axes, t.channels());
  old.data() = t.data();
  old.parameters() = t.parameters();
  test::TempDir dir;
  io::writeBinaryLut(old, io::SampleType::Float, dir / "old.bin");
  setBinaryVersion(dir / "old.bin", 2);
  const io::LoadedTable r = io::readLut(dir / "old.bin");
  CHECK_FALSE(r.table.axes()[1].folded);
  CHECK_FALSE(r.table.axes()[3].linearInExp2);
  CHECK(scatteringAxesRecord(r.table).w == 0.0f);
  CHECK(cloudlut_reader::readLut((dir / "old.bin").string()).version == 2);
  // layout 0: density fraction linear in log2 ρ, φv/2π
  const glm::vec3 S(0.48f, 0.0f, 0.877f), l(0.0f, 0.0f, 1.0f), v = glm::normalize(glm::vec3(-0.7f, -0.3f, -0.4f));
  const glm::vec4 x = glsl::scatteringAxes(S, v, l, 0.5f, scatteringAxesRecord(r.table), 3.0f);
  CHECK(x.w == Approx(glsl::densityAxis(0.5f, static_cast<float>(s.sMin), static_cast<float>(s.sMax))));
  CHECK(x.y > 0.5f);  // v.y < 0: φv in (π, 2π), not folded
}

TEST_CASE("Between density slices the tables interpolate linearly in rho", "[scattering][layout]") {
  // Two slices one octave apart: at ρ between them the stored value is the blend of the two
  // slices with the weight (ρ − ρ0)/(ρ1 − ρ0), computed here from the slices directly.
  bake::ScatteringSettings s;
  s.dims = {9, 9, 5, 2};
  s.sMin = 0;
  s.sMax = 1;
  s.orders = 2;
  s.single = true;
  s.multiple = false;
  const Table4D t = *bake::bakeScattering(s).single;
  const glm::vec3 S(0.0f, 0.0f, 1.0f), l(0.0f, 0.0f, 1.0f);
  // S at the pole, v straight in: every axis fraction on a node (θS = 0, θv = 0)
  const glm::vec3 v(0.0f, 0.0f, -1.0f);
  const float lo = t.at(t.index(0, 0, 0, 0), 0), hi = t.at(t.index(0, 0, 0, 1), 0);
  for (float rho : {1.0f, 1.2f, 1.5f, 1.9f, 2.0f}) {
    const float w = (rho - 1.0f) / (2.0f - 1.0f);
    CHECK(sampleScattering(t, S, v, l, rho) == Approx(lo + w * (hi - lo)).margin(1e-5));
  }
}
