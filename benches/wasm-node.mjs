#!/usr/bin/env node
// wasm vs native rollout throughput in Node.js (no timed assertions).
//
// Loads the same wasm package the page uses (www/pkg, `make build`), runs the
// RW / Lévy / NSARW rollout workloads of `torus-search bench` (N=40, r_v=1)
// in chunks (the first long call runs in V8's baseline tier, so the first
// chunks are a warm-up and are not counted), and prints one JSON object with
// wasm steps/s, native steps/s and their ratio.
// Usage: node benches/wasm-node.mjs [--seconds S] [--no-native]
import { execFileSync } from 'node:child_process';
import { existsSync, readFileSync } from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const ROOT = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const args = process.argv.slice(2);
const at = args.indexOf('--seconds');
const seconds = at >= 0 ? Number(args[at + 1]) : 3;
if (!(seconds > 0 && seconds <= 600)) {
  console.error(`error: --seconds must be a number in (0, 600], got ${args[at + 1]}`);
  process.exit(2);
}
const pkg = path.join(ROOT, 'www/pkg');
if (!existsSync(path.join(pkg, 'torus_search_bg.wasm'))) {
  console.error('error: www/pkg is missing; run `make build` first');
  process.exit(2);
}
const wasm = await import(path.join(pkg, 'torus_search.js'));
wasm.initSync({ module: readFileSync(path.join(pkg, 'torus_search_bg.wasm')) });

function rate(policy, chunk) {
  for (let i = 0; i < 5; i++) wasm.benchRolloutSteps(policy, 40, 1, 2, String(100 + i), chunk);
  let steps = 0;
  let seed = 1n;
  const t0 = performance.now();
  let t = t0;
  while (t - t0 < seconds * 1000) {
    steps += wasm.benchRolloutSteps(policy, 40, 1, 2, String(seed++), chunk);
    t = performance.now();
  }
  return steps / ((t - t0) / 1000);
}

const out = { node: process.version, seconds };
for (const [policy, chunk] of [['rw', 4e6], ['levy', 5e5], ['nsarw', 5e5]]) {
  out[`wasm_${policy}_steps_per_s`] = rate(policy, chunk);
}
if (!args.includes('--no-native')) {
  const bin = path.join(ROOT, 'target/release/torus-search');
  execFileSync('cargo', ['build', '--release', '--quiet'], { cwd: ROOT, stdio: 'inherit' });
  const native = JSON.parse(execFileSync(bin, ['bench', '--json', '--scale', '0.3'], { encoding: 'utf8' }));
  for (const policy of ['rw', 'levy', 'nsarw']) {
    const n = native[`${policy}_steps_per_s`];
    out[`native_${policy}_steps_per_s`] = n;
    out[`wasm_over_native_${policy}`] = out[`wasm_${policy}_steps_per_s`] / n;
  }
}
console.log(JSON.stringify(out, null, 1));
