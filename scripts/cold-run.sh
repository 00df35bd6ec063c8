#!/usr/bin/env bash
# Time `CI=true bash .ci/run` the way CI runs it: in a fresh clone of HEAD,
# with a fresh target/. With --cold-cargo, also with an empty CARGO_HOME, so
# the crates.io index, every crate download and the wasm-bindgen-cli compile
# are cold too (rustup's toolchain and apt's chromium are the machine's: the
# latter is timed only where it is missing). Writes the log, a time stamp on
# every line, to LOG (default: cold-run.log in the temporary directory), then
# prints the time of every step of `make test` (docs/testing.md). With --bare,
# also as if wasm-bindgen-cli were not installed: PATH's cargo bin directory
# is replaced by a copy of its links without wasm-bindgen*, so `make test`
# compiles the CLI as on a bare machine.
#
#   scripts/cold-run.sh [--cold-cargo | --bare] [LOG]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cold_cargo=0 bare=0
case "${1:-}" in
  --cold-cargo) cold_cargo=1; shift ;;
  --bare) cold_cargo=1; bare=1; shift ;;
esac
dir="$(mktemp -d)"
if [[ $bare == 1 ]]; then
  # Every PATH entry holding wasm-bindgen becomes a directory of links to
  # its other programs (rustup's cargo and rustc proxies among them).
  new_path=""
  IFS=: read -ra entries <<< "$PATH"
  for e in "${entries[@]}"; do
    if [[ -x "$e/wasm-bindgen" ]]; then
      shadow="$dir/path-$(( ${#new_path} ))"
      mkdir -p "$shadow"
      for f in "$e"/*; do [[ "$(basename "$f")" == wasm-bindgen* ]] || ln -s "$f" "$shadow/"; done
      e="$shadow"
    fi
    new_path="${new_path:+$new_path:}$e"
  done
  export PATH="$new_path"
  if command -v wasm-bindgen >/dev/null; then echo "error: wasm-bindgen still on PATH" >&2; exit 1; fi
fi
log="${1:-$dir/cold-run.log}"
git clone -q "$root" "$dir/p"
if [[ $cold_cargo == 1 ]]; then
  export CARGO_HOME="$dir/cargo"
  mkdir -p "$CARGO_HOME"
fi
echo "cold run of $(git -C "$dir/p" rev-parse --short HEAD) in $dir/p$([[ $cold_cargo == 1 ]] && echo ", CARGO_HOME=$CARGO_HOME")$([[ $bare == 1 ]] && echo ", no wasm-bindgen on PATH"); log: $log" >&2

start=$(date +%s)
set +e
(cd "$dir/p" && CI=true bash .ci/run < /dev/null 2>&1) |
  while IFS= read -r line; do printf '%s %s\n' "$(date +%s)" "$line"; done > "$log"
rc=${PIPESTATUS[0]}
set -e
total=$(($(date +%s) - start))

# A step runs from its "==== name ====" header to the next one; setup and
# build print their own parts ("[setup] ... in N s", "[build] done in N s").
awk -v total="$total" -v start="$start" '
  function flush(t) { if (name != "") printf "| %s | %d s |\n%s", name, t - since, parts; parts = "" }
  BEGIN { name = "setup (make setup-browser)"; since = start; print "| step | time |"; print "| --- | --- |" }
  / ==== .* ====$/ { flush($1); name = $0; sub(/^[0-9]+ ==== /, "", name); sub(/ ====$/, "", name); since = $1; next }
  / \[(setup|build)\] .* in [0-9]+ s/ { part = $0; sub(/^[0-9]+ /, "", part); parts = parts "| - " part " |  |\n" }
  { last = $1 }
  END { flush(last); printf "| **total** | **%d s (%d min %d s)** |\n", total, total / 60, total % 60 }
' "$log"
echo "exit code $rc; log: $log" >&2
if [[ $rc == 0 ]]; then rm -rf "$dir/p/target" "$dir/cargo"; fi
exit "$rc"
