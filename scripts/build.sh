#!/usr/bin/env bash
# Configures lightcone (Release) in build/ and builds the `lightcone` program, or the targets
# given (scripts/test.sh builds everything: `./scripts/build.sh all`).
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)" --target "${@:-lightcone}"
