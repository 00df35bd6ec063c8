// The batch panel: many trials of the current configuration in a pool of
// Web Workers, summarised by the engine (the same statistics as the CLI's
// --json). Trial i depends only on (config, i), so any number of workers
// gives the same results. In a race, both sides run on the same targets
// and the engine summarises the pairs: the paired difference with its
// interval and the wins.

import { $, setText, fmtInt, showMessage } from '../shared/ui.js';
import { WorkerPool } from './worker-pool.js';
import { engineModule } from '../shared/engine.js';

export class BatchPanel {
  /**
   * @param {object} engine the page's wasm module
   * @param {object} schema the engine's schema (limits of trials and step_cap)
   * @param {() => object} config the current engine config
   * @param {() => object|null} opponent the race opponent's config, or null
   */
  constructor(engine, schema, config, opponent = () => null) {
    this.engine = engine;
    this.config = config;
    this.opponent = opponent;
    this.paired = null;
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

  /** A config as the batch runs it: its step cap, no traces kept. */
  batchConfig(config) {
    return this.engine.setParam(this.engine.setParam(config, 'step_cap', $('batch-cap').value), 'keep_traces', '0');
  }

  async run() {
    let trials;
    let cfg;
    let opp = null;
    try {
      trials = this.engine.parseTrials($('batch-trials').value);
      cfg = this.batchConfig(this.config());
      const o = this.opponent();
      if (o) opp = this.batchConfig(o);
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
    $('batch-paired').hidden = true;
    const progress = $('batch-progress');
    const t0 = performance.now();
    setText(progress, `Running ${trials} trials on ${workers}…`);
    document.body.dataset.batch = 'running';
    try {
      const tick = (_, __, done) => setText(progress, `${done} / ${trials} ${opp ? 'paired ' : ''}trials (${workers}, ${((performance.now() - t0) / 1000).toFixed(1)} s)`);
      const results = opp ? await pool.runPaired(cfg, opp, trials, tick) : await pool.run(cfg, trials, tick);
      const secs = (performance.now() - t0) / 1000;
      this.results = results;
      if (opp) {
        // Side A's trials alone, then the pairs.
        this.show(this.engine.summarizeTrials(Float64Array.from(results.flatMap((r) => r.slice(0, r.length / 2)))), secs);
        this.paired = this.engine.summarizePaired(Float64Array.from(results.flat()));
        this.showPaired(this.paired);
      } else {
        this.paired = null;
        this.show(this.engine.summarizeTrials(Float64Array.from(results.flat())), secs);
      }
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

  /** The engine's paired summary of A against B as a table. */
  showPaired(p) {
    const num = (v, d = 1) => (Number.isFinite(v) ? v.toFixed(d) : '—');
    const d = p.difference;
    const rows = [
      ['Pairs (same target)', String(p.trials)],
      ['Mean steps A / B', `${num(p.mean_a)} / ${num(p.mean_b)}`],
      [`Mean difference A − B [${Math.round(100 * d.level)}% interval, ${d.method}]`, `${num(d.estimate)} [${num(d.lo)}, ${num(d.hi)}]`],
      ['SD of the differences', num(p.sd_difference)],
      ['A faster / tie / B faster', `${p.a_wins} / ${p.ties} / ${p.b_wins}`],
      ['Found A / B', `${p.found_a} / ${p.found_b}`],
    ];
    const body = $('batch-paired').querySelector('table').tBodies[0];
    body.replaceChildren();
    for (const [k, v] of rows) {
      const tr = body.insertRow();
      tr.insertCell().textContent = k;
      tr.insertCell().textContent = v;
    }
    const verdict = !Number.isFinite(d.lo) || !Number.isFinite(d.hi) ? 'too few pairs for an interval'
      : d.hi < 0 ? 'A takes fewer steps: the interval lies below 0'
      : d.lo > 0 ? 'B takes fewer steps: the interval lies above 0' : 'no clear difference: the interval holds 0';
    setText('batch-paired-note', `Race: A against B on the same ${p.trials} targets: ${verdict}.`);
    $('batch-paired').hidden = false;
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
