#pragma once
// A `cloudlut` verb. Each verb lives in its own file and registers itself with a static
// CommandRegistration; main() dispatches on the first argument.
#include <functional>
#include <string>
#include <vector>

namespace cloudlut::cli {

struct Command {
  std::string name;
  std::string summary;
  // argv[0] is "cloudlut VERB"; returns the process exit code. Errors are thrown
  // (UsageError -> 2, FileError -> 1) and reported by main.
  std::function<int(int argc, char** argv)> run;
};

std::vector<Command>& commandRegistry();

struct CommandRegistration {
  CommandRegistration(std::string name, std::string summary,
                      std::function<int(int, char**)> run) {
    commandRegistry().push_back({std::move(name), std::move(summary), std::move(run)});
  }
};

}  // namespace cloudlut::cli
