// The `cloudlut` executable end to end: bake, info, check, query, and every bad-input case
// giving one clear message, the right exit code and nothing written.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "support/CliRunner.h"
#include "core/Defaults.h"
#include "io/LutIo.h"

using namespace cloudlut;
using namespace cloudlut::test;
namespace fs = std::filesystem;

namespace {
const std::string kSmall = "--tables optical-depth --res-od 16,8,16,8 --quiet";

std::size_t lineCount(const std::string& s) { return static_cast<std::size_t>(std::count(s.begin(), s.end(), '\n')); }
}  // namespace

TEST_CASE("usage errors exit 2 with one line on stderr and write nothing", "[cli]") {
  TempDir tmp;
  const std::string out = (tmp / "luts").string();
  const char* cases[] = {
      "frobnicate",
      "bake --no-such-option",
      "bake --density-model cumulonimbus",
      "bake --res-od 64,32,64",
      "bake --res-od 64,0,64,32",
      "bake --res-od 64,-3,64,32",
      "bake --res-od 64,x,64,32",
      "bake --res-od 65536,65536,65536,65536",  // would not fit in memory
      "bake --format png",
      "bake --precision double",
      "bake --format exr --precision u8",
      "bake --tables everything",
      "bake --steps -1",
      "bake --extinction 0",
      "bake --radius -5",
      "bake --threads -2",
  };
  for (const char* c : cases) {
    INFO(c);
    const CliResult r = runCli(std::string(c) + " --out '" + out + "'");
    CHECK(r.exitCode == 2);
    CHECK(lineCount(r.err) == 1);
    CHECK(r.err.find("error") != std::string::npos);
    CHECK_FALSE(fs::exists(out));
  }
}

TEST_CASE("a value that is not a number names its option", "[cli]") {
  TempDir tmp;
  const std::string out = (tmp / "luts").string();
  for (const std::string option : {"--steps", "--threads", "--extinction"})
    for (const std::string form : {" ", "="}) {
      const std::string c = "bake " + option + form + "many --out '" + out + "'";
      INFO(c);
      const CliResult r = runCli(c);
      CHECK(r.exitCode == 2);
      CHECK(lineCount(r.err) == 1);
      CHECK(r.err.find(option + ": 'many'") != std::string::npos);
      CHECK_FALSE(fs::exists(out));
    }
}

TEST_CASE("an unwritable --out is a usage error", "[cli]") {
  TempDir tmp;
  std::ofstream(tmp / "file") << "x";
  const CliResult r = runCli("bake " + kSmall + " --out '" + (tmp / "file" / "luts").string() + "'");
  CHECK(r.exitCode == 2);
  CHECK(lineCount(r.err) == 1);
  CHECK(r.err.find("output directory") != std::string::npos);
}

TEST_CASE("bake writes a manifest and both formats; info describes them", "[cli]") {
  TempDir tmp;
  const std::string out = (tmp / "luts").string();
  const CliResult bake = runCli("bake " + kSmall + " --out '" + out + "'");
  REQUIRE(bake.exitCode == 0);
  CHECK(bake.err.empty());  // no TTY: quiet
  CHECK(fs::exists(tmp / "luts" / "manifest.json"));
  CHECK(fs::exists(tmp / "luts" / "optical_depth.bin"));
  CHECK(fs::exists(tmp / "luts" / "optical_depth.exr"));
  for (const auto& e : fs::directory_iterator(tmp / "luts"))
    CHECK(e.path().filename().string().find(".tmp") == std::string::npos);

  const CliResult info = runCli("info '" + out + "' --json");
  REQUIRE(info.exitCode == 0);
  const auto j = nlohmann::json::parse(info.out);
  REQUIRE(j["tables"].size() == 2);  // the bin and the exr file, each verified
  for (const auto& t : j["tables"]) {
    CHECK(t["name"] == "optical_depth");
    CHECK(t["dims"] == nlohmann::json({16, 8, 16, 8}));
    CHECK(t["checksum_status"] == "ok");
    CHECK(t["statistics"][0]["max"].get<double>() <= 1.0);
    CHECK(t["statistics"][0]["non_finite"] == 0);
  }
  const CliResult human = runCli("info '" + out + "/optical_depth.bin'");
  CHECK(human.exitCode == 0);
  CHECK(human.out.find("phi_s") != std::string::npos);
}

