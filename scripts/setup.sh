#!/usr/bin/env bash
# Installs the Debian bookworm packages shanshui needs, if any are missing.
# Idempotent and quiet when everything is present; needs root (or sudo) otherwise.
set -euo pipefail

packages=(
  build-essential cmake pkg-config ninja-build
  libcgal-dev libeigen3-dev libcgal-demo
  libopencv-dev
  libopenimageio-dev openimageio-tools libpng-dev libjpeg-dev libisal-dev
  libglm-dev libglfw3-dev libepoxy-dev libegl-dev libgl-dev
  libegl-mesa0 libgl1-mesa-dri libglx-mesa0
  libimgui-dev libcli11-dev nlohmann-json3-dev libtinyobjloader-dev
  libgdal-dev gdal-bin libassimp-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  xvfb xauth
  clang-format git
)

# `setup.sh fuzz`: also clang and its libFuzzer runtime, for make fuzz.
if [ "${1:-}" = "fuzz" ]; then
  packages+=(clang libclang-rt-14-dev)
fi

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${db:Status-Status}' "$p" 2>/dev/null || true)
  [ "$status" = "installed" ] || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "setup: installing ${#missing[@]} Debian package(s): ${missing[*]}" >&2
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "setup: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  sudo_cmd=(sudo)
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "setup: done" >&2
