// `cloudlut render` end to end: PNG and EXR output, command-line overrides, and every bad input
// (missing or corrupt tables, malformed scene fields, absurd sizes, bad options) giving one
// clear line on stderr, the right exit code and nothing written.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>

#include "support/CliRunner.h"
#include "core/Glsl.h"
#include "core/Errors.h"
#include "core/TableLookup.h"
#include "scene/Scene.h"
#include "support/RenderLuts.h"

using namespace cloudlut;
using namespace cloudlut::test;
namespace fs = std::filesystem;

namespace {

const std::string kScene = std::string(CLOUDLUT_SOURCE_DIR) + "/data/scenes/small.json";

std::size_t lineCount(const std::string& s) { return static_cast<std::size_t>(std::count(s.begin(), s.end(), '\n')); }

std::string q(const fs::path& p) { return "'" + p.string() + "'"; }

// A render command line for `luts`, `scene` and `out` at 96×64 plus `extra`.
std::string renderArgs(const fs::path& luts, const fs::path& scene, const fs::path& out, const std::string& extra = "") {
  return "render --luts " + q(luts) + " --particles " + q(scene) + " --out " + q(out) + " --width 96 --height 64 " + extra;
}

// The named FLOAT channels of an EXR image, and its size.
std::vector<std::vector<float>> readExrChannels(const fs::path& path, const std::vector<std::string>& names, int& w, int& h) {
  Imf::InputFile file(path.c_str());
  const Imath::Box2i dw = file.header().dataWindow();
  w = dw.max.x - dw.min.x + 1;
  h = dw.max.y - dw.min.y + 1;
  std::vector<std::vector<float>> channels(names.size(), std::vector<float>(static_cast<std::size_t>(w) * h));
  Imf::FrameBuffer frame;
  for (std::size_t c = 0; c < names.size(); ++c)
    frame.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(channels[c].data()), sizeof(float),
                                      sizeof(float) * static_cast<std::size_t>(w)));
  file.setFrameBuffer(frame);
  file.readPixels(dw.min.y, dw.max.y);
  return channels;
}

// Column k of every data row of a CSV text.
std::vector<double> csvColumn(const std::string& text, int k) {
  std::istringstream lines(text);
  std::string line;
  std::getline(lines, line);  // header
  std::vector<double> values;
  while (std::getline(lines, line)) {
    std::istringstream fields(line);
    std::string f;
    for (int i = 0; i <= k; ++i) std::getline(fields, f, ',');
    values.push_back(std::stod(f));
  }
  return values;
}

bool hasTempFiles(const fs::path& dir) {
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().find(".tmp") != std::string::npos) return true;
  return false;
}

}  // namespace