TEST_CASE("bake output does not depend on the thread count", "[cli]") {
  TempDir tmp;
  REQUIRE(runCli("bake " + kSmall + " --format bin --threads 1 --out '" + (tmp / "a").string() + "'").exitCode == 0);
  REQUIRE(runCli("bake " + kSmall + " --format bin --threads 2 --out '" + (tmp / "b").string() + "'").exitCode == 0);
  CHECK(readFile(tmp / "a" / "optical_depth.bin") == readFile(tmp / "b" / "optical_depth.bin"));
}

TEST_CASE("check passes on identical tables and catches one perturbed value", "[cli]") {
  TempDir tmp;
  const std::string golden = (tmp / "golden").string();
  REQUIRE(runCli("bake " + kSmall + " --format bin --precision float --out '" + golden + "'").exitCode == 0);
  const CliResult same = runCli("check '" + golden + "' --golden '" + golden + "'");
  CHECK(same.exitCode == 0);

  // A copy with one value moved by 0.01, written with a valid checksum.
  fs::copy(golden, tmp / "perturbed", fs::copy_options::recursive);
  io::LutSet set = io::readLutSet(tmp / "perturbed");
  Table4D table = set.tables.at("optical_depth").table;
  const std::size_t node = table.index(5, 3, 7, 2);
  table.at(node, 0) += 0.01f;
  io::writeBinaryLut(table, io::SampleType::Float, tmp / "perturbed" / "optical_depth.bin");
  auto manifest = set.manifest;
  manifest["tables"]["optical_depth"]["checksum"] = io::describeTable(table, io::SampleType::Float)["checksum"];
  io::writeManifest(tmp / "perturbed", manifest);

  const CliResult diff = runCli("check '" + (tmp / "perturbed").string() + "' --golden '" + golden + "'");
  CHECK(diff.exitCode == 1);
  CHECK(diff.out.find("1 of") != std::string::npos);
  CHECK(diff.out.find("phi_s[5]") != std::string::npos);
  CHECK(diff.out.find("theta_v[2]") != std::string::npos);
  // a looser tolerance accepts it
  CHECK(runCli("check '" + (tmp / "perturbed").string() + "' --golden '" + golden + "' --atol 0.02").exitCode == 0);
}

TEST_CASE("query evaluates the optical depth of the homogeneous sphere exactly", "[cli]") {
  TempDir tmp;
  const std::string out = (tmp / "luts").string();
  REQUIRE(runCli("bake --tables optical-depth --res-od 16,8,16,8 --quiet --density-model sphere --precision float --out '" + out + "'").exitCode == 0);
  std::ofstream(tmp / "in.csv") << "sx,sy,sz,vx,vy,vz,lx,ly,lz,density\n"
                                   "0,0,1,0,0,-1,0,0,1,0.5\n"           // through the centre: L = 2
                                   "1,0,0,-0.6,0.8,0,0,0,1,2\n";       // L = 2·0.6
  const CliResult r = runCli("query '" + out + "' --csv '" + (tmp / "in.csv").string() + "'");
  REQUIRE(r.exitCode == 0);
  std::istringstream lines(r.out);
  std::string header, row1, row2;
  std::getline(lines, header);
  std::getline(lines, row1);
  std::getline(lines, row2);
  CHECK(header == "sx,sy,sz,vx,vy,vz,lx,ly,lz,density,optical_depth,transmittance,optical_radius,single,multiple");
  auto column = [](const std::string& row, int k) {
    std::istringstream ss(row);
    std::string f;
    for (int i = 0; i <= k; ++i) std::getline(ss, f, ',');
    return std::stod(f);
  };
  const double sigma = defaults::kUnitOpticalRadius;  // the bake's default β·R
  CHECK(column(row1, 10) == Approx(sigma * 0.5 * 2.0).epsilon(1e-5));
  CHECK(column(row2, 10) == Approx(sigma * 2.0 * 1.2).epsilon(1e-5));
  CHECK(column(row1, 11) == Approx(std::exp(-sigma)).epsilon(1e-4));
}

