#include "BakedFixtures.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>
#include <system_error>

#include "io/LutIo.h"
#include "Files.h"

namespace cloudlut::test {

namespace {

namespace fs = std::filesystem;

// An exclusive advisory lock on a file, held while the object lives (released by the kernel
// if the process dies).
class FileLock {
 public:
  explicit FileLock(const fs::path& path) : fd_(::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644)) {
    if (fd_ < 0 || ::flock(fd_, LOCK_EX) != 0) throw std::runtime_error("cannot lock " + path.string());
  }
  ~FileLock() { ::close(fd_); }
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;

 private:
  int fd_;
};

// Identifies the test executable (a rebuilt one never reads an older one's fixtures).
std::string executableStamp() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec) return "unknown";
  const auto size = fs::file_size(exe, ec);
  const auto time = fs::last_write_time(exe, ec).time_since_epoch().count();
  return std::to_string(size) + "-" + std::to_string(time);
}

bake::ScatteringResult bakeDefault(int orders) {
  bake::ScatteringSettings s;
  s.orders = orders;
  return bake::bakeScattering(s);
}

void save(const bake::ScatteringResult& r, const fs::path& dir) {
  fs::create_directories(dir);
  io::writeBinaryLut(*r.single, io::SampleType::Float, dir / "single.bin");
  io::writeBinaryLut(*r.multiple, io::SampleType::Float, dir / "multiple.bin");
  writeFile(dir / "report.json", r.report.dump());
}

bake::ScatteringResult load(const fs::path& dir) {
  bake::ScatteringResult r;
  r.single = io::readLut(dir / "single.bin").table;
  r.multiple = io::readLut(dir / "multiple.bin").table;
  r.report = nlohmann::json::parse(readFile(dir / "report.json"));
  return r;
}

// The fixture from the shared directory, baking and publishing it first if no process has.
bake::ScatteringResult bakeOrLoad(int orders, const fs::path& cache) {
  fs::create_directories(cache);
  const std::string key = "default-scattering-orders-" + std::to_string(orders) + "-" + executableStamp();
  const FileLock lock(cache / (key + ".lock"));
  const fs::path final = cache / key;
  if (fs::exists(final / "report.json")) return load(final);
  bake::ScatteringResult r = bakeDefault(orders);
  const fs::path scratch = cache / (key + ".tmp-" + std::to_string(::getpid()));
  fs::remove_all(scratch);
  save(r, scratch);
  fs::rename(scratch, final);  // atomic: a reader sees all of it or nothing
  return r;
}

}  // namespace

const bake::ScatteringResult& defaultScattering(int orders) {
  static std::mutex mutex;
  static std::map<int, bake::ScatteringResult> baked;
  const std::lock_guard<std::mutex> guard(mutex);
  auto it = baked.find(orders);
  if (it == baked.end()) {
    const char* cache = std::getenv("CLOUDLUT_TEST_FIXTURE_DIR");
    it = baked.emplace(orders, cache && *cache ? bakeOrLoad(orders, cache) : bakeDefault(orders)).first;
  }
  return it->second;
}

}  // namespace cloudlut::test
