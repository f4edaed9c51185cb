// `kill -9` during a bake leaves every final file name either absent or complete (the set's
// replacement as a whole, and kills by SIGTERM and SIGINT: test_hostile_files.cpp, fault 7).
// The bake is killed at moments chosen while it is writing (a temporary file exists), when the
// outcome is most at risk, and at a few points during the computation.
#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include <nlohmann/json.hpp>

#include "support/CliRunner.h"
#include "io/LutIo.h"

using namespace cloudlut;
using namespace cloudlut::test;
namespace fs = std::filesystem;

namespace {

pid_t startBake(const fs::path& out) {
  const pid_t pid = fork();
  if (pid == 0) {
    const std::string o = out.string();
    execl(CLOUDLUT_EXE, CLOUDLUT_EXE, "bake", "--tables", "optical-depth", "--res-od", "64,32,64,48",
          "--precision", "float", "--format", "both", "--quiet", "--out", o.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  return pid;
}

// A temporary file in the bake's staging directory beside `out` (".NAME.baking.PID",
// io/LutSetTransaction.h), where every file of the new set is written.
bool tempFileExists(const fs::path& out) {
  std::error_code ec;
  const std::string prefix = "." + out.filename().string() + ".baking.";
  for (fs::directory_iterator it(out.parent_path(), ec), end; !ec && it != end; it.increment(ec)) {
    if (it->path().filename().string().rfind(prefix, 0) != 0) continue;
    std::error_code inner;
    for (fs::directory_iterator f(it->path(), inner), fend; !inner && f != fend; f.increment(inner))
      if (f->path().filename().string().find(".tmp") != std::string::npos) return true;
  }
  return false;
}

// Every final name present must be complete: tables load with valid checksums, the manifest
// parses and every table it lists loads.
// Returns how many final names were present.
int requireFinalNamesComplete(const fs::path& dir) {
  int present = 0;
  for (const char* name : {"optical_depth.bin", "optical_depth.exr"}) {
    if (!fs::exists(dir / name)) continue;
    ++present;
    REQUIRE_NOTHROW(io::readLut(dir / name));
  }
  if (fs::exists(dir / "manifest.json")) {
    ++present;
    REQUIRE_NOTHROW(io::readLutSet(dir));
  }
  return present;
}

}  // namespace

TEST_CASE("kill -9 during a bake leaves final names absent or complete", "[cli][interrupt]") {
  int killedWhileWriting = 0, finalNamesSeen = 0;
  // The set appears under its final name only when the bake commits it (io/LutSetTransaction.h):
  // the last run (delay -1) is not killed but finishes, and must leave a complete set.
  const int delaysAfterTempMs[] = {0, 2, 10, 40, 150, 400, 1000, -1};
  for (int delay : delaysAfterTempMs) {
    TempDir tmp;
    const fs::path out = tmp / "luts";
    const pid_t pid = startBake(out);
    const auto start = std::chrono::steady_clock::now();
    bool sawTemp = false;
    while (std::chrono::steady_clock::now() - start < std::chrono::seconds(60)) {
      if (tempFileExists(out)) { sawTemp = true; break; }
      int status = 0;
      if (waitpid(pid, &status, WNOHANG) == pid) break;  // finished before we saw a temp file
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    if (sawTemp && delay < 0) {
      waitpid(pid, nullptr, 0);
    } else if (sawTemp) {
      std::this_thread::sleep_for(std::chrono::milliseconds(delay));
      kill(pid, SIGKILL);
      waitpid(pid, nullptr, 0);
      ++killedWhileWriting;
    }
    INFO("delay after the first temporary file: " << delay << " ms");
    finalNamesSeen += requireFinalNamesComplete(out);
  }
  CHECK(killedWhileWriting >= 3);
  CHECK(finalNamesSeen >= 1);  // the finished run left its set: both outcomes were exercised

  // During the computation: nothing at all under a final name.
  TempDir tmp;
  const pid_t pid = startBake(tmp / "luts");
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  kill(pid, SIGKILL);
  waitpid(pid, nullptr, 0);
  requireFinalNamesComplete(tmp / "luts");
}