TEST_CASE("info, check and query reject bad files with a message naming the file", "[cli]") {
  TempDir tmp;
  const std::string good = (tmp / "good").string();
  REQUIRE(runCli("bake " + kSmall + " --out '" + good + "'").exitCode == 0);
  const std::string bin = readFile(tmp / "good" / "optical_depth.bin");

  std::ofstream(tmp / "in.csv") << "sx,sy,sz,vx,vy,vz,lx,ly,lz,density\n0,0,1,0,0,-1,0,0,1,1\n";
  struct Bad { std::string name, bytes; };
  std::string flipped = bin;
  flipped[flipped.size() - 10] = static_cast<char>(flipped[flipped.size() - 10] ^ 0x5a);
  std::string version = bin;
  version[8] = 7;  // the format version follows the 8-byte magic
  const Bad bads[] = {{"truncated", bin.substr(0, bin.size() / 2)},
                      {"corrupted", flipped},
                      {"wrong-version", version},
                      {"not-a-lut", "hello, I am a text file\n"},
                      {"empty", ""}};
  for (const Bad& b : bads) {
    INFO(b.name);
    const fs::path dir = tmp / b.name;
    fs::copy(good, dir, fs::copy_options::recursive);
    fs::remove(dir / "optical_depth.exr");
    std::ofstream(dir / "optical_depth.bin", std::ios::binary | std::ios::trunc) << b.bytes;
    auto m = nlohmann::json::parse(readFile(dir / "manifest.json"));
    m["tables"]["optical_depth"]["files"].erase("exr");
    std::ofstream(dir / "manifest.json", std::ios::trunc) << m.dump();

    const CliResult info = runCli("info '" + (dir / "optical_depth.bin").string() + "'");
    CHECK(info.exitCode == 1);
    CHECK(info.err.find("optical_depth.bin") != std::string::npos);
    const CliResult infoDir = runCli("info '" + dir.string() + "'");
    CHECK(infoDir.exitCode == 1);
    const CliResult check = runCli("check '" + dir.string() + "' --golden '" + good + "'");
    CHECK(check.exitCode == 1);
    CHECK(check.err.find("optical_depth.bin") != std::string::npos);
    const CliResult query = runCli("query '" + dir.string() + "' --csv '" + (tmp / "in.csv").string() + "'");
    CHECK(query.exitCode == 1);
    CHECK(query.err.find("optical_depth.bin") != std::string::npos);
  }
  CHECK(runCli("info '" + (tmp / "missing").string() + "'").exitCode == 1);
  std::ofstream(tmp / "garbage.exr") << "v/1 not really";
  CHECK(runCli("info '" + (tmp / "garbage.exr").string() + "'").exitCode == 1);
}

TEST_CASE("scattering options: bad values are usage errors and write nothing", "[cli]") {
  TempDir tmp;
  const std::string out = (tmp / "luts").string();
  const char* cases[] = {
      "bake --tables single --g1 1",
      "bake --tables multiple --gm -1.5",
      "bake --tables single --phase rayleigh",
      "bake --tables single --phase jd --droplet-um 2",
      "bake --tables multiple --orders 0",
      "bake --tables multiple --orders many",
      "bake --tables single --densities 3:-4",
      "bake --tables single --densities -4,-3,-1",
      "bake --tables single --densities 2",
      "bake --tables single --res-sc 32,64,16",
      "bake --tables single --res-sc 4096,4096,4096,8",
      "bake --tables multiple --method magic",
      "bake --tables single --extinction -1",
  };
  for (const char* c : cases) {
    INFO(c);
    const CliResult r = runCli(std::string(c) + " --quiet --out '" + out + "'");
    CHECK(r.exitCode == 2);
    CHECK(lineCount(r.err) == 1);
    CHECK_FALSE(fs::exists(out));
  }
}

TEST_CASE("a small scattering bake is queried and its energy integrated", "[cli]") {
  TempDir tmp;
  const std::string out = (tmp / "luts").string();
  const CliResult bake = runCli("bake --tables single,multiple --res-sc 8,16,6,3 --densities -2:0 --orders 4 --quiet "
                                "--precision float --format bin --out '" + out + "'");
  REQUIRE(bake.exitCode == 0);
  const CliResult energy = runCli("info '" + out + "' --energy --json");
  REQUIRE(energy.exitCode == 0);
  const auto j = nlohmann::json::parse(energy.out);
  REQUIRE(j["slices"].size() == 5);  // log2 rho -2 ... 0, two slices per octave (the default)
  for (const auto& s : j["slices"]) {
    CHECK(s["single"].get<double>() > 0.0);
    CHECK(s["multiple"].get<double>() > 0.0);
    CHECK(s["total"].get<double>() <= 1.02);  // a non-absorbing particle returns at most what it receives
  }
  std::ofstream(tmp / "in.csv") << "sx,sy,sz,vx,vy,vz,lx,ly,lz,density\n0,0,1,0,0,-1,0,0,1,0.5\n";
  const CliResult q = runCli("query '" + out + "' --csv '" + (tmp / "in.csv").string() + "'");
  REQUIRE(q.exitCode == 0);
  // the optical-depth columns are empty (no table), the scattering ones are filled
  CHECK(q.out.find("0.5,,,") != std::string::npos);
}
