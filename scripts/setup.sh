#!/usr/bin/env bash
# Installs the Debian 12 packages cloudlut builds and runs with, when any is missing.
set -euo pipefail
packages=(build-essential cmake pkg-config libopenexr-dev libglm-dev libtbb-dev catch2
          libcxxopts-dev nlohmann-json3-dev libeigen3-dev libosmesa6-dev libgl-dev libstb-dev
          python3-matplotlib clang libclang-rt-14-dev
          libglfw3-dev xvfb xdotool)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "installing: ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
