#!/usr/bin/env bash
# Serves the browser build (scripts/build-web.sh) at http://127.0.0.1:${PORT:-8000}/ : any static
# host does; the page needs no special headers (it runs on one thread).
set -euo pipefail
cd "$(dirname "$0")/../build-web"
exec python3 -m http.server "${PORT:-8000}" --bind 127.0.0.1
