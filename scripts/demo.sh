#!/usr/bin/env bash
# The main job on embedded defaults: install what is missing, build, bake the default tables
# into out/luts and describe them; bake the converged tables a cloudscape needs (every
# scattering order: light crosses a cumulus in hundreds of them, docs/LIGHTING.md) into
# out/luts-converged, and render the default cloudscape from them into out/cloudscape.png.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
./build/cloudlut bake --out out/luts
./build/cloudlut info out/luts --energy
./build/cloudlut bake --out out/luts-converged --orders converged
./build/cloudlut render --luts out/luts-converged --out out/cloudscape.png
