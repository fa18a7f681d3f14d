#!/usr/bin/env bash
# Installs everything lightcone needs on Debian 12 (bookworm). Safe to run again.
#   ./setup.sh            the build and the tests
#   ./setup.sh --checks   also clang and its sanitizer and fuzzer runtimes (scripts/sanitize.sh,
#                         scripts/fuzz.sh)
#   ./setup.sh --web      also emscripten, chromium and, from npm, playwright-core (the web page,
#                         scripts/build-web.sh, and its tests: the README's test command)
set -euo pipefail
packages=(
  build-essential cmake ninja-build pkg-config git clang-format
  libembree-dev libtbb-dev nlohmann-json3-dev libtinyobjloader-dev libtinygltf-dev
  libstb-dev libspng-dev zlib1g-dev libturbojpeg0-dev libopenexr-dev libcli11-dev libfmt-dev libgtest-dev libgmock-dev libbenchmark-dev
  libboost-math-dev
  libgl-dev libegl-dev libegl-mesa0 libgl1-mesa-dri glslang-tools libglfw3-dev libimgui-dev
  xvfb xdotool x11-apps ffmpeg slurm-wlm munge
  kstars-data
  pybind11-dev python3-dev python3-numpy python3-pytest python3-venv python3-setuptools
)
if [ "${1:-}" = "--checks" ]; then packages+=(clang libclang-rt-14-dev); fi
if [ "${1:-}" = "--web" ]; then
  packages+=(emscripten chromium)
  command -v npm >/dev/null || packages+=(npm)
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  sudo_cmd=""
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  $sudo_cmd apt-get update
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y --no-install-recommends "${missing[@]}"
fi
if [ "${1:-}" = "--web" ]; then
  # The page's tests drive Debian's Chromium with playwright-core (no browser download).
  (cd "$(dirname "$0")/web/test" && npm ci --no-audit --no-fund --loglevel=error)
fi
