// Regression tests for the hostile-input probe of issue 16: each fault it found, by number.
// Promises under test: a clear message naming the file and the field, exit 1 for a bad file or a
// failed check, 2 for bad usage; never a crash, a hang or a huge allocation.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "core/Errors.h"
#include "core/ParameterRules.h"
#include "io/BinaryHeader.h"
#include "io/Fnv1a.h"
#include "io/LutIo.h"
#include "io/LutSetMedium.h"
#include "io/TableDescription.h"
#include "scene/Scene.h"
#include "support/Checks.h"
#include "support/CliRunner.h"
#include "support/SmallTables.h"

using namespace cloudlut;
using namespace cloudlut::test;
namespace fs = std::filesystem;

namespace {

// A small optical-depth LUT set baked by the real executable.
void bakeSmall(const fs::path& out, int seed = 1, const std::string& dims = "16,8,16,8") {
  const CliResult r = runCli("bake --tables optical-depth --res-od " + dims + " --seed " + std::to_string(seed) +
                             " --quiet --out '" + out.string() + "'");
  REQUIRE(r.exitCode == 0);
}


// The manifest of `dir` with its optical-depth parameters changed by `edit`.
template <typename Edit>
void editManifest(const fs::path& dir, Edit&& edit) {
  nlohmann::json m = nlohmann::json::parse(readFile(dir / "manifest.json"));
  edit(m);
  writeFile(dir / "manifest.json", m.dump(1));
}

}  // namespace

TEST_CASE("fault 1: check --worst beyond the failing cells lists them and exits 1", "[cli][hostile]") {
  TempDir tmp;
  bakeSmall(tmp / "A", 1);
  bakeSmall(tmp / "B", 2);
  const CliResult r = runCli("check '" + (tmp / "B").string() + "' --golden '" + (tmp / "A").string() + "' --worst 10000");
  CHECK(r.exitCode == 1);  // a failed check, not a crash (139)
  CHECK(r.out.find("out of tolerance") != std::string::npos);
  CHECK(r.out.find("channel mean_density") != std::string::npos);
  const CliResult negative = runCli("check '" + (tmp / "B").string() + "' --golden '" + (tmp / "A").string() + "' --worst=-1");
  CHECK(negative.exitCode == 2);  // fault 12: bad usage, with a message
  CHECK(negative.err.find("--worst") != std::string::npos);
}

TEST_CASE("fault 2: slices refuses ranges that overflow float", "[cli][hostile]") {
  TempDir tmp;
  bakeSmall(tmp / "A");
  const std::string base = "slices '" + (tmp / "A").string() + "' --out '" + (tmp / "s.png").string() + "' ";
  for (const char* range : {"--range=-1e39,1e39", "--range=-inf,inf", "--range=-1e308,1e308", "--range=0,inf",
                            "--range=nan,1", "--range=-3e38,3e38", "--range=1,1"}) {
    INFO(range);
    const CliResult r = runCli(base + range);
    CHECK(r.exitCode == 2);
    CHECK(r.err.find("--range") != std::string::npos);
    CHECK(!fs::exists(tmp / "s.png"));
  }
  CHECK(runCli(base + "--range=-1e37,1e37").exitCode == 0);  // wide but finite: drawn
}

TEST_CASE("faults 3, 10: extinction beyond the rules is bad usage for every verb", "[cli][hostile]") {
  TempDir tmp;
  writeFile(tmp / "q.csv", "sx,sy,sz,vx,vy,vz,lx,ly,lz,density\n0,0,1,0,0,-1,0,1,0,1\n");
  writeFile(tmp / "scene.json", R"({"particles": [{"center": [0, 0, 0], "radii": [1, 1, 1]}]})");
  const std::string scene = " --particles '" + (tmp / "scene.json").string() + "' --width 8 --height 8 --spp 2 --quiet";
  for (const char* value : {"1e308", "1e6", "-1", "0", "11"}) {
    INFO(value);
    const CliResult sphere = runCli(std::string("reference sphere --paths 2 --csv '") + (tmp / "q.csv").string() +
                                    "' --extinction=" + value);
    CHECK(sphere.exitCode == 2);
    CHECK(sphere.out.find("nan") == std::string::npos);
    const CliResult ref = runCli(std::string("reference scene") + scene + " --out '" + (tmp / "r.exr").string() +
                                 "' --extinction=" + value);
    CHECK(ref.exitCode == 2);
    CHECK(ref.err.find("--extinction") != std::string::npos);
    const CliResult bake = runCli(std::string("bake --tables optical-depth --res-od 4,4,4,4 --quiet --out '") +
                                  (tmp / "L").string() + "' --extinction=" + value);
    CHECK(bake.exitCode == 2);
  }
  CHECK(runCli("reference scene" + scene + " --out '" + (tmp / "r.exr").string() + "' --radius 1e308").exitCode == 2);
  // the sphere's density comes from the CSV: a row too thick to trace names the file and the row
  writeFile(tmp / "thick.csv", "sx,sy,sz,vx,vy,vz,lx,ly,lz,density\n0,0,1,0,0,-1,0,1,0,1e30\n");
  const CliResult thick = runCli("reference sphere --paths 2 --csv '" + (tmp / "thick.csv").string() + "'");
  CHECK(thick.exitCode == 1);
  CHECK(thick.err.find("thick.csv: row '0,0,1,0,0,-1,0,1,0,1e30'") != std::string::npos);
}