TEST_CASE("render CLI: PNG and EXR output of the small scene", "[render][cli]") {
  TempDir tmp;
  writeSyntheticLutSet(tmp / "luts");
  fs::create_directories(tmp / "img");

  const CliResult png = runCli(renderArgs(tmp / "luts", kScene, tmp / "img" / "small.png"));
  REQUIRE(png.exitCode == 0);
  CHECK(png.err.empty());
  const std::string bytes = readFile(tmp / "img" / "small.png");
  REQUIRE(bytes.size() > 8);
  CHECK(bytes.substr(1, 3) == "PNG");

  const CliResult exr = runCli(renderArgs(tmp / "luts", kScene, tmp / "img" / "small.exr", "--quiet"));
  REQUIRE(exr.exitCode == 0);
  CHECK(exr.out.empty());
  Imf::InputFile file((tmp / "img" / "small.exr").c_str());
  const Imath::Box2i dw = file.header().dataWindow();
  const int w = dw.max.x - dw.min.x + 1, h = dw.max.y - dw.min.y + 1;
  REQUIRE(w == 96);
  REQUIRE(h == 64);
  const char* names[] = {"R", "G", "B", "A", "Z"};
  std::vector<std::vector<float>> channels(5, std::vector<float>(static_cast<std::size_t>(w * h)));
  Imf::FrameBuffer frame;
  for (int c = 0; c < 5; ++c) {
    REQUIRE(file.header().channels().findChannel(names[c]) != nullptr);
    frame.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(channels[c].data()), sizeof(float),
                                      sizeof(float) * static_cast<std::size_t>(w)));
  }
  file.setFrameBuffer(frame);
  file.readPixels(dw.min.y, dw.max.y);
  std::size_t opaque = 0, empty = 0;
  for (std::size_t i = 0; i < channels[3].size(); ++i) {
    const float a = channels[3][i];
    CHECK((a >= 0.0f && a <= 1.0f));
    for (int c = 0; c < 3; ++c) CHECK(std::isfinite(channels[c][i]));
    if (a > 0.5f) {
      ++opaque;
      CHECK(std::isfinite(channels[4][i]));
      CHECK(channels[4][i] > 0.0f);
    }
    if (a == 0.0f) {
      ++empty;
      CHECK(std::isinf(channels[4][i]));
    }
  }
  CHECK(opaque > 500);
  CHECK(empty > 500);
  CHECK_FALSE(hasTempFiles(tmp / "img"));

  // Command-line camera overrides the scene's: from far away the cloud covers fewer pixels.
  const CliResult far = runCli(renderArgs(tmp / "luts", kScene, tmp / "img" / "far.exr", "--quiet --eye=0,1.2,-60 --fov 30"));
  REQUIRE(far.exitCode == 0);
  Imf::InputFile farFile((tmp / "img" / "far.exr").c_str());
  std::vector<float> alpha(static_cast<std::size_t>(w * h));
  Imf::FrameBuffer farFrame;
  farFrame.insert("A", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(alpha.data()), sizeof(float),
                                  sizeof(float) * static_cast<std::size_t>(w)));
  farFile.setFrameBuffer(farFrame);
  farFile.readPixels(dw.min.y, dw.max.y);
  const auto farOpaque = std::count_if(alpha.begin(), alpha.end(), [](float a) { return a > 0.5f; });
  CHECK(farOpaque > 0);
  CHECK(static_cast<std::size_t>(farOpaque) < opaque / 4);
}

TEST_CASE("render: the command line overrides the scene file, which overrides the defaults", "[render]") {
  scene::Scene scene = scene::parseScene(nlohmann::json::parse(R"({
      "camera": {"eye": [0, 0, 10], "fov_deg": 30},
      "sun": {"direction": [0, 2, 0]},
      "particles": [{"center": [1, 2, 3], "radii": 1}]})"), "inline");
  scene::ViewSettings cli;
  cli.fovDeg = 60.0f;
  cli.skyColor = glm::vec3(0.5f);
  const scene::View view = scene::resolveView(scene, cli);
  CHECK(view.camera.eye == glm::vec3(0, 0, 10));
  CHECK(view.camera.target == glm::vec3(1, 2, 3));  // default: the particles' centre
  CHECK(view.camera.fovDeg == 60.0f);
  CHECK(view.lighting.sunDirection == glm::vec3(0, 1, 0));
  CHECK(view.lighting.skyColor == glm::vec3(0.5f));
  CHECK(view.lighting.sunColor == glm::vec3(1.0f));
  cli.eye = glm::vec3(1, 2, 3);
  CHECK_THROWS_AS(scene::resolveView(scene, cli), UsageError);
}

