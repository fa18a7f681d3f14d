#!/usr/bin/env bash
# Builds lightcone, its tests and benchmarks, and the web page, and runs every test (the page's
# in headless Chromium: setup.sh --web installs what they need).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/build.sh all
./scripts/build-web.sh
ctest --test-dir build --output-on-failure -j"$(nproc)"
