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
import path from 'node:path';
import { ROOT, loadPkg, secondsArg } from './wasm-pkg.mjs';

const args = process.argv.slice(2);
const seconds = secondsArg(args, 3);
const wasm = await loadPkg();

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
