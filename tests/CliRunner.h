#pragma once
// Runs the real `cloudlut` executable for end-to-end tests and captures its output.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace cloudlut::test {

struct CliResult {
  int exitCode;
  std::string out;
  std::string err;
};

// A fresh, empty directory under the system temp dir, removed when the object dies.
class TempDir {
 public:
  TempDir() {
    std::string tmpl = (std::filesystem::temp_directory_path() / "cloudlut-test-XXXXXX").string();
    if (!mkdtemp(tmpl.data())) throw std::runtime_error("mkdtemp failed");
    path_ = tmpl;
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

inline std::string readFile(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Runs `cloudlut ARGS` (ARGS is passed to /bin/sh as is) with stdin closed.
inline CliResult runCli(const std::string& args) {
  TempDir tmp;
  const std::string cmd = std::string("'") + CLOUDLUT_EXE + "' " + args + " > '" +
                          (tmp / "out").string() + "' 2> '" + (tmp / "err").string() + "' < /dev/null";
  const int status = std::system(cmd.c_str());
  CliResult r{WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status), readFile(tmp / "out"),
              readFile(tmp / "err")};
  return r;
}

}  // namespace cloudlut::test