TEST_CASE("fault 3: reference scene stops at a time limit and refuses particles too thick to trace", "[cli][hostile]") {
  TempDir tmp;
  writeFile(tmp / "scene.json", R"({"particles": [{"center": [0, 0, 0], "radii": [1, 1, 1]}]})");
  const std::string scene = " --particles '" + (tmp / "scene.json").string() + "' --out '" + (tmp / "r.exr").string() + "'";
  // A job of an hour (256 x 256 pixels, 4096 paths each) given 0.3 s: exit 1, nothing written.
  const CliResult slow = runCli("reference scene" + scene + " --width 256 --height 256 --spp 4096 --max-seconds 0.3 --quiet");
  CHECK(slow.exitCode == 1);
  CHECK(slow.err.find("--max-seconds") != std::string::npos);
  CHECK(slow.err.find("needed for the whole image") != std::string::npos);
  CHECK(!fs::exists(tmp / "r.exr"));
  CHECK(runCli("reference scene" + scene + " --max-seconds=-1").exitCode == 2);
  // density 1e6: optical radius 1.3e7, far beyond what paths of about tau^2 events can follow
  writeFile(tmp / "dense.json", R"({"particles": [{"center": [0, 0, 0], "radii": [1, 1, 1], "density": 1e6}]})");
  const CliResult dense = runCli("reference scene --particles '" + (tmp / "dense.json").string() + "' --out '" +
                                 (tmp / "r.exr").string() + "' --width 8 --height 8 --spp 2 --quiet");
  CHECK(dense.exitCode == 1);
  CHECK(dense.err.find("dense.json: particles[0].density") != std::string::npos);
}

TEST_CASE("faults 3, 8: a manifest's physics obey the command line's rules, naming the field", "[cli][hostile]") {
  TempDir tmp;
  bakeSmall(tmp / "L");
  writeFile(tmp / "scene.json", R"({"particles": [{"center": [0, 0, 0], "radii": [1, 1, 1]}]})");
  struct Case {
    const char* table;  // the table whose parameters are edited
    const char* field;
    nlohmann::json value;
  };
  const Case cases[] = {{"optical_depth", "radius_m", 1e308},     {"optical_depth", "extinction_per_m", -1.0},
                        {"optical_depth", "extinction_per_m", 0.0}, {"optical_depth", "extinction_per_m", "x"},
                        {"optical_depth", "seed", -1},             {"optical_depth", "seed", 1.5},
                        {"optical_depth", "density_model", "bogus"}};
  for (const Case& c : cases) {
    INFO(c.field << " = " << c.value.dump());
    TempDir dir;
    fs::copy(tmp / "L", dir / "L");
    editManifest(dir / "L", [&](nlohmann::json& m) { m["tables"][c.table]["parameters"][c.field] = c.value; });
    const std::string message = fileErrorOf([&] { io::mediumFromLutSet(dir / "L"); });
    CHECK(message.find("manifest.json: tables.optical_depth.parameters." + std::string(c.field)) != std::string::npos);
    CHECK(message.find("json.exception") == std::string::npos);
    const CliResult r = runCli("reference scene --luts '" + (dir / "L").string() + "' --particles '" +
                               (tmp / "scene.json").string() + "' --out '" + (dir / "r.exr").string() +
                               "' --width 4 --height 4 --spp 2 --quiet");
    CHECK(r.exitCode == 1);
    CHECK(r.err.find(c.field) != std::string::npos);
  }
  // The phase functions a manifest records: kind and param by the same rules as --phase, --g1.
  const nlohmann::json phases[] = {{{"kind", 2}, {"param", 5.0}}, {{"kind", 1099511627776LL}, {"param", 0.5}},
                                   {{"kind", 99}, {"param", 0.5}}, {{"kind", 3}, {"param", 2.0}}, "cs"};
  for (const nlohmann::json& phase : phases) {
    INFO(phase.dump());
    TempDir dir;
    fs::copy(tmp / "L", dir / "L");
    editManifest(dir / "L", [&](nlohmann::json& m) {
      m["tables"]["single_scattering"] = {{"parameters", {{"first_phase", phase}}}};
    });
    const std::string message = fileErrorOf([&] { io::mediumFromLutSet(dir / "L"); });
    CHECK(message.find("tables.single_scattering.parameters.first_phase") != std::string::npos);
  }
}

