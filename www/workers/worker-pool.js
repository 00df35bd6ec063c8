// A pool of Web Workers (www/workers/trial-worker.js), each with its own wasm
// instance, for batch trials and experiment units in the browser. Tasks
// are handed out one at a time, so fast and slow tasks balance across
// workers; results are keyed by task number, and a task's result depends
// only on the task, so the outcome is the same whatever the number of
// workers. Tasks (see trial-worker.js):
//   { kind: 'trial', config, index }          one batch trial → number[7]
//   { kind: 'experiment', spec, from, to }    experiment units from..to → Float64Array of rows

import { scriptURL } from '../shared/trusted.js';

/** How many times a task is retried on a fresh worker after its worker died. */
export const MAX_RETRIES = 2;

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
    /** Workers replaced after they died, over the pool's life (tests read it). */
    this.replaced = 0;
  }

  fresh() {
    const w = new Worker(scriptURL(new URL('./trial-worker.js', import.meta.url)), { type: 'module' });
    if (this.module) w.postMessage({ init: this.module });
    return w;
  }

  spawn() {
    while (this.workers.length < this.size) this.workers.push(this.fresh());
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
   * Fault injection for tests: worker `i` dies mid-task as a crashed worker
   * does (terminated, then its error event), and the pool must recover.
   */
  killWorker(i) {
    const w = this.workers[i];
    if (!w) return false;
    w.terminate();
    w.dispatchEvent(new ErrorEvent('error', { message: 'worker killed (fault injection)' }));
    return true;
  }

  /**
   * Runs `tasks` on the workers. onResult(taskNumber, result, doneCount) is
   * called as tasks finish. Resolves to the results in task order; rejects
   * with the first task's error, or "stopped" after terminate().
   *
   * A worker that dies (its error event: a crash, a failed start, the
   * browser killing it) is replaced by a fresh one, which re-runs the task
   * the dead one held; a task's result depends only on the task, so the
   * outcome is unchanged. A task whose worker dies more than MAX_RETRIES
   * times fails the job. A task that reports an error (a bad config, a wasm
   * panic) fails the job at once: re-running it would fail the same way.
   */
  runTasks(tasks, onResult = () => {}) {
    this.spawn();
    const id = ++this.job;
    const results = new Array(tasks.length);
    const retries = new Map(); // task number -> times its worker died
    const queue = []; // task numbers to run again, before new ones
    const held = new Map(); // worker -> the task number it runs
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
        const seq = queue.length ? queue.shift() : next < tasks.length ? next++ : -1;
        if (seq < 0) return;
        held.set(w, seq);
        w.postMessage({ id, seq, task: tasks[seq] });
      };
      const lost = (w, why) => {
        if (this.job !== id) return;
        const at = this.workers.indexOf(w);
        if (at < 0) return;
        w.terminate();
        const seq = held.get(w);
        held.delete(w);
        if (seq !== undefined) {
          const n = (retries.get(seq) ?? 0) + 1;
          retries.set(seq, n);
          if (n > MAX_RETRIES) {
            this.discard();
            finish(reject, new Error(`task ${seq} lost its worker ${n} times (${why}); giving up`));
            return;
          }
          queue.push(seq);
        }
        this.replaced++;
        const fresh = this.fresh();
        this.workers[at] = fresh;
        attach(fresh);
        feed(fresh);
      };
      const attach = (w) => {
        w.onmessage = (e) => {
          const m = e.data;
          // A replaced worker's last words are not this job's.
          if (m.id !== id || this.job !== id || !this.workers.includes(w)) return;
          if (m.error !== undefined) {
            // A failed task may have left its engine trapped: start the next job on fresh workers.
            this.discard();
            finish(reject, new Error(m.error));
            return;
          }
          held.delete(w);
          if (results[m.seq] !== undefined) {
            feed(w);
            return;
          }
          done++;
          results[m.seq] = m.result;
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
          e.preventDefault?.();
          lost(w, e.message || 'a worker failed');
        };
      };
      for (const w of this.workers) {
        attach(w);
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

  /** As run(), each trial of config `a` and of config `b` on the same target (runPairedTrial: 14 numbers). */
  runPaired(a, b, trials, onResult = () => {}) {
    const tasks = Array.from({ length: trials }, (_, index) => ({ kind: 'paired', a, b, index }));
    return this.runTasks(tasks, onResult);
  }
}
