#!/usr/bin/env node
// Instructions per MCTS loop, wasm (V8's optimising tier) vs native, counted
// by valgrind's callgrind: unlike seconds, the counts do not depend on what
// else the machine is doing (native ones repeat exactly, wasm ones within
// about 0.2%), so a change to the hot loop can be judged in one run on a
// noisy 2-core VM. No timed assertions.
//
// Each side runs loops 0..A and 0..B of the same episode (config, seed) and
// the difference is divided by B − A, so start-up and compilation cancel.
// wasm runs in Node.js with --no-liftoff (every function compiled by
// TurboFan, the tier the page's long-running search ends up in).
// Prints one JSON object. Needs `make build` (www/pkg), `cargo build
// --release` (in $CARGO_TARGET_DIR when set, like cargo) and valgrind
// (`apt-get install -y valgrind`).
// Usage: node benches/instructions.mjs [--config FILE.json] [--seed S] [--loops A..B]
import { execFileSync, spawnSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const ROOT = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const SELF = fileURLToPath(import.meta.url);
const PKG = path.join(ROOT, 'www/pkg');
const BIN = path.join(process.env.CARGO_TARGET_DIR ? path.resolve(process.env.CARGO_TARGET_DIR) : path.join(ROOT, 'target'), 'release/torus-search');
/** The default workload: a long N=100 episode, as in the browser benchmark. */
const DEFAULT_CONFIG = { n: 100, sigma: 15, loops: 100, belief: 'posterior' };

function fail(msg) {
  console.error(`error: ${msg}`);
  process.exit(2);
}

const args = process.argv.slice(2);

if (args[0] === '--child') {
  // Runs inside valgrind: `loops` loops of the episode in one wasm call.
  const [, configJson, loops] = args;
  const wasm = await import(path.join(PKG, 'torus_search.js'));
  wasm.initSync({ module: readFileSync(path.join(PKG, 'torus_search_bg.wasm')) });
  wasm.benchMctsLoops(JSON.parse(configJson), Number(loops));
  process.exit(0);
}

function option(name) {
  const at = args.indexOf(name);
  if (at < 0) return null;
  if (at + 1 >= args.length) fail(`${name} needs a value`);
  return args[at + 1];
}
for (let i = 0; i < args.length; i += 2) {
  if (!['--config', '--seed', '--loops'].includes(args[i])) {
    fail(`unknown argument ${JSON.stringify(args[i])} (usage: [--config FILE.json] [--seed S] [--loops A..B])`);
  }
}

let config = DEFAULT_CONFIG;
const configFile = option('--config');
if (configFile !== null) {
  try {
    config = JSON.parse(readFileSync(configFile, 'utf8'));
  } catch (err) {
    fail(`--config ${configFile}: ${err.message}`);
  }
}
// The seed goes into the config; the native check below reads it (and
// names it if it is out of range).
const seedText = option('--seed') ?? String(config.seed ?? '1');
config = { ...config, seed: seedText };
const loopsText = option('--loops') ?? '2000..6000';
const m = /^(\d{1,9})\.\.(\d{1,9})$/.exec(loopsText);
const [a, b] = m ? [Number(m[1]), Number(m[2])] : [NaN, NaN];
if (!(a >= 0 && b > a && b <= 1e7)) {
  fail(`--loops must be A..B with 0 <= A < B <= 10000000, got ${JSON.stringify(loopsText)}`);
}
if (!existsSync(path.join(PKG, 'torus_search_bg.wasm'))) fail('www/pkg is missing; run `make build` first');
if (!existsSync(BIN)) fail(`${BIN} is missing; run \`cargo build --release\` first`);
if (spawnSync('valgrind', ['--version']).status !== 0) fail('valgrind is missing; run `apt-get install -y valgrind`');

// The native CLI checks the config and names a bad field; do that first so
// a bad config fails in a second, not after a minute under valgrind.
const dir = mkdtempSync(path.join(tmpdir(), 'torus-instr-'));
const file = path.join(dir, 'config.json');
writeFileSync(file, JSON.stringify(config));
const nativeArgs = (loops) => ['bench', '--json', '--episode', file, '--loops', `0..${loops}`];
try {
  execFileSync(BIN, nativeArgs(1), { stdio: ['ignore', 'ignore', 'pipe'], encoding: 'utf8' });
} catch (err) {
  fail(`the config was refused: ${String(err.stderr || err.message).trim()}`);
}

/** Instructions callgrind counted for one command (the whole process). */
function instructions(cmd, cmdArgs) {
  const r = spawnSync('valgrind', ['--tool=callgrind', '--callgrind-out-file=/dev/null', cmd, ...cmdArgs], {
    encoding: 'utf8',
    maxBuffer: 64 << 20,
  });
  const hit = /Collected : (\d+)/.exec(r.stderr);
  if (r.status !== 0 || !hit) fail(`valgrind ${cmd} failed:\n${r.stderr.slice(-2000)}`);
  return Number(hit[1]);
}

const wasmArgs = (loops) => ['--no-liftoff', SELF, '--child', JSON.stringify(config), String(loops)];
const perLoop = (run) => (run(b) - run(a)) / (b - a);
const wasm = perLoop((loops) => instructions(process.execPath, wasmArgs(loops)));
const native = perLoop((loops) => instructions(BIN, nativeArgs(loops)));
console.log(
  JSON.stringify(
    {
      config,
      seed: seedText,
      loops: [a, b],
      wasm_instructions_per_loop: Math.round(wasm),
      native_instructions_per_loop: Math.round(native),
      native_over_wasm: +(native / wasm).toFixed(3),
    },
    null,
    2,
  ),
);
