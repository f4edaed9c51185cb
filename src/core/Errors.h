#pragma once
// Error kinds and the exit codes every verb maps them to:
//   0 ok, 1 a check failed or a file is bad, 2 bad usage (options, values, resources).
#include <stdexcept>
#include <string>

namespace cloudlut {

inline constexpr int kExitOk = 0;
inline constexpr int kExitFailed = 1;
inline constexpr int kExitUsage = 2;

// Bad options or values, or a request the machine cannot satisfy: exit code 2.
struct UsageError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

// A file that is missing, truncated, corrupt, of the wrong version or not a LUT: exit code 1.
// The message names the file and the problem.
struct FileError : std::runtime_error {
  FileError(const std::string& path, const std::string& problem)
      : std::runtime_error(path + ": " + problem) {}
};

}  // namespace cloudlut
