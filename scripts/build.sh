#!/usr/bin/env bash
# Configures and builds cloudlut (Release) into build/. Extra arguments go to CMake.
set -euo pipefail
cd "$(dirname "$0")/.."
werror=OFF
[ "${CI:-}" = "true" ] && werror=ON
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DCLOUDLUT_WERROR="$werror" "$@" >/dev/null
cmake --build build -j"$(nproc)"
