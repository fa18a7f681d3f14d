#!/usr/bin/env bash
# Builds lightcone, its tests and benchmarks, and runs every test.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/build.sh all
ctest --test-dir build --output-on-failure -j"$(nproc)"
