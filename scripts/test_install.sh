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
for h in cloudlut_lut.h cloudlut_quadrilinear.h cloudlut_manifest.h cloudlut_reader.h cloudlut_glsl.hpp; do
  test -f "$work/prefix/include/cloudlut/$h"
done
test -f "$work/prefix/include/cloudlut/glsl/cloudlut_geometry.glsl"
cmake -S "$src/examples/sample_lut" -B "$work/example" -DCMAKE_PREFIX_PATH="$work/prefix" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$work/example" >/dev/null
"$work/prefix/bin/cloudlut" bake --tables optical-depth --res-od 16,8,16,8 --density-model sphere --format bin --quiet --out "$work/luts"
out=$("$work/example/sample_lut" "$work/luts" 1)
echo "$out"
# The homogeneous sphere: mean density 1, and optical depth = σ·L for the example's ray.
echo "$out" | grep -q "mean_density 1.000000"
# Scattering tables: the example's values equal `cloudlut query` for the same ray.
"$work/prefix/bin/cloudlut" bake --tables single,multiple --res-sc 32,32,8,3 --densities -1:1 --orders 3 --format bin --quiet --out "$work/sc"
out=$("$work/example/sample_lut" "$work/sc" 1.5)
echo "$out"
python3 - "$work" "$out" <<'PY'
import math, subprocess, sys
work, out = sys.argv[1], sys.argv[2]
n = lambda a: [x / math.sqrt(sum(y * y for y in a)) for x in a]
S = n([0.3, -0.5, 0.8]); v = n([-S[0] + 0.2, -S[1] + 0.1, -S[2]]); l = n([0.2, 0.9, 0.4])
open(work + "/rays.csv", "w").write("sx,sy,sz,vx,vy,vz,lx,ly,lz,density\n" + ",".join(f"{x:.9g}" for x in S + v + l + [1.5]) + "\n")
q = subprocess.run([work + "/prefix/bin/cloudlut", "query", work + "/sc", "--csv", work + "/rays.csv"],
                   check=True, capture_output=True, text=True).stdout.splitlines()[1].split(",")
example = dict(line.split() for line in out.splitlines() if line.split()[0] in ("single", "multiple"))
for key, column in (("single", 13), ("multiple", 14)):
    a, b = float(example[key]), float(q[column])
    print(f"{key}: example {a:.6g}, query {b:.6g}")
    assert b > 0 and abs(a - b) <= 1e-4 * b, key
PY
echo "install test passed"
