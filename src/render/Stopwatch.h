#pragma once
// Wall-clock time of a pass (the passes end with glFinish, so that it is the GPU's time too).
#include <chrono>

namespace cloudlut::render {

class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  // Seconds since construction.
  double seconds() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

 private:
  std::chrono::steady_clock::time_point start_;
};

}  // namespace cloudlut::render