TEST_CASE("render CLI: missing or corrupt tables are file errors naming the file", "[render][cli]") {
  TempDir tmp;
  writeSyntheticLutSet(tmp / "good");
  const fs::path out = tmp / "out.png";

  // No LUT directory at all.
  CliResult r = runCli(renderArgs(tmp / "nowhere", kScene, out));
  CHECK(r.exitCode == 1);
  CHECK(lineCount(r.err) == 1);
  CHECK(r.err.find("manifest.json") != std::string::npos);

  // A set without the multiple-scattering table.
  {
    const Table4D od = smallOpticalDepth(), l1 = syntheticSingle();
    writeLutSet(tmp / "partial", {&od, &l1});
  }
  r = runCli(renderArgs(tmp / "partial", kScene, out));
  CHECK(r.exitCode == 1);
  CHECK(lineCount(r.err) == 1);
  CHECK(r.err.find("multiple_scattering") != std::string::npos);

  // A truncated and a bit-flipped optical-depth file.
  const std::string bin = readFile(tmp / "good" / "optical_depth.bin");
  std::string flipped = bin;
  flipped[flipped.size() - 7] = static_cast<char>(flipped[flipped.size() - 7] ^ 0x21);
  for (const std::string& bytes : {bin.substr(0, bin.size() / 2), flipped, std::string("not a table")}) {
    fs::remove_all(tmp / "bad");
    fs::copy(tmp / "good", tmp / "bad", fs::copy_options::recursive);
    std::ofstream(tmp / "bad" / "optical_depth.bin", std::ios::binary | std::ios::trunc) << bytes;
    r = runCli(renderArgs(tmp / "bad", kScene, out));
    CHECK(r.exitCode == 1);
    CHECK(lineCount(r.err) == 1);
    CHECK(r.err.find("optical_depth.bin") != std::string::npos);
  }
  CHECK_FALSE(fs::exists(out));
  CHECK_FALSE(hasTempFiles(tmp.path()));
}

TEST_CASE("render CLI: a malformed scene is a file error naming the field", "[render][cli]") {
  TempDir tmp;
  writeSyntheticLutSet(tmp / "luts");
  const fs::path out = tmp / "out.png";
  const std::string ok = R"({"center": [0, 0, 0], "radii": 1})";
  struct Bad {
    std::string json, field;
  };
  const Bad bads[] = {
      {"{\"particles\": [" + ok + ", {\"center\": [0, 0, 0], \"radii\": [1, -2, 1]}]}", "particles[1].radii"},
      {"{\"particles\": [" + ok + ", " + ok + ", " + ok + ", {\"center\": [0, 0, 0], \"radii\": [1, 2]}]}", "particles[3].radii"},
      {R"({"particles": [{"center": [0, 0], "radii": 1}]})", "particles[0].center"},
      {R"({"particles": [{"center": [0, "x", 0], "radii": 1}]})", "particles[0].center"},
      {R"({"particles": [{"radii": 1}]})", "particles[0].center"},
      {R"({"particles": [{"centre": [0, 0, 0], "radii": 1}]})", "particles[0].centre"},
      {R"({"particles": [{"center": [0, 0, 0], "radii": 1, "density": -1}]})", "particles[0].density"},
      {R"({"particles": [{"center": [0, 0, 0], "radii": 1, "density": "thick"}]})", "particles[0].density"},
      {R"({"particles": [{"center": [0, 0, 0], "radii": 1, "quaternion": [0, 0, 0, 0]}]})", "particles[0].quaternion"},
      {R"({"particles": [{"center": [0, 0, 0], "radii": 1, "euler_deg": [0, 0]}]})", "particles[0].euler_deg"},
      {R"({"particles": [{"center": [0, 0, 0], "radii": 1, "quaternion": [1, 0, 0, 0], "euler_deg": [0, 0, 0]}]})", "particles[0]"},
      {R"({"particles": [7]})", "particles[0]"},
      {R"({"particles": {}})", "particles"},
      {R"({"camera": {"eye": [0, 0, 1]}})", "particles"},
      {R"({"camera": {"fov_deg": 0}, "particles": []})", "camera.fov_deg"},
      {R"({"camera": {"up": [0, 0, 0]}, "particles": []})", "camera.up"},
      {R"({"sun": {"direction": [0, 0, 0]}, "particles": []})", "sun.direction"},
      {R"({"sun": {"color": [1, -1, 1]}, "particles": []})", "sun.color"},
      {R"({"sky": {"colour": [1, 1, 1]}, "particles": []})", "sky.colour"},
      {R"({"particles": [], "lights": []})", "lights"},
      {R"([1, 2, 3])", "(document)"},
      {R"({"particles": [)", "invalid JSON"},
  };
  for (const Bad& b : bads) {
    INFO(b.json);
    std::ofstream(tmp / "scene.json", std::ios::trunc) << b.json;
    const CliResult r = runCli(renderArgs(tmp / "luts", tmp / "scene.json", out));
    CHECK(r.exitCode == 1);
    CHECK(lineCount(r.err) == 1);
    CHECK(r.err.find("scene.json") != std::string::npos);
    CHECK(r.err.find(b.field) != std::string::npos);
  }
  const CliResult missing = runCli(renderArgs(tmp / "luts", tmp / "no-scene.json", out));
  CHECK(missing.exitCode == 1);
  CHECK(missing.err.find("no-scene.json") != std::string::npos);
  CHECK_FALSE(fs::exists(out));
}

