// The batch panel: many trials of the current configuration in a pool of
// Web Workers, summarised by the engine (the same statistics as the CLI's
// --json). Trial i depends only on (config, i), so any number of workers
// gives the same results.

import { $, setText, fmtInt, showMessage } from '../shared/ui.js';
import { WorkerPool } from './worker-pool.js';
import { engineModule } from '../shared/engine.js';

export class BatchPanel {
  /**
   * @param {object} engine the page's wasm module
   * @param {object} schema the engine's schema (limits of trials and step_cap)
   * @param {() => object} config the current engine config
   */
  constructor(engine, schema, config) {
    this.engine = engine;
    this.config = config;
    this.pool = null;
    this.results = null;
    const cap = schema.params.find((p) => p.key === 'step_cap');
    Object.assign($('batch-trials'), { min: schema.trials.min, max: schema.trials.max });
    Object.assign($('batch-cap'), { min: cap.min, max: cap.max });
    $('batch-run').addEventListener('click', () => this.run());
    $('batch-stop').addEventListener('click', () => this.pool?.terminate());
  }

  /** Replaces the pool with one of `size` workers (tests compare worker counts). */
  usePool(size) {
    this.pool?.terminate();
    this.pool = new WorkerPool(size, engineModule());
  }

  async run() {
    let trials;
    let cfg;
    try {
      trials = this.engine.parseTrials($('batch-trials').value);
      cfg = this.engine.setParam(this.config(), 'step_cap', $('batch-cap').value);
      cfg = this.engine.setParam(cfg, 'keep_traces', '0');
    } catch (err) {
      showMessage(`Batch: ${err.message}`);
      return;
    }
    this.pool ??= new WorkerPool(undefined, engineModule());
    const pool = this.pool;
    const workers = `${pool.size} worker${pool.size > 1 ? 's' : ''}`;
    $('batch-run').disabled = true;
    $('batch-stop').disabled = false;
    $('batch-summary').hidden = true;
    const progress = $('batch-progress');
    const t0 = performance.now();
    setText(progress, `Running ${trials} trials on ${workers}…`);
    document.body.dataset.batch = 'running';
    try {
      const results = await pool.run(cfg, trials, (_, __, done) => {
        setText(progress, `${done} / ${trials} trials (${workers}, ${((performance.now() - t0) / 1000).toFixed(1)} s)`);
      });
      const secs = (performance.now() - t0) / 1000;
      this.results = results;
      this.show(this.engine.summarizeTrials(Float64Array.from(results.flat())), secs);
      setText(progress, `${trials} trials in ${secs.toFixed(2)} s on ${workers} (${(trials / secs).toFixed(1)} trials/s).`);
      document.body.dataset.batch = 'done';
    } catch (err) {
      const stopped = err.message === 'stopped';
      setText(progress, stopped ? 'Stopped.' : `Batch failed: ${err.message}`);
      document.body.dataset.batch = stopped ? 'stopped' : 'error';
    } finally {
      $('batch-run').disabled = false;
      $('batch-stop').disabled = true;
    }
  }

  /** The engine's summary (CLI --json field names) as a table. */
  show(s, secs) {
    // An interval {estimate, lo, hi}; an end the engine could not compute (too few trials) is null.
    const num = (v, d) => (Number.isFinite(v) ? v.toFixed(d) : '—');
    const ci = (i, d = 1) => `${num(i.estimate, d)} [${num(i.lo, d)}, ${num(i.hi, d)}]`;
    const rows = [
      ['Trials', String(s.trials)],
      ['Mean steps [95% interval]', ci(s.mean_steps)],
      ['Mean optimal', num(s.mean_optimal.estimate, 1)],
      ['ASOO = mean(steps − optimal)', ci(s.asoo)],
      ['Mean steps/optimal', Number.isFinite(s.mean_ratio.estimate) ? ci(s.mean_ratio, 2) : '—'],
      ['Mean steps / mean optimal', s.steps_over_mean_optimal.toFixed(2)],
      ['Median steps [95% interval] (q1–q3)', `${ci(s.median_steps)} (${s.q1_steps}–${s.q3_steps})`],
      ['Capped (not found)', String(s.capped)],
      ['Optimal = 0 (excluded from ratio)', String(s.zero_optimal)],
      ['Truncated rollouts', fmtInt(s.truncated_rollouts)],
      ['Seconds', secs.toFixed(2)],
    ];
    const body = $('batch-summary').tBodies[0];
    body.replaceChildren();
    for (const [k, v] of rows) {
      const tr = body.insertRow();
      tr.insertCell().textContent = k;
      tr.insertCell().textContent = v;
    }
    $('batch-summary').hidden = false;
  }
}
