#!/usr/bin/env node
// Cost per real move of every searcher, in wasm (Node.js) and natively
// (no timed assertions): the workload is `bench::move_cases` — every
// registered searcher and MCTS variant at its defaults, Gaussian prior with
// σ = N/8, at N = 40 and N = 256 — timed for about `--seconds` each after a
// warm-up move. Prints one JSON object and a table with wasm ÷ native.
// Usage: node benches/moves.mjs [--seconds S] [--no-native]
import { execFileSync } from 'node:child_process';
import path from 'node:path';
import { ROOT, loadPkg, secondsArg } from './wasm-pkg.mjs';

const args = process.argv.slice(2);
const seconds = secondsArg(args, 0.4);
const wasm = await loadPkg();

/** ms per move of `config` in wasm: one warm-up move, then single moves for `seconds` (as the CLI does). */
function msPerMove(config) {
  const bench = new wasm.MoveBench(config);
  const m0 = bench.run(1);
  let moves = m0;
  const t0 = performance.now();
  let t = t0;
  while (t - t0 < seconds * 1000 || moves - m0 < 3) {
    moves = bench.run(1);
    t = performance.now();
  }
  bench.free();
  return (t - t0) / (moves - m0);
}

const rows = [];
for (const n of [40, 256]) {
  for (const { label, config } of wasm.benchMoveCases(n)) rows.push({ searcher: label, n, wasm_ms_per_move: msPerMove(config) });
}
if (!args.includes('--no-native')) {
  execFileSync('cargo', ['build', '--release', '--quiet'], { cwd: ROOT, stdio: 'inherit' });
  const bin = path.join(ROOT, 'target/release/torus-search');
  const native = JSON.parse(execFileSync(bin, ['bench', '--moves', '--json', '--scale', String(seconds / 0.4)], { encoding: 'utf8' }));
  for (const r of rows) {
    const m = native.moves.find((x) => x.searcher === r.searcher && x.n === r.n);
    if (!m) continue;
    r.native_ms_per_move = m.ms_per_move;
    r.wasm_over_native_time = r.wasm_ms_per_move / m.ms_per_move;
  }
}
console.log(JSON.stringify({ node: process.version, seconds, prior: 'gaussian, sigma = N/8', rows }, null, 1));
const pad = (s, w) => String(s).padStart(w);
console.error(`${'searcher'.padEnd(16)}${pad('N', 6)}${pad('wasm ms', 12)}${pad('native ms', 12)}${pad('wasm/native', 13)}`);
for (const r of rows) {
  const f = (v, d = 4) => (v === undefined ? '–' : v.toFixed(d));
  console.error(`${r.searcher.padEnd(16)}${pad(r.n, 6)}${pad(f(r.wasm_ms_per_move), 12)}${pad(f(r.native_ms_per_move), 12)}${pad(f(r.wasm_over_native_time, 2), 13)}`);
}
