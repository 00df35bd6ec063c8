// A Web Worker with its own wasm instance: runs whole trials of a batch.
// Messages in:  { id, config, seed: string, indices: number[] }
// Messages out: { id, index, result: number[7] } per trial, then { id, done: true },
//               or { id, error: string }.
import init, { runTrial, lastPanic } from './pkg/torus_search.js';

const ready = init();

self.onmessage = async (e) => {
  const { id, config, seed, indices } = e.data;
  try {
    await ready;
    const s = BigInt(seed);
    for (const index of indices) {
      const result = Array.from(runTrial(config, s, index));
      self.postMessage({ id, index, result });
    }
    self.postMessage({ id, done: true });
  } catch (err) {
    let msg = err && err.message ? err.message : String(err);
    if (err instanceof WebAssembly.RuntimeError) {
      try {
        msg = `wasm panic: ${lastPanic() || msg}`;
      } catch {
        /* unusable after the trap */
      }
    }
    self.postMessage({ id, error: msg });
  }
};
