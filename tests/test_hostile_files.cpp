// Regression tests for the hostile-input probe of issue 16, the faults about files and work:
// EXR headers that claim more pixels than their file holds (5, 6) or a LUT description that
// claims more than its window (8), an interrupted re-bake (7)
// and a render of more particles than it can finish (4).
#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <string>
#include <thread>

#include "core/Errors.h"
#include "io/ExrImage.h"
#include "scene/Scene.h"
#include "io/LutIo.h"
#include "support/Checks.h"
#include "support/CliRunner.h"
#include "support/SmallTables.h"

using namespace cloudlut;
using namespace cloudlut::test;
namespace fs = std::filesystem;

namespace {

// Rewrites the data window (box2i xmin, ymin, xmax, ymax) of the EXR file's header in place.
void claimDataWindow(const fs::path& file, int width, int height) {
  std::string bytes = readFile(file);
  const std::string key("dataWindow\0box2i\0", 17);
  const std::size_t at = bytes.find(key);
  REQUIRE(at != std::string::npos);
  const std::int32_t box[4] = {0, 0, width - 1, height - 1};
  std::memcpy(&bytes[at + key.size() + 4], box, sizeof box);  // after the int32 size
  writeFile(file, bytes);
}


// Forks and execs the re-bake. SIGTERM and SIGINT stay blocked across the fork until the child
// has dropped the test framework's handlers, so a signal that arrives before exec kills it by the
// default action instead of running the parent's handler in the child.
pid_t startRebake(const fs::path& out) {
  sigset_t block, previous;
  sigemptyset(&block);
  sigaddset(&block, SIGTERM);
  sigaddset(&block, SIGINT);
  sigprocmask(SIG_BLOCK, &block, &previous);
  const pid_t pid = fork();
  if (pid != 0) {
    sigprocmask(SIG_SETMASK, &previous, nullptr);
    return pid;
  }
  {
    signal(SIGTERM, SIG_DFL);
    signal(SIGINT, SIG_DFL);
    sigprocmask(SIG_SETMASK, &previous, nullptr);
    const std::string o = out.string();
    execl(CLOUDLUT_EXE, CLOUDLUT_EXE, "bake", "--tables", "optical-depth", "--res-od", "32,16,32,16", "--precision",
          "float", "--format", "both", "--quiet", "--out", o.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  return pid;
}

// The optical-depth dims of the set in `dir`, which must load completely and pass `info`.
std::array<int, 4> consistentSetDims(const fs::path& dir) {
  const io::LutSet set = io::readLutSet(dir);  // checks every table against the manifest
  REQUIRE(set.tables.count("optical_depth") == 1);
  const CliResult info = runCli("info '" + dir.string() + "'");
  CHECK(info.exitCode == 0);
  return set.tables.at("optical_depth").table.dims();
}

}  // namespace

TEST_CASE("fault 5: an EXR image whose data window claims more than its file holds is refused unread", "[io][hostile]") {
  TempDir tmp;
  // noise, which ZIP cannot shrink: the file is large enough to hold the line-offset table of
  // the window it will claim, so that only the pixel budget can refuse it
  io::ExrImage image(64, 64);
  std::vector<float>& red = image.channel("R");
  std::uint32_t state = 1;
  for (float& v : red) v = static_cast<float>((state = state * 1664525u + 1013904223u) >> 8);
  io::writeExrImage(image, tmp / "small.exr");
  REQUIRE_NOTHROW(io::readExrImage(tmp / "small.exr"));
  claimDataWindow(tmp / "small.exr", 16384, 16384);  // a few KB claiming 1 GiB of floats
  const std::string message = fileErrorOf([&] { io::readExrImage(tmp / "small.exr"); });
  CHECK(message.find("small.exr: corrupt: its data window (16384x16384") != std::string::npos);
  // through compare, exit 1
  const CliResult r = runCli("compare '" + (tmp / "small.exr").string() + "' '" + (tmp / "small.exr").string() + "'");
  CHECK(r.exitCode == 1);
  CHECK(r.err.find("data window") != std::string::npos);

  io::ExrImage wide(8, 8);
  for (int c = 0; c < 200; ++c) wide.channel("c" + std::to_string(c)).assign(64, 1.0f);
  io::writeExrImage(wide, tmp / "wide.exr");
  CHECK(fileErrorOf([&] { io::readExrImage(tmp / "wide.exr"); }).find("more than 64 channels") != std::string::npos);
}

TEST_CASE("fault 6: a LUT EXR whose data window claims more than its file holds is refused unread", "[io][hostile]") {
  TempDir tmp;
  const Table4D table = makeTable({16, 8, 16, 8}, 2, 0.0f, 1.0f);  // a 64 KB atlas of noise
  io::writeExrLut(table, io::SampleType::Half, tmp / "t.exr");
  REQUIRE_NOTHROW(io::readLut(tmp / "t.exr"));
  claimDataWindow(tmp / "t.exr", 16384, 16384);  // what a 128^4 table's atlas would be
  const std::string message = fileErrorOf([&] { io::readLut(tmp / "t.exr"); });
  CHECK(message.find("t.exr: corrupt: its data window (16384x16384") != std::string::npos);
  CHECK(runCli("info '" + (tmp / "t.exr").string() + "'").exitCode == 1);
}

TEST_CASE("fault 8: a LUT EXR whose description claims a larger table than its window is refused unallocated", "[io][hostile]") {
  TempDir tmp;
  const Table4D table = makeTable({16, 8, 16, 8}, 2, 0.0f, 1.0f, 1, "optical_depth_pad");
  io::writeExrLut(table, io::SampleType::Half, tmp / "t.exr");
  REQUIRE_NOTHROW(io::readLut(tmp / "t.exr"));
  // The description (the "cloudlut" attribute) now claims 128x64x128x64 nodes: 537 MB of floats
  // for a file of a few hundred KB. The name loses the 4 bytes the sizes gain, so the header
  // keeps its length and OpenEXR parses it as before.
  std::string bytes = readFile(tmp / "t.exr");
  const auto replaceOnce = [&](const std::string& from, const std::string& to) {
    const std::size_t at = bytes.find(from);
    REQUIRE(at != std::string::npos);
    bytes.replace(at, from.size(), to);
  };
  replaceOnce("\"name\":\"optical_depth_pad\"", "\"name\":\"optical_depth\"");
  for (int k = 0; k < 2; ++k) {
    replaceOnce("\"size\":16,", "\"size\":128,");
    replaceOnce("\"size\":8,", "\"size\":64,");
  }
  writeFile(tmp / "t.exr", bytes);
  rusage before{}, after{};
  getrusage(RUSAGE_SELF, &before);
  const std::string message = fileErrorOf([&] { io::readLut(tmp / "t.exr"); });
  getrusage(RUSAGE_SELF, &after);
  CHECK(message.find("t.exr: the description claims a table of 128x64x128x64 nodes x 2 channels, more than the") !=
        std::string::npos);
  // the peak resident size (kB) grew by less than the claim, so the table was never filled
  CHECK(after.ru_maxrss - before.ru_maxrss < 128 * 1024);
  CHECK(runCli("info '" + (tmp / "t.exr").string() + "'").exitCode == 1);
}

TEST_CASE("fault 7: a re-bake killed at any moment leaves the old set or the new one", "[cli][hostile][interrupt]") {
  TempDir tmp;
  const fs::path dir = tmp / "luts";
  REQUIRE(runCli("bake --tables optical-depth --res-od 16,8,16,8 --quiet --out '" + dir.string() + "'").exitCode == 0);
  writeFile(dir / "notes.txt", "the user's own file");
  const std::array<int, 4> oldDims{16, 8, 16, 8}, newDims{32, 16, 32, 16};
  // How long a re-bake takes, to spread the kills over it (and past its end).
  const auto t0 = std::chrono::steady_clock::now();
  {
    const pid_t pid = startRebake(tmp / "timing");
    int status = 0;
    waitpid(pid, &status, 0);
    REQUIRE((WIFEXITED(status) && WEXITSTATUS(status) == 0));
  }
  const double bakeMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  int oldSeen = 0, newSeen = 0, kills = 0;
  const int signals[] = {SIGKILL, SIGTERM, SIGINT};
  // Fractions of the timed bake; a negative one lets the bake finish before the signal, so the
  // new set is seen whatever the machine's load does to the bake's length.
  const double fractions[] = {0.0, 0.1, 0.3, 0.5, 0.7, 0.85, 0.95, 1.0, -1.0};
  for (const int sig : signals)
    for (const double f : fractions) {
      INFO("signal " << sig << " at " << f << " of the bake (" << bakeMs << " ms)");
      const pid_t pid = startRebake(dir);
      int status = 0;
      if (f < 0)
        waitpid(pid, &status, 0);
      else
        std::this_thread::sleep_for(std::chrono::microseconds(static_cast<long long>(f * bakeMs * 1000.0)));
      if (f >= 0 && waitpid(pid, &status, WNOHANG) != pid) {
        kill(pid, sig);
        waitpid(pid, &status, 0);
        kills += WIFSIGNALED(status) ? 1 : 0;
      }
      const std::array<int, 4> dims = consistentSetDims(dir);
      CHECK((dims == oldDims || dims == newDims));
      if (dims == oldDims) ++oldSeen;
      if (dims == newDims) ++newSeen;
      CHECK(readFile(dir / "notes.txt") == "the user's own file");  // carried over by every swap
      if (dims == newDims)  // back to the old set for the next kill
        REQUIRE(runCli("bake --tables optical-depth --res-od 16,8,16,8 --quiet --out '" + dir.string() + "'").exitCode == 0);
    }
  CHECK(kills >= 9);
  CHECK(oldSeen >= 3);  // the kills landed during the bake...
  CHECK(newSeen >= 3);  // ... and some after it finished: both outcomes were exercised
  // Staging directories of the killed bakes are gone once a later bake ran beside them.
  REQUIRE(runCli("bake --tables optical-depth --res-od 16,8,16,8 --quiet --out '" + dir.string() + "'").exitCode == 0);
  for (const auto& e : fs::directory_iterator(tmp.path()))
    CHECK(e.path().filename().string().find(".baking.") == std::string::npos);
}

TEST_CASE("fault 4: a render of more particles than it can finish is refused before it starts", "[cli][hostile]") {
  TempDir tmp;
  // One particle over the ray marcher's limit (2^18): refused there; the particle method (limit
  // 2^20) reads on and stops at the missing tables instead.
  const std::size_t count = scene::kMaxRayMarchParticles + 1;
  std::string json = "{\"particles\": [";
  json.reserve(32 * count);
  for (std::size_t i = 0; i < count; ++i) json += i ? ",{\"center\":[0,0,0],\"radii\":1}" : "{\"center\":[0,0,0],\"radii\":1}";
  json += "]}";
  writeFile(tmp / "big.json", json);
  const std::string scene = " --particles '" + (tmp / "big.json").string() + "' --out '" + (tmp / "x.png").string() + "'";
  const CliResult marched = runCli("render --method raymarch" + scene);
  CHECK(marched.exitCode == 2);
  CHECK(marched.err.find("big.json: " + std::to_string(count) + " particles, more than") != std::string::npos);
  const CliResult drawn = runCli("render --method particles --luts '" + (tmp / "none").string() + "'" + scene);
  CHECK(drawn.exitCode != 0);
  CHECK(drawn.err.find("particles, more than") == std::string::npos);
  CHECK(drawn.err.find("none") != std::string::npos);  // the missing tables are the complaint
  // The particle method's own limit, through the check both verbs call (a scene file of 2^20
  // particles would take long to write and parse in a sanitised test run).
  CHECK_NOTHROW(scene::checkRenderParticleCount(scene::kMaxRenderParticles, "big.json"));
  CHECK_THROWS_AS(scene::checkRenderParticleCount(scene::kMaxRenderParticles + 1, "big.json"), UsageError);
  CHECK_THROWS_AS(scene::checkRenderParticleCount(count, "big.json", scene::kMaxRayMarchParticles, "raymarch"), UsageError);
}
