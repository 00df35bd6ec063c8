#!/usr/bin/env node
// The cost of an experiment point's statistics in wasm (Node.js), which the
// page pays each time it draws a result (no timed assertions; `make bench`
// runs it). A point of T trials (a random walk on an 8-torus) is summarised
// by experimentResult: its mean and excess intervals (two bootstraps of
// 2000 resamples), its median's interval, the JSON. Prints one JSON object
// with milliseconds per point; `cargo bench -- intervals` gives the native
// cost of one interval.
// Usage: node benches/intervals.mjs [--seconds S]
import { loadPkg, secondsArg } from './wasm-pkg.mjs';

const seconds = secondsArg(process.argv.slice(2), 2);
const wasm = await loadPkg();
const out = { node: process.version };
for (const trials of [100, 1000, 10000]) {
  const spec = { name: 'custom', trials, seed: '3', preset: null, params: { n: '8', searcher: 'rw', step_cap: '2000' } };
  const rows = wasm.experimentRun(spec, 0, trials);
  for (let i = 0; i < 3; i++) wasm.experimentResult(spec, rows);
  let k = 0;
  const t0 = performance.now();
  let t = t0;
  while (t - t0 < seconds * 1000) {
    wasm.experimentResult(spec, rows);
    k++;
    t = performance.now();
  }
  out[`point_of_${trials}_trials_ms`] = (t - t0) / k;
}
console.log(JSON.stringify(out));
