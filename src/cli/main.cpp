// cloudlut: precomputed lighting of particle-based cumulus clouds.
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>

#include "cli/Command.h"
#include "cli/TtyProgress.h"
#include "core/Errors.h"

namespace cloudlut::cli {
std::vector<Command>& commandRegistry() {
  static std::vector<Command> registry;
  return registry;
}
}  // namespace cloudlut::cli

namespace {

void printUsage(std::FILE* out) {
  std::fprintf(out,
               "cloudlut %s: precomputed lighting of particle-based cumulus clouds\n\n"
               "usage: cloudlut VERB [options]   (cloudlut VERB --help for its options)\n\nverbs:\n",
               CLOUDLUT_VERSION);
  for (const auto& c : cloudlut::cli::commandRegistry())
    std::fprintf(out, "  %-10s %s\n", c.name.c_str(), c.summary.c_str());
  std::fprintf(out, "\nexit codes: 0 ok, 1 check failed or bad file, 2 bad usage\n");
}

}  // namespace

int main(int argc, char** argv) {
  using namespace cloudlut;
  if (argc < 2) {
    printUsage(stderr);
    return kExitUsage;
  }
  const std::string verb = argv[1];
  if (verb == "--help" || verb == "-h" || verb == "help") {
    printUsage(stdout);
    return kExitOk;
  }
  if (verb == "--version") {
    std::printf("cloudlut %s\n", CLOUDLUT_VERSION);
    return kExitOk;
  }
  for (const auto& c : cli::commandRegistry()) {
    if (c.name != verb) continue;
    std::string program = "cloudlut " + verb;
    argv[1] = program.data();
    try {
      return c.run(argc - 1, argv + 1);
    } catch (const UsageError& e) {
      cli::finishTtyProgress();
      std::fprintf(stderr, "cloudlut %s: error: %s\n", verb.c_str(), e.what());
      return kExitUsage;
    } catch (const FileError& e) {
      cli::finishTtyProgress();
      std::fprintf(stderr, "cloudlut %s: error: %s\n", verb.c_str(), e.what());
      return kExitFailed;
    } catch (const std::bad_alloc&) {
      cli::finishTtyProgress();
      std::fprintf(stderr, "cloudlut %s: error: out of memory\n", verb.c_str());
      return kExitUsage;
    } catch (const std::exception& e) {
      cli::finishTtyProgress();
      std::fprintf(stderr, "cloudlut %s: error: %s\n", verb.c_str(), e.what());
      return kExitFailed;
    }
  }
  std::fprintf(stderr, "cloudlut: error: unknown verb '%s' (cloudlut --help lists them)\n",
               verb.c_str());
  return kExitUsage;
}
