// A pool of Web Workers (www/trial-worker.js), each with its own wasm
// instance, for batch trials and experiment units in the browser. Tasks
// are handed out one at a time, so fast and slow tasks balance across
// workers; results are keyed by task number, and a task's result depends
// only on the task, so the outcome is the same whatever the number of
// workers. Tasks (see trial-worker.js):
//   { kind: 'trial', config, index }          one batch trial → number[7]
//   { kind: 'experiment', spec, from, to }    experiment units from..to → Float64Array of rows

import { scriptURL } from './trusted.js';

export class WorkerPool {
  /**
   * @param {number} size   number of workers
   * @param {WebAssembly.Module|null} module  the page's compiled engine, handed to
   *        each worker so the wasm bytes are fetched and compiled once
   */
  constructor(size = Math.max(1, Math.min(8, (navigator.hardwareConcurrency || 2) - 1)), module = null) {
    this.size = size;
    this.module = module;
    this.workers = [];
    this.job = 0;
    this.reject = null;
  }

  spawn() {
    while (this.workers.length < this.size) {
      const w = new Worker(scriptURL(new URL('./trial-worker.js', import.meta.url)), { type: 'module' });
      if (this.module) w.postMessage({ init: this.module });
      this.workers.push(w);
    }
  }

  /** Stops every worker (a running job rejects with "stopped"); the next job starts fresh ones. */
  terminate() {
    this.discard();
    const reject = this.reject;
    this.reject = null;
    if (reject) reject(new Error('stopped'));
  }

  discard() {
    for (const w of this.workers) w.terminate();
    this.workers = [];
  }

  /**
   * Runs `tasks` on the workers. onResult(taskNumber, result, doneCount) is
   * called as tasks finish. Resolves to the results in task order; rejects
   * with the first task's error, or "stopped" after terminate().
   */
  runTasks(tasks, onResult = () => {}) {
    this.spawn();
    const id = ++this.job;
    const results = new Array(tasks.length);
    let next = 0;
    let done = 0;
    return new Promise((resolve, reject) => {
      if (!tasks.length) {
        resolve(results);
        return;
      }
      const finish = (fn, value) => {
        if (this.job !== id) return;
        this.job++; // later messages of this job are ignored
        this.reject = null;
        fn(value);
      };
      this.reject = reject;
      const feed = (w) => {
        if (next < tasks.length) {
          const seq = next++;
          w.postMessage({ id, seq, task: tasks[seq] });
        }
      };
      for (const w of this.workers) {
        w.onmessage = (e) => {
          const m = e.data;
          if (m.id !== id || this.job !== id) return;
          if (m.error !== undefined) {
            // A failed task may have left its engine trapped: start the next job on fresh workers.
            this.discard();
            finish(reject, new Error(m.error));
            return;
          }
          results[m.seq] = m.result;
          done++;
          feed(w);
          try {
            onResult(m.seq, m.result, done);
          } catch (err) {
            this.discard();
            finish(reject, err);
            return;
          }
          if (done === tasks.length) finish(resolve, results);
        };
        w.onerror = (e) => {
          e.preventDefault();
          this.discard();
          finish(reject, new Error(e.message || 'a worker failed to start'));
        };
        feed(w);
      }
    });
  }

  /**
   * Runs trials 0..trials-1 of `config` (the engine's config, seed included).
   * onResult(index, result, doneCount) is called as trials finish.
   * Resolves to the results in trial order (arrays of 7 numbers, see runTrial).
   */
  run(config, trials, onResult = () => {}) {
    const tasks = Array.from({ length: trials }, (_, index) => ({ kind: 'trial', config, index }));
    return this.runTasks(tasks, onResult);
  }
}
