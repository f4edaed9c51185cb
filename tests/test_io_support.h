#pragma once
// Shared helpers of the io tests: scratch directories, small deterministic tables, file bytes.
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "core/Table4D.h"

namespace iotest {

// A fresh directory under the system temp dir, removed with everything in it at scope exit.
class TempDir {
 public:
  TempDir() {
    static std::atomic<int> counter{0};
    path_ = std::filesystem::temp_directory_path() /
            ("cloudlut_io_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

// A small table with the optical-depth table's axes, `channels` channels and deterministic
// values spread over [lo, hi] (a fixed linear-congruential sequence).
inline cloudlut::Table4D makeTable(std::array<int, 4> dims, int channels, float lo = -0.25f,
                                   float hi = 1.25f, std::uint32_t seed = 1,
                                   const std::string& name = "optical_depth") {
  const double pi = 3.14159265358979323846;
  std::array<cloudlut::Axis, 4> axes = {
      cloudlut::Axis{"phi_s", "rad", 0.0, 2.0 * pi, dims[0], true},
      cloudlut::Axis{"theta_s", "rad", 0.0, pi, dims[1], false},
      cloudlut::Axis{"phi_v", "rad", 0.0, 2.0 * pi, dims[2], true},
      cloudlut::Axis{"theta_v", "rad", 0.0, 0.5 * pi, dims[3], false}};
  std::vector<cloudlut::Channel> names = {{"mean_density", "mean normalized density"},
                                          {"first_matter", "distance to first matter / chord"},
                                          {"extra_b", "test channel"},
                                          {"extra_a", "test channel"}};
  names.resize(static_cast<std::size_t>(channels));
  cloudlut::Table4D table(name, axes, names);
  // built first, then moved in: clang 14 leaks the old value of `json& = {init-list}`
  nlohmann::json parameters = {{"extinction", 0.07}, {"radius", 183.8}, {"model", "test"}};
  table.parameters() = std::move(parameters);
  std::uint32_t state = seed;
  for (float& v : table.data()) {
    state = state * 1664525u + 1013904223u;
    v = lo + (hi - lo) * static_cast<float>(state >> 8) / 16777216.0f;
  }
  return table;
}

inline std::string readBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

inline void writeBytes(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// Files in `dir` (names only), to check that failed writes leave nothing behind.
inline std::vector<std::string> listDir(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    names.push_back(e.path().filename().string());
  return names;
}

}  // namespace iotest