TEST_CASE("render CLI: absurd sizes and bad options are usage errors", "[render][cli]") {
  TempDir tmp;
  writeSyntheticLutSet(tmp / "luts");
  const fs::path out = tmp / "out.png";
  const std::string base = "render --luts " + q(tmp / "luts") + " --particles " + q(kScene) + " --out " + q(out) + " ";
  const char* cases[] = {
      "--width 0 --height 64",
      "--width=-5 --height 64",
      "--width 96 --height=-1",
      "--width 16385 --height 64",
      "--width 96 --height 100000",
      "--width 16384 --height 16384",  // about 21 GiB of buffers
      "--width 99999999999999999999",
      "--width abc",
      "--eye 1,2",
      "--eye 1,2,x",
      "--target 1,2,3,4",
      "--sun 0,0,0",
      "--sun-color 1,-1,1",
      "--sky-color 1,1",
      "--fov 0",
      "--fov 200",
      "--up 0,0,0",
      "--exposure 0",
      "--terms sunlight",
      "--lighting bogus",
      "--sunlight nowhere",
      "--diffusion 1.5",
      "--diffusion 0.5 --diffusion-sweeps 0",
      "--diffusion-cycles -1",
      "--diffusion 0.5 --diffusion-spacing 0",
      "--eye 0,0,0 --target 0,0,0",
      "--no-such-option",
  };
  for (const char* c : cases) {
    INFO(c);
    const CliResult r = runCli(base + c);
    CHECK(r.exitCode == 2);
    CHECK(lineCount(r.err) == 1);
    CHECK(r.err.find("error") != std::string::npos);
    CHECK_FALSE(fs::exists(out));
  }
  for (const std::string& c : {std::string("render --particles ") + q(kScene) + " --out " + q(out),
                               "render --luts " + q(tmp / "luts") + " --out " + q(out) + " --scene no_such_preset",
                               "render --luts " + q(tmp / "luts") + " --particles " + q(kScene),
                               base.substr(0, base.find(" --out")) + " --out " + q(tmp / "out.jpg"),
                               base.substr(0, base.find(" --out")) + " --out " + q(tmp / "no-dir" / "out.png")}) {
    INFO(c);
    const CliResult r = runCli(c);
    CHECK(r.exitCode == 2);
    CHECK(lineCount(r.err) == 1);
  }
  CHECK_FALSE(fs::exists(tmp / "out.jpg"));
}

TEST_CASE("render CLI: without an OpenGL 4.5 core context the error says what is missing", "[render][cli]") {
  TempDir tmp;
  writeSyntheticLutSet(tmp / "luts");
  const fs::path out = tmp / "out.png";
  // Mesa honours this variable: its contexts then claim OpenGL 3.3 at most.
  ::setenv("MESA_GL_VERSION_OVERRIDE", "3.3", 1);
  const CliResult r = runCli(renderArgs(tmp / "luts", kScene, out));
  ::unsetenv("MESA_GL_VERSION_OVERRIDE");
  CHECK(r.exitCode == 1);
  CHECK(lineCount(r.err) == 1);
  CHECK(r.err.find("OpenGL 4.5 core") != std::string::npos);
  CHECK(r.err.find("3.3") != std::string::npos);
  CHECK_FALSE(fs::exists(out));
}

