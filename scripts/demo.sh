#!/usr/bin/env bash
# The main job on embedded defaults: install what is missing, build, bake the default tables
# into out/luts, describe them, and render the default cloudscape into out/cloudscape.png.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
./build/cloudlut bake --out out/luts
./build/cloudlut info out/luts --energy
./build/cloudlut render --luts out/luts --out out/cloudscape.png
