#include "cli/TtyProgress.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <memory>
#include <mutex>
#include <string>

namespace cloudlut::cli {

namespace {
std::mutex gMutex;
bool gDrawn = false;
}  // namespace

ProgressFn makeTtyProgress(bool quiet) {
  if (quiet || !isatty(STDERR_FILENO)) return {};
  auto last = std::make_shared<std::chrono::steady_clock::time_point>();
  auto lastStage = std::make_shared<std::string>();
  return [last, lastStage](std::string_view stage, double fraction) {
    std::lock_guard lock(gMutex);
    const auto now = std::chrono::steady_clock::now();
    if (stage == *lastStage && fraction < 1.0 && now - *last < std::chrono::milliseconds(100)) return;
    *last = now;
    *lastStage = std::string(stage);
    const int width = 30;
    const int filled = static_cast<int>(fraction * width + 0.5);
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.resize(width, '.');
    std::fprintf(stderr, "\r%-28.28s [%s] %5.1f%%", std::string(stage).c_str(), bar.c_str(),
                 100.0 * fraction);
    std::fflush(stderr);
    gDrawn = true;
  };
}

void finishTtyProgress() {
  std::lock_guard lock(gMutex);
  if (gDrawn) std::fputc('\n', stderr);
  gDrawn = false;
}

}  // namespace cloudlut::cli