TEST_CASE("render CLI: pixels of one particle reproduce `cloudlut query` for the same rays", "[render][cli]") {
  TempDir tmp;
  writeSyntheticLutSet(tmp / "luts", DensityModel::Noise);
  // Red sun, green sky: R = single + multiple, A = 1 - transmittance.
  std::ofstream(tmp / "one.json") << R"({
    "camera": {"eye": [0.7, 1.1, 6.5], "target": [0.2, -0.1, 0.0], "fov_deg": 40},
    "sun": {"direction": [0.3, 0.8, 0.5], "color": [1, 0, 0]},
    "sky": {"color": [0, 1, 0]},
    "particles": [{"center": [0.3, -0.2, 0.1], "radii": 1.6, "euler_deg": [20, -35, 50], "density": 0.25}]})";
  // `query` evaluates the seed's shading model (seed §4.4): render with it.
  const CliResult r = runCli(renderArgs(tmp / "luts", tmp / "one.json", tmp / "one.exr", "--quiet --lighting seed"));
  REQUIRE(r.exitCode == 0);
  int w = 0, h = 0;
  const auto px = readExrChannels(tmp / "one.exr", {"R", "A"}, w, h);

  const scene::Scene scene = scene::readScene(tmp / "one.json");
  const scene::View view = scene::resolveView(scene, {});
  const scene::Particle& p = scene.particles[0];
  const scene::CameraFrame camera(view.camera, w, h);
  const glm::vec3 l = glm::normalize(p.toParticle() * view.lighting.sunDirection);
  const io::LutSet luts = io::readLutSet(tmp / "luts");
  const Table4D& od = luts.tables.at("optical_depth").table;

  // Rays through every third pixel where the particle is not too thin to matter.
  struct Ray { std::size_t pixel; glm::vec3 S, v; float chord; };
  std::vector<Ray> rays;
  for (int y = 0; y < h; y += 3)
    for (int x = 0; x < w; x += 3) {
      const Hit hit = intersect(p, camera.eye(), camera.rayDirection(float(x) + 0.5f, float(y) + 0.5f));
      if (!hit.hit) continue;
      const OpticalDepthSample s = lookupOpticalDepth(od, hit.S, hit.v, p.density);
      if (s.chordLength < 0.2f || s.opticalDepth < 0.05f) continue;
      rays.push_back({static_cast<std::size_t>(y) * w + x, hit.S, hit.v, s.chordLength});
    }
  REQUIRE(rays.size() > 100);
  const auto writeCsv = [&](const fs::path& path, const std::vector<float>& density) {
    std::ofstream csv(path);
    csv << "sx,sy,sz,vx,vy,vz,lx,ly,lz,density\n";
    char line[256];
    for (std::size_t i = 0; i < rays.size(); ++i) {
      const Ray& ray = rays[i];
      std::snprintf(line, sizeof line, "%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", ray.S.x, ray.S.y,
                    ray.S.z, ray.v.x, ray.v.y, ray.v.z, l.x, l.y, l.z, double(density[i]));
      csv << line;
    }
  };
  // Query 1 at the particle's density: optical depth, transmittance, multiple scattering.
  writeCsv(tmp / "rho.csv", std::vector<float>(rays.size(), p.density));
  const CliResult q1 = runCli("query " + q(tmp / "luts") + " --csv " + q(tmp / "rho.csv"));
  REQUIRE(q1.exitCode == 0);
  const auto tau = csvColumn(q1.out, 10), transmittance = csvColumn(q1.out, 11), multiple = csvColumn(q1.out, 14);
  REQUIRE(tau.size() == rays.size());
  // Query 2 at the ray's mean density ρ·T̄ (seed §4.4), T̄ = τ / (σ ρ L): single scattering.
  const double sigma = unitOpticalRadius(od);
  std::vector<float> meanDensity(rays.size());
  for (std::size_t i = 0; i < rays.size(); ++i)
    meanDensity[i] = static_cast<float>(tau[i] / (sigma * rays[i].chord));
  writeCsv(tmp / "mean.csv", meanDensity);
  const CliResult q2 = runCli("query " + q(tmp / "luts") + " --csv " + q(tmp / "mean.csv"));
  REQUIRE(q2.exitCode == 0);
  const auto single = csvColumn(q2.out, 13);

  double maxRadiance = 0, maxTransmittance = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    // `query` gives the homogeneous chord's multiple scattering; the renderer carries the
    // same mean source over the ray's own opacity (shading.glsl)
    const float tauHomogeneous = glsl::particleOpticalDepth(p.density, static_cast<float>(sigma), rays[i].chord, 1.0f);
    const double radiance = single[i] + multiple[i] * glsl::chordOpacity(static_cast<float>(tau[i])) /
                                            glsl::chordOpacity(tauHomogeneous);
    maxRadiance = std::max(maxRadiance, std::abs(px[0][rays[i].pixel] - radiance) / radiance);
    maxTransmittance = std::max(maxTransmittance, std::abs(1.0 - px[1][rays[i].pixel] - transmittance[i]) / transmittance[i]);
  }
  std::printf("[render] render vs `cloudlut query`, %zu rays: max relative difference radiance %.2e, "
              "transmittance %.2e\n", rays.size(), maxRadiance, maxTransmittance);
  CHECK(maxRadiance <= 0.01);
  CHECK(maxTransmittance <= 0.01);
}

