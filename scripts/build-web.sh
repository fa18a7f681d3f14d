#!/usr/bin/env bash
# Builds the browser build (web/: WebAssembly and WebGL 2, from the same C++) into build-web/:
# lightcone.js, lightcone.wasm and lightcone.data (the bundled scenes and their assets), and the
# page around them. It takes the emitter nodes the native build fits and the star catalogue it
# converts (scripts/build.sh). Needs Debian's emscripten (setup.sh --web installs it).
set -euo pipefail
cd "$(dirname "$0")/.."
[ -f build/generated/rgb_emitter_nodes.cpp ] && [ -f build/data/stars-bright.lcstars ] ||
  ./scripts/build.sh
# Debian's emscripten runs its JavaScript optimiser with Node.js modules from Debian's folder.
export NODE_PATH=/usr/share/nodejs
emcmake cmake -S web -B build-web -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build-web -j"$(nproc)"
echo "build-web/: $(du -ch build-web/lightcone.{js,wasm,data} | tail -1 | cut -f1) in all"
