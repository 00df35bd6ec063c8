// Runs an experiment on a pool of Web Workers (www/workers/worker-pool.js), the
// same way the CLI does: the engine plans the units, the workers run
// deterministic chunks of units (experimentRun), the rows are put back in
// unit order, and the engine turns them into the result (experimentResult),
// byte for byte the CLI's <name>.json for the same spec. No DOM; nothing
// here computes a statistic.
//
// The engine numbers units trial-major (every run of consecutive units
// visits every point), so plain consecutive chunks fill every point in
// from the start: the live chart shows every point as its trials come in,
// and the ETA sees every series' cost early. Which unit is which point is
// the engine's business, not this file's.

import { WorkerPool } from '../workers/worker-pool.js';

/** Chunks per worker over a run: enough to balance uneven units, few enough to keep messages cheap. */
const CHUNKS_PER_WORKER = 512;

/**
 * The chunks of a run of `totalUnits` units: [{ from, to }] in the order
 * they are handed out, consecutive and covering every unit once. The split
 * depends only on its arguments.
 */
export function chunkPlan(totalUnits, workers) {
  if (!Number.isInteger(totalUnits) || totalUnits < 0) throw new Error(`${totalUnits} is not a number of units`);
  const c = Math.max(1, Math.floor(totalUnits / (workers * CHUNKS_PER_WORKER)));
  const out = [];
  for (let from = 0; from < totalUnits; from += c) out.push({ from, to: Math.min(totalUnits, from + c) });
  return out;
}

export class ExperimentRunner {
  /**
   * @param {object} engine  the page's wasm module (plans and results; it runs no unit)
   * @param {object} o
   * @param {number} o.workers  pool size
   * @param {WebAssembly.Module|null} o.module  the compiled engine for the workers
   */
  constructor(engine, { workers, module = null }) {
    this.engine = engine;
    this.workers = workers;
    this.module = module;
    this.pool = new WorkerPool(workers, module);
    this.active = null;
  }

  /** Replaces the pool with one of `k` workers (tests and benchmarks compare sizes). */
  usePool(k) {
    this.cancel();
    this.workers = k;
    this.pool = new WorkerPool(k, this.module);
  }

  /** Stops a run: its promise rejects with "stopped"; the next run starts on fresh workers. */
  cancel() {
    this.pool.terminate();
  }

  /**
   * The rows finished so far in the run under way, flattened (any subset
   * of rows is a valid experimentResult input: each row names its point
   * and trial), or null.
   */
  finishedRows() {
    const a = this.active;
    if (!a?.rows) return null;
    const out = new Float64Array(a.done * a.fields);
    let at = 0;
    for (const c of a.finished) {
      out.set(a.rows.subarray(c.from * a.fields, c.to * a.fields), at);
      at += (c.to - c.from) * a.fields;
    }
    return out;
  }

  /**
   * Runs `spec` to the end; onProgress({ done, total, seconds, eta }) after
   * every chunk. Resolves to { plan, text, seconds, workers }: `text` is
   * the engine's result JSON of every row in unit order. Rejects with the
   * engine's message, or "stopped" after cancel().
   */
  async run(spec, { onProgress = () => {} } = {}) {
    const plan = this.engine.experimentPlan(spec);
    const total = plan.totalUnits;
    const fields = plan.rowFields.length;
    const chunks = chunkPlan(total, this.workers);
    const rows = new Float64Array(total * fields);
    const a = { rows, fields, done: 0, finished: [] };
    this.active = a;
    const t0 = performance.now();
    const tasks = chunks.map((c) => ({ kind: 'experiment', spec, from: c.from, to: c.to }));
    try {
      await this.pool.runTasks(tasks, (seq, result) => {
        const c = chunks[seq];
        const n = c.to - c.from;
        if (result.length !== n * fields) throw new Error(`experimentRun gave ${result.length} numbers for ${n} units of ${fields}`);
        rows.set(result, c.from * fields);
        a.done += n;
        a.finished.push(c);
        const seconds = (performance.now() - t0) / 1000;
        onProgress({ done: a.done, total, seconds, eta: a.done < total ? (seconds / a.done) * (total - a.done) : 0 });
      });
    } finally {
      this.active = null;
    }
    const text = this.engine.experimentResult(spec, rows);
    return { plan, text, seconds: (performance.now() - t0) / 1000, workers: this.workers };
  }
}
