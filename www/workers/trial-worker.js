// A Web Worker with its own wasm instance: runs batch trials and experiment
// units for www/workers/worker-pool.js. No game logic: each task is one facade call.
// Messages in:  { init: WebAssembly.Module }   (optional, first) the page's compiled engine
//               { id, seq, task }             task: { kind: 'trial', config, index }
//                                                  or { kind: 'paired', a, b, index } (two configs, one target)
//                                                  or { kind: 'experiment', spec, from, to }
// Messages out: { id, seq, result }  (a trial: number[7], a paired trial number[14]; experiment units: a
//               Float64Array of rows, its buffer transferred), or { id, seq, error: string }.
import { loadEngine, describeError } from '../shared/engine.js';

let ready = null;

function run(engine, task) {
  switch (task.kind) {
    case 'trial':
      return Array.from(engine.runTrial(task.config, task.index));
    case 'paired':
      return Array.from(engine.runPairedTrial(task.a, task.b, task.index));
    case 'experiment':
      return engine.experimentRun(task.spec, task.from, task.to);
    default:
      throw new Error(`unknown task kind ${JSON.stringify(task.kind)}`);
  }
}

self.onmessage = async (e) => {
  if (e.data.init) {
    ready ??= loadEngine(e.data.init);
    return;
  }
  const { id, seq, task } = e.data;
  try {
    ready ??= loadEngine();
    const result = run(await ready, task);
    self.postMessage({ id, seq, result }, ArrayBuffer.isView(result) ? [result.buffer] : []);
  } catch (err) {
    self.postMessage({ id, seq, error: describeError(err) });
  }
};
