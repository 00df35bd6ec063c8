#!/usr/bin/env bash
# Print the wasm-bindgen version pinned in Cargo.toml (`wasm-bindgen = "=X"`).
# This is the ONE place the wasm-bindgen-cli version comes from: the CLI must
# match the library exactly, or wasm-bindgen refuses the .wasm file.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
v="$(sed -n -E 's/^[[:space:]]*wasm-bindgen[[:space:]]*=[[:space:]]*"=([0-9][^"]*)".*/\1/p' "$root/Cargo.toml" | head -n1)"
if [[ -z "$v" ]]; then
  echo 'error: Cargo.toml has no exact pin of the form: wasm-bindgen = "=X.Y.Z"' >&2
  exit 1
fi
echo "$v"
