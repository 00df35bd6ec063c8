#!/usr/bin/env node
// Cost per real move of every searcher, in wasm (Node.js) and natively
// (no timed assertions): the workload is `bench::move_cases` — every
// registered searcher and MCTS variant at its defaults, Gaussian prior with
// σ = N/8, at N = 40 and N = 256 — timed for about `--seconds` each after a
// warm-up move, each decision timed alone. Prints one JSON object and a
// table: mean ms per move, median and longest decision, episodes finished
// in the window (0: only trial 0's first moves), and wasm ÷ native.
// With --whole, every decision of trial 0 to its end (the first, which
// makes a planner's plan, included) instead of --seconds of moves.
// Usage: node benches/moves.mjs [--seconds S | --whole] [--no-native]
import { execFileSync } from 'node:child_process';
import path from 'node:path';
import { ROOT, loadPkg, secondsArg } from './wasm-pkg.mjs';

const args = process.argv.slice(2);
const seconds = secondsArg(args, 0.4);
const whole = args.includes('--whole');
const wasm = await loadPkg();

/**
 * Cost per move of `config` in wasm: one warm-up move, then single
 * decisions (calls that make one move) for `seconds`, each timed alone and
 * without setting up the next trial (`ready`), as the CLI does. Returns the
 * mean ms per move, the median and longest decision, and the episodes the
 * window finished (0: only trial 0's first moves). With --whole: every
 * decision of trial 0, and no warm-up move.
 */
function timeMoves(config) {
  const bench = new wasm.MoveBench(config);
  const m0 = whole ? 0 : bench.run(1);
  const e0 = bench.episodes();
  const each = [];
  let moves = m0;
  const t0 = performance.now();
  let t = t0;
  const more = () => (whole ? bench.episodes() === 0 : t - t0 < seconds * 1000 || moves - m0 < 3);
  while (more()) {
    bench.ready();
    const start = performance.now();
    moves = bench.run(1);
    t = performance.now();
    each.push(t - start);
  }
  const episodes = bench.episodes() - e0;
  bench.free();
  const total = each.reduce((a, b) => a + b, 0);
  each.sort((a, b) => a - b);
  return {
    wasm_ms_per_move: total / Math.max(1, moves - m0),
    wasm_median_ms: each[each.length >> 1],
    wasm_longest_ms: each[each.length - 1],
    wasm_moves: moves - m0,
    wasm_episodes: episodes,
  };
}

// V8 compiles wasm in tiers, and a function's first calls run before its
// optimised code is ready: without this pass the first case's longest
// decisions were 2-3 times its others. Two decisions of every case run
// every searcher's code; on a lattice of another size, so that the plans
// the belief MCTS keeps for the process are not the timed cases'.
for (const { config } of wasm.benchMoveCases(24)) {
  const bench = new wasm.MoveBench(config);
  bench.run(2);
  bench.free();
}
const rows = [];
for (const n of [40, 256]) {
  for (const { label, config } of wasm.benchMoveCases(n)) rows.push({ searcher: label, n, ...timeMoves(config) });
}
if (!args.includes('--no-native')) {
  execFileSync('cargo', ['build', '--release', '--quiet'], { cwd: ROOT, stdio: 'inherit' });
  const bin = path.join(ROOT, 'target/release/torus-search');
  const flags = ['bench', '--moves', '--json', '--scale', String(seconds / 0.4), ...(whole ? ['--whole'] : [])];
  const native = JSON.parse(execFileSync(bin, flags, { encoding: 'utf8' }));
  for (const r of rows) {
    const m = native.moves.find((x) => x.searcher === r.searcher && x.n === r.n);
    if (!m) continue;
    r.native_ms_per_move = m.ms_per_move;
    r.native_median_ms = m.median_ms;
    r.native_longest_ms = m.longest_ms;
    r.wasm_over_native_time = r.wasm_ms_per_move / m.ms_per_move;
  }
}
console.log(JSON.stringify({ node: process.version, seconds, whole_trial: whole, prior: 'gaussian, sigma = N/8', rows }, null, 1));
const pad = (s, w) => String(s).padStart(w);
const f = (v, d = 4) => (v === undefined ? '–' : v.toFixed(d));
console.error(
  `${'searcher'.padEnd(16)}${pad('N', 6)}${pad('wasm ms', 12)}${pad('median', 10)}${pad('longest', 10)}${pad('episodes', 10)}` +
    `${pad('native ms', 12)}${pad('median', 10)}${pad('longest', 10)}${pad('wasm/native', 13)}`,
);
for (const r of rows) {
  console.error(
    `${r.searcher.padEnd(16)}${pad(r.n, 6)}${pad(f(r.wasm_ms_per_move), 12)}${pad(f(r.wasm_median_ms), 10)}${pad(f(r.wasm_longest_ms, 3), 10)}${pad(r.wasm_episodes, 10)}` +
      `${pad(f(r.native_ms_per_move), 12)}${pad(f(r.native_median_ms), 10)}${pad(f(r.native_longest_ms, 3), 10)}${pad(f(r.wasm_over_native_time, 2), 13)}`,
  );
}
