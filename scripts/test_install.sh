#!/usr/bin/env bash
# Installs a built cloudlut into a scratch prefix, builds examples/sample_lut against it with
# find_package(cloudlut), bakes a small LUT set with the installed binary and runs the example.
# usage: test_install.sh BUILD_DIR
set -euo pipefail
build=$(cd "$1" && pwd)
src=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/prefix" >/dev/null
test -x "$work/prefix/bin/cloudlut"
test -f "$work/prefix/include/cloudlut/cloudlut_reader.h"
test -f "$work/prefix/include/cloudlut/glsl/cloudlut_geometry.glsl"
cmake -S "$src/examples/sample_lut" -B "$work/example" -DCMAKE_PREFIX_PATH="$work/prefix" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$work/example" >/dev/null
"$work/prefix/bin/cloudlut" bake --tables optical-depth --res-od 16,8,16,8 --density-model sphere --format bin --quiet --out "$work/luts"
out=$("$work/example/sample_lut" "$work/luts" 1)
echo "$out"
# The homogeneous sphere: mean density 1, and optical depth = σ·L for the example's ray.
echo "$out" | grep -q "mean_density 1.000000"
echo "install test passed"
