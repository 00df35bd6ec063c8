// A pool of Web Workers (www/trial-worker.js), each with its own wasm
// instance, for batch trials in the browser. Trials are handed out one at a
// time, so fast and slow trials balance across workers; results are keyed
// by trial index, and trial i depends only on (config, seed, i), so the
// batch is the same whatever the number of workers.

export class WorkerPool {
  constructor(size = Math.max(1, Math.min(8, (navigator.hardwareConcurrency || 2) - 1))) {
    this.size = size;
    this.workers = [];
    this.job = 0;
  }

  spawn() {
    while (this.workers.length < this.size) {
      this.workers.push(new Worker(new URL('./trial-worker.js', import.meta.url), { type: 'module' }));
    }
  }

  /** Stops every worker (a running batch rejects with "stopped"). */
  terminate() {
    for (const w of this.workers) w.terminate();
    this.workers = [];
    if (this.reject) this.reject(new Error('stopped'));
    this.reject = null;
  }

  /**
   * Runs trials 0..trials-1 of `config` (the engine's config, seed included).
   * onResult(index, result, doneCount) is called as trials finish.
   * Resolves to the results in trial order (arrays of 7 numbers, see runTrial).
   */
  run(config, trials, onResult = () => {}) {
    this.spawn();
    const id = ++this.job;
    const results = new Array(trials);
    let next = 0;
    let done = 0;
    return new Promise((resolve, reject) => {
      this.reject = reject;
      const feed = (w) => {
        if (next < trials) w.postMessage({ id, config, indices: [next++] });
      };
      for (const w of this.workers) {
        w.onmessage = (e) => {
          const m = e.data;
          if (m.id !== id) return;
          if (m.error) {
            this.reject = null;
            reject(new Error(m.error));
            return;
          }
          if (m.done) {
            feed(w);
            return;
          }
          results[m.index] = m.result;
          done++;
          onResult(m.index, m.result, done);
          if (done === trials) {
            this.reject = null;
            resolve(results);
          }
        };
        w.onerror = (e) => {
          this.reject = null;
          reject(new Error(e.message || 'worker failed to start'));
        };
        feed(w);
      }
    });
  }
}
