#pragma once
// A progress bar on stderr when stderr is a terminal and the user did not ask for quiet;
// otherwise a ProgressFn that prints nothing.
#include "core/Progress.h"

namespace cloudlut::cli {

ProgressFn makeTtyProgress(bool quiet);
// Ends the current bar line, if one was drawn.
void finishTtyProgress();

}  // namespace cloudlut::cli
