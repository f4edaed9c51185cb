#pragma once
// Runs the real `cloudlut` executable for end-to-end tests and captures its output.
#include <sys/wait.h>

#include <cstdlib>
#include <string>

#include "Files.h"
#include "TempDir.h"

namespace cloudlut::test {

struct CliResult {
  int exitCode;
  std::string out;
  std::string err;
};

// Runs `cloudlut ARGS` (ARGS is passed to /bin/sh as is) with stdin closed.
inline CliResult runCli(const std::string& args) {
  TempDir tmp;
  const std::string cmd = std::string("'") + CLOUDLUT_EXE + "' " + args + " > '" + (tmp / "out").string() +
                          "' 2> '" + (tmp / "err").string() + "' < /dev/null";
  const int status = std::system(cmd.c_str());
  return CliResult{WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status), readFile(tmp / "out"),
                   readFile(tmp / "err")};
}

}  // namespace cloudlut::test
