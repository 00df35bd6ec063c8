#!/usr/bin/env bash
# Build the WebAssembly package into www/pkg and vendor browser libraries into
# www/vendor (both are build outputs, ignored by git). Assumes scripts/setup.sh ran.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
cargo_bin="${CARGO_HOME:-$HOME/.cargo}/bin"
[[ -x "$cargo_bin/wasm-bindgen" && ":$PATH:" != *":$cargo_bin:"* ]] && export PATH="$cargo_bin:$PATH"

start=$SECONDS
cargo build --lib --release --target wasm32-unknown-unknown
wasm-bindgen --target web --out-dir www/pkg \
  "${CARGO_TARGET_DIR:-target}/wasm32-unknown-unknown/release/torus_search.wasm"

# Vendored browser libraries: copied from node_modules (pinned by package-lock.json),
# so the page loads them from its own origin and works offline.
mkdir -p www/vendor
vendor() { # vendor SRC DEST: copy only if changed
  if ! cmp -s "$1" "$2"; then cp "$1" "$2"; fi
}
vendor node_modules/uplot/dist/uPlot.esm.js  www/vendor/uPlot.esm.js
vendor node_modules/uplot/dist/uPlot.min.css www/vendor/uPlot.min.css
vendor node_modules/uplot/LICENSE            www/vendor/uPlot.LICENSE
# Observable Plot and d3 (the Experiments view's charts): their UMD builds,
# loaded as classic scripts (an import map would need an inline script, which
# the page's CSP refuses). Plot's UMD build is made against d3 7.9.0 (pinned).
vendor node_modules/d3/dist/d3.min.js                     www/vendor/d3.min.js
vendor node_modules/d3/LICENSE                            www/vendor/d3.LICENSE
vendor node_modules/@observablehq/plot/dist/plot.umd.min.js www/vendor/plot.umd.min.js
vendor node_modules/@observablehq/plot/LICENSE            www/vendor/plot.LICENSE

echo "[build] www/pkg: $(du -sh www/pkg/torus_search_bg.wasm | cut -f1) wasm; www/vendor: $(ls www/vendor | tr '\n' ' ')"
echo "[build] done in $((SECONDS - start)) s"
