#!/usr/bin/env bash
# Install what is missing, build with warnings as errors and run the whole test suite; then the
# same suite built by clang with AddressSanitizer + UndefinedBehaviorSanitizer (the build that
# also holds the libFuzzer targets); then a short smoke run of every fuzz target.
# CLOUDLUT_QUICK_TEST=1 skips the last two.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
jobs=$(nproc)

echo "== release build and tests"
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DCLOUDLUT_WERROR=ON >/dev/null
cmake --build build -j"$jobs"
(cd build && ctest --output-on-failure -j"$jobs")

[ "${CLOUDLUT_QUICK_TEST:-0}" = "1" ] && exit 0

echo "== sanitizer build (clang: ASan + UBSan + fuzz targets) and the same tests under it"
CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=Release -DCLOUDLUT_FUZZ=ON >/dev/null
cmake --build build-fuzz -j"$jobs"
# Mesa's llvmpipe keeps allocations until exit: leaks are checked everywhere but in its libraries.
(cd build-fuzz && LSAN_OPTIONS="suppressions=$PWD/../tests/lsan.supp:print_suppressions=0" \
  ASAN_OPTIONS="detect_leaks=1:abort_on_error=1" UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1" \
  ctest --output-on-failure -j"$jobs")

echo "== fuzz smoke run"
bash scripts/fuzz.sh "${CLOUDLUT_FUZZ_SECONDS:-20}"