TEST_CASE("faults 8, 9: a table's physics obey the rules, and wrong types name the field", "[io][hostile]") {
  TempDir tmp;
  struct Case {
    const char* field;
    nlohmann::json value;
  };
  const Case bad[] = {{"extinction_per_m", -1.0},  {"extinction_per_m", 0.0},   {"extinction_per_m", "x"},
                      {"radius_m", 1e308},         {"radius_m", 0.0},           {"first_phase", "cs"},
                      {"first_phase", {{"kind", 99}, {"param", 0.9}}},          {"first_phase", {{"kind", 2}, {"param", 5}}},
                      {"later_phase", {{"kind", 1}, {"param", -1.0}}},          {"seed", -1},
                      {"seed", 1.5},               {"density_model", 7},
                      {"chord_outer_third_share", 0.9}, {"chord_outer_third_share", -0.1},
                      {"chord_outer_third_share", "x"},
                      {"angular_closure", "x"},
                      {"angular_closure", {{"log2_rho_first", 0}, {"log2_rho_step", 1}, {"density_nodes", 1},
                                           {"mu_bins", 2}, {"values", {1.0, 1e30}}}},
                      {"angular_closure", {{"log2_rho_first", 0}, {"log2_rho_step", 1}, {"density_nodes", 1e12},
                                           {"mu_bins", 2}, {"values", {1.0, 1.0}}}}};
  for (const Case& c : bad)
    for (const char* ext : {".bin", ".exr"}) {
      INFO(c.field << " = " << c.value.dump() << " in " << ext);
      Table4D table = makeTable({4, 4, 4, 4}, 2, 0.0f, 1.0f);
      table.parameters() = {{"extinction_per_m", 0.07}, {"radius_m", 183.8}};
      table.parameters()[c.field] = c.value;
      const fs::path file = tmp / (std::string("t") + ext);
      // the writers record what they are given, checksums included: the reader must judge
      if (std::string(ext) == ".bin") io::writeBinaryLut(table, io::SampleType::Float, file);
      else io::writeExrLut(table, io::SampleType::Float, file);
      const std::string message = fileErrorOf([&] { io::readLut(file); });
      CHECK(message.find(file.string() + ": parameters." + c.field) != std::string::npos);
      CHECK(message.find("json.exception") == std::string::npos);
    }
  // and query, which used to print optical depth -241.6 and transmittance inf
  const fs::path dir = tmp / "L";
  bakeSmall(dir);
  Table4D od = io::readLut(dir / "optical_depth.bin").table;
  od.parameters()["extinction_per_m"] = -1.0;
  io::writeBinaryLut(od, io::SampleType::Half, dir / "optical_depth.bin");
  editManifest(dir, [&](nlohmann::json& m) {
    const nlohmann::json entry = io::describeTable(od, io::SampleType::Half);
    for (const char* key : {"payload_bytes", "payload_fnv1a64", "parameters"}) m["tables"]["optical_depth"][key] = entry[key];
    m["tables"]["optical_depth"]["files"].erase("exr");
  });
  writeFile(tmp / "q.csv", "sx,sy,sz,vx,vy,vz,lx,ly,lz,density\n0,0,1,0,0,-1,0,1,0,1\n");
  const CliResult r = runCli("query '" + dir.string() + "' --csv '" + (tmp / "q.csv").string() + "'");
  CHECK(r.exitCode == 1);
  CHECK(r.err.find("parameters.extinction_per_m") != std::string::npos);
  CHECK(r.out.empty());
}