TEST_CASE("render CLI: --sky-model picks the sky that lights the clouds; the atmosphere's own settings are refused",
          "[render][cli]") {
  TempDir tmp;
  writeSyntheticLutSet(tmp / "luts");
  // the default cloudscape preset, whose sky is the atmosphere
  const std::string base = "render --luts " + q(tmp / "luts") + " --width 48 --height 27 --terms ambient ";
  for (const char* c : {"--sky-color 1,1,1", "--sky-below 0.1", "--sky-model atmosphere --sky-color 0,0,0",
                        "--sky-model foggy"}) {
    INFO(c);
    const CliResult r = runCli(base + c + " --out " + q(tmp / "refused.exr"));
    CHECK(r.exitCode == 2);
    CHECK(lineCount(r.err) == 1);
    CHECK(r.err.find("--sky-") != std::string::npos);
    if (std::string(c).find("foggy") == std::string::npos) CHECK(r.err.find("--sky-model uniform") != std::string::npos);
  }
  CHECK_FALSE(fs::exists(tmp / "refused.exr"));
  // Ambient alone: under the atmosphere the clouds take its sky's light; under a uniform black
  // sky none.
  const CliResult lit = runCli(base + "--out " + q(tmp / "atmosphere.exr"));
  const CliResult dark = runCli(base + "--sky-model uniform --sky-color 0,0,0 --out " + q(tmp / "black.exr"));
  REQUIRE(lit.exitCode == 0);
  REQUIRE(dark.exitCode == 0);
  int w = 0, h = 0;
  const auto a = readExrChannels(tmp / "atmosphere.exr", {"R", "A"}, w, h);
  const auto b = readExrChannels(tmp / "black.exr", {"R", "A"}, w, h);
  double litSum = 0.0, darkSum = 0.0;
  std::size_t cloud = 0;
  for (std::size_t i = 0; i < a[0].size(); ++i) {
    if (b[1][i] <= 0.01f) continue;
    ++cloud;
    litSum += a[0][i];
    darkSum += std::abs(b[0][i]);
  }
  REQUIRE(cloud > 50);
  CHECK(litSum > 0.01 * static_cast<double>(cloud));
  CHECK(darkSum == 0.0);
  // the ray marcher has only the uniform sky
  const CliResult marched = runCli(renderArgs(tmp / "luts", kScene, tmp / "marched.png", "--method raymarch --sky-model atmosphere"));
  CHECK(marched.exitCode == 2);
  CHECK(marched.err.find("--sky-model") != std::string::npos);
  // nor the path tracer; a scene file's atmosphere sky is refused by both, naming the file's
  // field, and --sky-model uniform lights it by its uniform sky
  const fs::path atmosphereScene = tmp / "atmosphere-sky.json";
  std::ofstream(atmosphereScene) << R"({"sky": {"model": "atmosphere"}, "particles": [{"center": [0, 0, 0], "radii": 1}]})";
  const std::string small = " --width 8 --height 6 --quiet ";
  const std::string traced = "reference scene --particles " + q(atmosphereScene) + small + "--spp 4 --out " + q(tmp / "t.exr");
  for (const std::string& c : {renderArgs(tmp / "luts", atmosphereScene, tmp / "m.exr", "--method raymarch" + small), traced}) {
    INFO(c);
    const CliResult r = runCli(c);
    CHECK(r.exitCode == 2);
    CHECK(lineCount(r.err) == 1);
    CHECK(r.err.find("atmosphere-sky.json: sky.model") != std::string::npos);
    CHECK(r.err.find("--sky-model uniform") != std::string::npos);
    CHECK(runCli(c + " --sky-model uniform").exitCode == 0);
    CHECK(runCli(c + " --sky-model foggy").exitCode == 2);
  }
  CHECK(fs::exists(tmp / "m.exr"));
  CHECK(fs::exists(tmp / "t.exr"));
}

