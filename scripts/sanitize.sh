#!/usr/bin/env bash
# Builds lightcone and its tests with clang's AddressSanitizer and UndefinedBehaviorSanitizer
# (float-cast-overflow included; any finding stops the run) into build-sanitize/, runs the whole
# test suite, and renders every bundled scene at a small size.
set -euo pipefail
cd "$(dirname "$0")/.."
flags="-fsanitize=address,undefined,float-cast-overflow -fno-sanitize-recover=all -fno-omit-frame-pointer -g -O1"
CC=clang CXX=clang++ cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DLIGHTCONE_BENCH=OFF -DLIGHTCONE_PYTHON=OFF \
  -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" >/dev/null
cmake --build build-sanitize -j"$(nproc)"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# Mesa's drivers keep a few static allocations until they are unloaded at exit, when the leak
# checker would find them unreachable: loaded first, they are never unloaded (and are not
# instrumented, hence verify_asan_link_order=0).
preload=""
for lib in /usr/lib/x86_64-linux-gnu/libGLX_mesa.so.0 /usr/lib/x86_64-linux-gnu/libEGL_mesa.so.0 \
  /usr/lib/x86_64-linux-gnu/dri/swrast_dri.so; do
  [ -e "$lib" ] && preload="$preload $lib"
done
if [ -n "$preload" ]; then
  export LD_PRELOAD="${preload# }" ASAN_OPTIONS="$ASAN_OPTIONS:verify_asan_link_order=0"
fi
# The five slowest end-to-end comparisons (each over 100 s sanitized, the README's commands ten
# minutes) are left to the plain build: every path they take is also taken here by smaller tests
# and by the renders of every bundled scene below.
# The web page's tests judge the page (WebAssembly), not this build.
slow='^(WebPage\..*|Readme\.EveryCommandRunsAsWritten|RasterAgreement\.(TessellatedOnTheGpuTooTheyMatch|TexturesAndSkyImagesMatchTheRayTracer|RetardedShadowsMatchTheRayTracer)|RasterHoleBodies\.MatchTheRayTracerOffTheOutlines)$'
ctest --test-dir build-sanitize --output-on-failure -j"$(nproc)" -E "$slow"
out=$(mktemp -d)
for scene in scenes/*.json; do
  echo "sanitized render: $scene"
  ./build-sanitize/lightcone render "$scene" -o "$out/$(basename "$scene" .json).png" \
    --width 96 --height 54 --samples 1 --quiet
done
rm -rf "$out"
echo "sanitizers: every test and every bundled scene clean"