TEST_CASE("fault 8: the rules a file obeys are the command line's", "[cli][hostile]") {
  // Each value is tried on the command line (bake --extinction) and in a table's parameters;
  // both must accept it or both refuse it.
  TempDir tmp;
  for (const double beta : {-1.0, 0.0, 1e-9, 0.07, 10.0, 10.5, 1e308}) {
    INFO("extinction " << beta);
    char value[32];
    std::snprintf(value, sizeof value, "%.17g", beta);
    const CliResult cli = runCli(std::string("bake --tables optical-depth --res-od 2,2,2,2 --quiet --radius 1 --out '") +
                                 (tmp / "L").string() + "' --extinction=" + value);
    bool fileRefused = false;
    try {
      io::checkTableParameters({{"extinction_per_m", beta}, {"radius_m", 1.0}}, "t.bin");
    } catch (const FileError&) {
      fileRefused = true;
    }
    CHECK((cli.exitCode == 2) == fileRefused);
    CHECK((cli.exitCode == 0) == !fileRefused);
  }
}

TEST_CASE("fault 11: camera checks say what is wrong, in double precision", "[scene][hostile]") {
  const auto message = [](const scene::Scene& s, const scene::ViewSettings& o) -> std::string {
    try {
      scene::resolveView(s, o);
    } catch (const UsageError& e) {
      return e.what();
    }
    return {};
  };
  scene::Scene one;
  one.particles.push_back(scene::Particle{});
  scene::ViewSettings far;
  far.eye = glm::vec3(1e20f, 0.0f, 0.0f);
  CHECK(message(one, far).find("eye lies 1e+20 m from the origin") != std::string::npos);
  CHECK(message(one, far).find("coincide") == std::string::npos);
  scene::Scene distant;
  distant.particles.push_back(scene::Particle{});
  distant.particles.back().center = glm::vec3(1e30f, 0.0f, 0.0f);
  CHECK(!message(distant, {}).empty());
  CHECK(message(distant, {}).find("coincide") == std::string::npos);
  scene::Scene tiny;
  tiny.particles.push_back(scene::Particle{});
  tiny.particles.back().radii = glm::vec3(1e-6f);
  scene::ViewSettings close;
  close.eye = glm::vec3(0.0f, 0.0f, 2e-6f);
  CHECK(message(tiny, close).empty());  // a tiny scene seen from nearby is a valid view
  scene::ViewSettings deep;
  deep.target = glm::vec3(0.0f, 0.0f, -1e30f);
  CHECK(message(one, deep).find("parallel") == std::string::npos);
  CHECK(message(one, deep).find("from the origin") != std::string::npos);
  scene::ViewSettings same;
  same.eye = same.target = glm::vec3(3.0f, 0.0f, 0.0f);
  CHECK(message(one, same).find("coincide") != std::string::npos);  // the real case is still caught
  scene::ViewSettings up;
  up.eye = glm::vec3(0.0f, 5.0f, 0.0f);
  up.target = glm::vec3(0.0f);
  CHECK(message(one, up).find("parallel") != std::string::npos);
}

TEST_CASE("fault 12: options that do not apply to the method, and invalid values, are bad usage", "[cli][hostile]") {
  TempDir tmp;
  bakeSmall(tmp / "L");
  writeFile(tmp / "scene.json", R"({"particles": [{"center": [0, 0, 0], "radii": [1, 1, 1]}]})");
  const std::string render = "render --luts '" + (tmp / "L").string() + "' --particles '" + (tmp / "scene.json").string() +
                             "' --out '" + (tmp / "x.png").string() + "' ";
  for (const char* option : {"--phase bogus", "--density-model bogus", "--extinction=-1", "--radius 0", "--g1 1",
                             "--phase hg", "--steps 32"}) {
    INFO(option);
    const CliResult r = runCli(render + option);
    CHECK(r.exitCode == 2);
    CHECK(!r.err.empty());
  }
  for (const char* option : {"--g1 5", "--g1 0.5", "--phase jd --g1 0.5", "--phase cs --droplet-um 10",
                             "--phase hg --g1 1", "--phase jd --droplet-um 60"}) {
    INFO(option);
    const CliResult r = runCli(render + "--method raymarch " + option);
    CHECK(r.exitCode == 2);
    CHECK(r.err.find("--") != std::string::npos);
  }
}

