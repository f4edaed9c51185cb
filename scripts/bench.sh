#!/usr/bin/env bash
# Runs every `cloudlut bench` suite once (all figures of one run, so their ratios compare) and
# draws the charts into out/bench. Extra arguments go to `cloudlut bench` (e.g. --quick).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
./build/cloudlut bench --out out/bench "$@"
/usr/bin/python3 scripts/plot_bench.py out/bench/bench.csv out/bench/speed_accuracy.png
/usr/bin/python3 scripts/plot_render_bench.py out/bench/bench.csv out/bench/ground_truth.png out/bench/frames.png || true
/usr/bin/python3 scripts/plot_atmosphere_bench.py out/bench/bench.csv out/bench/atmosphere.png || true
echo "charts: out/bench/speed_accuracy.png out/bench/ground_truth.png out/bench/frames.png out/bench/atmosphere.png"
