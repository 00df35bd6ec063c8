// A Web Worker with its own wasm instance: runs whole trials of a batch.
// Messages in:  { id, config, indices: number[] } (config: the engine's, seed included)
// Messages out: { id, index, result: number[7] } per trial, then { id, done: true },
//               or { id, error: string }.
import { loadEngine, describeError } from './engine.js';

const ready = loadEngine();

self.onmessage = async (e) => {
  const { id, config, indices } = e.data;
  try {
    const engine = await ready;
    for (const index of indices) {
      self.postMessage({ id, index, result: Array.from(engine.runTrial(config, index)) });
    }
    self.postMessage({ id, done: true });
  } catch (err) {
    self.postMessage({ id, error: describeError(err) });
  }
};
