#pragma once
// Progress reporting from long computations. A computation calls the function with the name
// of its current stage and the fraction of the whole work done, in [0, 1]; it may be called
// from worker threads (calls are serialised by the caller's implementation) and must be cheap.
#include <functional>
#include <string_view>

namespace cloudlut {

using ProgressFn = std::function<void(std::string_view stage, double fraction)>;

inline void reportProgress(const ProgressFn& fn, std::string_view stage, double fraction) {
  if (fn) fn(stage, fraction);
}

}  // namespace cloudlut
