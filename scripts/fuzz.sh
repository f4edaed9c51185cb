#!/usr/bin/env bash
# Builds cloudlut with clang, AddressSanitizer, UndefinedBehaviorSanitizer and the libFuzzer
# targets into build-fuzz/ (the same build runs the sanitized test suite: scripts/test.sh), and
# runs each fuzz target for SECONDS seconds (default 20: the CI smoke run; more for a campaign).
# Seeds come from tests/fuzz/corpus/NAME; new inputs go to out/fuzz/corpus/NAME, crashes to
# out/fuzz/crashes (turn each into a regression test in tests/ with its input).
# The smoke run uses a fixed seed (CLOUDLUT_FUZZ_SEED, default 1) so that CI explores the same
# inputs on every run; a campaign sets CLOUDLUT_FUZZ_SEED=0 for a random one.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-20}
seed=${CLOUDLUT_FUZZ_SEED:-1}
targets=(fuzz_binary_lut fuzz_exr_lut fuzz_exr_image fuzz_table_description fuzz_manifest fuzz_scene fuzz_query_csv)
CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=Release -DCLOUDLUT_FUZZ=ON >/dev/null
cmake --build build-fuzz -j"$(nproc)" --target "${targets[@]}"
mkdir -p out/fuzz/crashes
# A small quarantine keeps the resident size of long runs honest; a run whose resident size
# passes 2 GiB is a finding, and so is one allocation over 1 GiB. (OpenEXR's header parser
# reserves what an attribute declares, up to 2 GiB, before it finds the file short; the EXR
# reader checks every attribute by content before OpenEXR sees the header, see io/ExrLut.cpp,
# so no input of 64 KiB should come near these limits.)
export ASAN_OPTIONS=detect_leaks=0:allocator_may_return_null=1:quarantine_size_mb=16
status=0
for t in "${targets[@]}"; do
  mkdir -p "out/fuzz/corpus/$t"
  echo "fuzzing $t for ${seconds}s"
  if ! ./build-fuzz/tests/fuzz/$t "out/fuzz/corpus/$t" "tests/fuzz/corpus/$t" -max_total_time="$seconds" -seed="$seed" \
       -rss_limit_mb=2048 -malloc_limit_mb=1024 -max_len=65536 -artifact_prefix=out/fuzz/crashes/$t- -print_final_stats=1 \
       > "out/fuzz/$t.log" 2>&1; then
    echo "FAILED: $t (see out/fuzz/$t.log and out/fuzz/crashes)"
    tail -n 30 "out/fuzz/$t.log"
    status=1
  else
    grep -E "stat::number_of_executed_units" "out/fuzz/$t.log" || true
  fi
done
exit $status
