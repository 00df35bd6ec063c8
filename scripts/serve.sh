#!/usr/bin/env bash
# Serve a directory (default: the repository root) on http://127.0.0.1:PORT/
# with Python's standard static server (serves .wasm as application/wasm),
# adding the headers of DIR/_headers if there is one (dist/ has: the CSP
# and nosniff a static host would send).
#   scripts/serve.sh [DIR]      PORT=8080 by default
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
dir="${1:-$root}"
port="${PORT:-8080}"
echo "Serving $dir at http://127.0.0.1:${port}/  (Ctrl-C to stop)"
exec python3 "$root/scripts/static_server.py" "$port" "$dir"