TEST_CASE("render CLI: a path whose sun moves relights only the sun; --diffusion-warm-cycles out of range is bad usage",
          "[render][cli][kept]") {
  TempDir tmp;
  writeSyntheticLutSet(tmp / "luts");
  const fs::path path = tmp / "sun.json";
  const std::string frame = R"({"seconds": 0, "eye": [0, 1.2, 9], "target": [0, 0.6, 0], "up": [0, 1, 0], "fov_deg": 40, "sun": )";
  std::ofstream(path) << R"({"format": "cloudlut camera path", "version": 1, "frames": [)" << frame << "[0.5, 0.8, 0.35]}, "
                      << frame << "[0.45, 0.8, 0.42]}]}";
  const auto mentions = [](const std::string& text) {
    std::size_t n = 0;
    for (std::size_t at = text.find("only the sun moved"); at != std::string::npos; at = text.find("only the sun moved", at + 1))
      ++n;
    return n;
  };
  const CliResult moved = runCli(renderArgs(tmp / "luts", kScene, tmp / "m.exr", "--blend volume --path " + q(path)));
  REQUIRE(moved.exitCode == 0);
  CHECK(mentions(moved.out) == 1);  // the second frame
  CHECK(moved.out.find("the diffusion solve started from the frame before's") != std::string::npos);
  const CliResult relit = runCli(renderArgs(tmp / "luts", kScene, tmp / "r.exr", "--blend volume --relight --path " + q(path)));
  REQUIRE(relit.exitCode == 0);
  CHECK(mentions(relit.out) == 0);
  for (const char* bad : {"-1", "1001", "x"}) {
    const CliResult r = runCli(renderArgs(tmp / "luts", kScene, tmp / "b.exr", std::string("--diffusion-warm-cycles ") + bad));
    INFO(bad << ": " << r.err);
    CHECK(r.exitCode == 2);
    CHECK(lineCount(r.err) == 1);
    CHECK(r.err.find("diffusion-warm-cycles") != std::string::npos);
  }
}

TEST_CASE("render CLI: still frames keep the light-space volumes, --relight builds them each frame, the same images",
          "[render][cli][kept]") {
  TempDir tmp;
  writeSyntheticLutSet(tmp / "luts");
  const std::string still = "--blend volume --frames 3 --speed 0 --yaw 0";
  const CliResult kept = runCli(renderArgs(tmp / "luts", kScene, tmp / "kept.exr", still));
  const CliResult relit = runCli(renderArgs(tmp / "luts", kScene, tmp / "relit.exr", still + " --relight"));
  REQUIRE(kept.exitCode == 0);
  REQUIRE(relit.exitCode == 0);
  const auto mentions = [](const std::string& text) {
    std::size_t n = 0;
    for (std::size_t at = text.find("light-space volumes kept"); at != std::string::npos;
         at = text.find("light-space volumes kept", at + 1))
      ++n;
    return n;
  };
  CHECK(mentions(kept.out) == 2);  // every frame but the first
  CHECK(mentions(relit.out) == 0);
  for (const char* frame : {"_0000.exr", "_0001.exr", "_0002.exr"}) {
    INFO(frame);
    const std::string a = readFile(tmp / (std::string("kept") + frame)), b = readFile(tmp / (std::string("relit") + frame));
    REQUIRE(!a.empty());
    CHECK(a == b);
  }
}