TEST_CASE("fault 13: clear messages for directories, devices, NUL bytes and the right option", "[cli][hostile]") {
  TempDir tmp;
  bakeSmall(tmp / "L");
  const CliResult csvDir = runCli("query '" + (tmp / "L").string() + "' --csv '" + tmp.path().string() + "'");
  CHECK(csvDir.exitCode == 1);
  CHECK(csvDir.err.find("is a directory") != std::string::npos);
  for (const std::string& particles : {tmp.path().string(), std::string("/dev/zero")}) {
    const CliResult r = runCli("render --luts '" + (tmp / "L").string() + "' --particles '" + particles + "' --out '" +
                               (tmp / "x.png").string() + "'");
    CHECK(r.exitCode == 1);
    CHECK(r.err.find("no such scene file") == std::string::npos);
  }
  const CliResult forScene = runCli("bake --for-scene '" + (tmp / "nope.json").string() + "' --out '" + (tmp / "M").string() + "'");
  CHECK(forScene.exitCode == 2);
  CHECK(forScene.err.find("--for-scene") != std::string::npos);
  CHECK(forScene.err.find("--scene:") == std::string::npos);
  writeFile(tmp / "nul.csv", std::string("sx,sy,sz,vx,vy,vz,lx,ly,lz,density\n0,0,1,0,0,-1,0,1,0,1") + std::string(1, '\0') +
                                 "tail\n");
  const CliResult nul = runCli("query '" + (tmp / "L").string() + "' --csv '" + (tmp / "nul.csv").string() + "'");
  CHECK(nul.exitCode == 1);
  CHECK(nul.err.find("\\x00tail") != std::string::npos);  // the whole field, NUL shown
}

TEST_CASE("fault 13: a binary table with a NaN axis or reserved flag bits is refused", "[io][hostile]") {
  TempDir tmp;
  Table4D table = makeTable({4, 4, 4, 4}, 2, 0.0f, 1.0f);
  table.parameters() = nlohmann::json::object();
  {
    Table4D nan = table;
    std::array<Axis, 4> axes = nan.axes();
    axes[1].min = std::nan("");
    Table4D withNan(nan.name(), axes, nan.channels());
    withNan.data() = nan.data();
    io::writeBinaryLut(withNan, io::SampleType::Float, tmp / "nan.bin");
    CHECK(fileErrorOf([&] { io::readLut(tmp / "nan.bin"); }).find("axis 1 range") != std::string::npos);
  }
  io::writeBinaryLut(table, io::SampleType::Float, tmp / "flags.bin");
  std::string bytes = readFile(tmp / "flags.bin");
  // the first axis record's flags (lut_formats/FORMAT.md: offset 40 in the record), then the
  // header checksum recomputed so that only the flag is wrong
  const std::size_t flags = io::binary::kAxesOffset + 40;
  REQUIRE(bytes[flags] == 1);  // phi_s is periodic
  bytes[flags] = 1 | 8;  // bit 3 is reserved in every version
  std::uint32_t headerBytes = 0, version = 0;
  io::binary::parsePrefix(bytes, version, headerBytes);
  const std::uint64_t h = io::fnv1a64(std::string_view(bytes).substr(0, headerBytes - 8));
  for (int k = 0; k < 8; ++k) bytes[headerBytes - 8 + static_cast<std::size_t>(k)] = static_cast<char>(h >> (8 * k));
  writeFile(tmp / "flags.bin", bytes);
  CHECK(fileErrorOf([&] { io::readLut(tmp / "flags.bin"); }).find("flag bits reserved") != std::string::npos);
}

TEST_CASE("fault 13: a write that fails (a full disk) exits 1, and leaves no file", "[cli][hostile]") {
  TempDir tmp;
  // RLIMIT_FSIZE makes write() fail with EFBIG, as ENOSPC does when the disk is full (SIGXFSZ ignored).
  const std::string cmd = "sh -c \"trap '' XFSZ; ulimit -f 16; '" + std::string(CLOUDLUT_EXE) +
                          "' bake --tables optical-depth --res-od 32,16,32,16 --precision float --quiet --out '" +
                          (tmp / "L").string() + "'\" > /dev/null 2> '" + (tmp / "err").string() + "'";
  const int status = std::system(cmd.c_str());
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 1);
  CHECK(readFile(tmp / "err").find("cannot write") != std::string::npos);
  CHECK(!fs::exists(tmp / "L" / "manifest.json"));
}
