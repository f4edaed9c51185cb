#!/usr/bin/env bash
# Install what is missing, build with warnings as errors and run the whole test suite; then the
# same suite built with AddressSanitizer + UndefinedBehaviorSanitizer; then a short smoke run of
# every libFuzzer target. CLOUDLUT_QUICK_TEST=1 skips the last two.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
jobs=$(nproc)

echo "== release build and tests"
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DCLOUDLUT_WERROR=ON >/dev/null
cmake --build build -j"$jobs"
(cd build && ctest --output-on-failure -j"$jobs")

[ "${CLOUDLUT_QUICK_TEST:-0}" = "1" ] && exit 0

echo "== sanitizer build (ASan + UBSan) and tests"
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCLOUDLUT_SANITIZE=ON >/dev/null
cmake --build build-asan -j"$jobs"
# Mesa's llvmpipe keeps allocations until exit: leaks are checked everywhere but in its libraries.
export LSAN_OPTIONS="suppressions=$PWD/tests/lsan.supp:print_suppressions=0"
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
(cd build-asan && ctest --output-on-failure -j"$jobs")

echo "== fuzz smoke run"
bash scripts/fuzz.sh "${CLOUDLUT_FUZZ_SECONDS:-20}"
