// The Experiments view: pick a named experiment (the engine's
// experimentList()) or build a custom sweep, run it on a pool of Web
// Workers (www/experiments/runner.js), watch its charts fill in
// (www/experiments/charts.js), download CSV (per point, per trial, paired
// comparisons) / JSON / SVG / PNG, load a
// results file, and open a point in the live view. Choices and limits come
// from the engine's schema and experiment list; every value is checked by
// the engine (through url-state.js's experiment reader, the same as a
// URL's); every statistic shown is the engine's.

import { $, setText, showMessage, download, fillSelect } from '../shared/ui.js';
import { CUSTOM, experimentSpec, formatPairs, formatSeries, parsePairs, parseSeries, presetChoices, readExperimentUrl, writeExperimentUrl } from '../shared/url-state.js';
import { ExperimentRunner } from './runner.js';
import { MODE_LABELS, chartModes, drawExperiment, pointSummary, standaloneSvg, svgToPng, xName } from './charts.js';

/** Least time between live chart redraws while a run goes on (ms). */
const LIVE_MS = 1000;
/** Most of the page's thread the live statistics may take during a run. */
const LIVE_SHARE = 0.05;
/** Larger results files are refused before they are read. */
export const MAX_RESULT_BYTES = 256 << 20;

/** 83 s → "1 min 23 s". */
export function fmtDuration(s) {
  if (!Number.isFinite(s)) return '—';
  if (s < 60) return `${s.toFixed(s < 10 ? 1 : 0)} s`;
  const m = Math.floor(s / 60);
  if (m < 60) return `${m} min ${Math.round(s - 60 * m)} s`;
  return `${Math.floor(m / 60)} h ${m % 60} min`;
}

/** A statistic for the table: integers as they are, others rounded; none (null: no data) as —. */
function num(v, digits = 1) {
  if (v === null || v === undefined) return '—';
  return Number.isInteger(v) ? String(v) : v.toFixed(digits);
}

/** An interval {estimate, lo, hi} as "estimate [lo, hi]" (an end the engine could not compute as —). */
function interval(i, digits = 1) {
  return `${num(i?.estimate, digits)} [${num(i?.lo, digits)}, ${num(i?.hi, digits)}]`;
}

/** The downloads: button id → [kind, file suffix]. */
const DOWNLOADS = {
  'exp-csv': ['csv', '.csv'],
  'exp-trials-csv': ['trials-csv', '.trials.csv'],
  'exp-paired-csv': ['paired-csv', '.paired.csv'],
  'exp-json': ['json', '.json'],
  'exp-svg': ['svg', '.svg'],
  'exp-png': ['png', '.png'],
};

export class ExperimentsView {
  /**
   * @param {object} o
   * @param {object} o.engine        the page's wasm module
   * @param {object} o.schema        the engine's schema
   * @param {object} o.state         the initial state (url-state.js readExperimentUrl)
   * @param {WebAssembly.Module} o.module  the compiled engine, for the workers
   * @param {(query) => void} o.onUrl      the experiment's query changed
   * @param {(config, note) => void} o.onOpen  open a config in the live view
   */
  constructor({ engine, schema, state, module, onUrl, onOpen }) {
    this.engine = engine;
    this.schema = schema;
    this.list = engine.experimentList();
    this.presets = presetChoices(engine, schema, this.list);
    this.state = state;
    this.onUrl = onUrl;
    this.onOpen = onOpen;
    this.runner = new ExperimentRunner(engine, { workers: Math.max(1, navigator.hardwareConcurrency || 2), module });
    this.result = null; // { text, data, source }
    this.shown = null; // the result drawn (possibly partial)
    this.fig = null;
    this.mode = null;
    this.live = null; // the run under way: { spec, plan, lastDraw, gap, drawn }
    this.lastRun = null;
    this.drawing = Promise.resolve();

    fillSelect($('exp-name'), this.list.map((e) => [e.name, `${e.name}: ${e.title}`]));
    fillSelect($('exp-preset'), this.presets.map((p) => [p, p === 'none' ? 'none (the experiment\'s parameters as given)' : p]));
    // Any parameter but the seed (the spec's own field) can be swept.
    fillSelect($('exp-sweep-key'), schema.params.filter((p) => p.key !== 'seed').map((p) => [p.key, `${p.key}: ${p.help}`]));
    Object.assign($('exp-trials'), { min: schema.trials.min, max: schema.trials.max, title: `trials per point: ${schema.trials.allowed}` });
    $('exp-seed').title = `seed: ${schema.params.find((p) => p.key === 'seed').allowed}`;
    for (const id of ['exp-name', 'exp-trials', 'exp-seed', 'exp-preset', 'exp-sweep-key', 'exp-sweep-values', 'exp-series', 'exp-params']) {
      $(id).addEventListener('change', () => this.edit(id));
    }
    $('exp-run').addEventListener('click', () => this.run());
    $('exp-cancel').addEventListener('click', () => this.cancel());
    $('exp-chart').addEventListener('change', (e) => this.redraw(e.target.value));
    for (const [id, [kind]] of Object.entries(DOWNLOADS)) $(id).addEventListener('click', () => this.save(kind));
    $('exp-load').addEventListener('change', async (e) => {
      const file = e.target.files?.[0];
      e.target.value = '';
      if (file) await this.loadFile(file);
    });
    this.ro = new ResizeObserver(() => {
      if (this.shown && !$('experiments').hidden && Math.abs(($('exp-figure').clientWidth || 0) - (this.drawnWidth || 0)) > 40) this.redraw(this.mode);
    });
    this.ro.observe($('exp-figure'));
    this.sync();
    this.setStatus('idle', '');
  }

  /** The experiment's query string (view=experiments …). */
  query() {
    return writeExperimentUrl(this.state);
  }

  /** Shows the state in the controls. */
  sync() {
    const s = this.state;
    $('exp-name').value = s.name;
    $('exp-trials').value = s.trials;
    $('exp-seed').value = s.seed;
    $('exp-preset').value = s.preset;
    $('exp-params').value = formatPairs(s.params);
    const custom = s.name === CUSTOM;
    $('exp-custom').hidden = !custom;
    if (s.sweep) {
      $('exp-sweep-key').value = s.sweep.key;
      $('exp-sweep-values').value = s.sweep.values.join(' ');
    } else if (!custom) $('exp-sweep-values').value = '';
    $('exp-series').value = s.series.map(formatSeries).join('\n');
    const e = this.list.find((x) => x.name === s.name);
    setText('exp-help', e ? `${e.help} (default ${e.defaultTrials} trials per point).` : '');
    const p = this.schema.params.find((q) => q.key === $('exp-sweep-key').value);
    setText('exp-sweep-help', p ? `${p.key}: ${p.allowed}` : '');
  }

  /** The controls' values as an experiment query (the URL's form). */
  controlsQuery(changed) {
    const q = new URLSearchParams([['exp', $('exp-name').value], ['seed', $('exp-seed').value.trim()]]);
    // A new experiment starts from its own default trials and preset.
    if (changed !== 'exp-name') {
      q.set('trials', $('exp-trials').value.trim());
      q.set('preset', $('exp-preset').value);
    }
    return q;
  }

  /**
   * A control changed: the whole form is read back through the URL reader
   * (one validator for both); a bad value keeps the state as it was.
   */
  edit(changed) {
    const q = this.controlsQuery(changed);
    const problems = [];
    try {
      for (const [k, v] of parsePairs($('exp-params').value)) q.append(k, v);
    } catch (err) {
      problems.push(`Base parameters: ${err.message}.`);
    }
    if ($('exp-name').value === CUSTOM) {
      const values = $('exp-sweep-values').value.trim();
      if (values) q.set('sweep', `${$('exp-sweep-key').value}:${values}`);
      for (const line of $('exp-series').value.split('\n').map((l) => l.trim()).filter(Boolean)) {
        try {
          parseSeries(line);
          q.append('series', line);
        } catch (err) {
          problems.push(`Series: ${err.message}.`);
        }
      }
    }
    const { state, messages, conflict } = readExperimentUrl(this.engine, this.schema, q.toString(), this.list, this.presets);
    if (problems.length || messages.length) {
      showMessage([...problems, ...messages, 'The experiment was not changed.'].join('\n'));
      this.sync();
      return;
    }
    // A conflict between valid values is shown, not undone: the next edit may resolve it.
    showMessage(conflict ?? '');
    this.state = state;
    this.sync();
    this.onUrl(this.query());
  }

  /** Copies the live view's configuration (its non-default parameters, not the seed) as base parameters. */
  useLiveConfig(pairs) {
    this.state = { ...this.state, params: pairs.filter(([k]) => k !== 'seed') };
    this.sync();
    this.onUrl(this.query());
  }

  /** Replaces the whole state (a URL, the test hook). */
  setState(state) {
    this.state = state;
    this.sync();
    this.onUrl(this.query());
  }

  setStatus(status, text) {
    document.body.dataset.experiment = status;
    setText('exp-status', text);
    const running = status === 'running';
    $('exp-run').disabled = running;
    $('exp-cancel').disabled = !running;
    for (const id of Object.keys(DOWNLOADS)) $(id).disabled = running || !this.result;
  }

  /** Runs the current experiment; resolves to the result text, or null if it failed or was cancelled. */
  async run() {
    if (this.live) return null;
    const spec = experimentSpec(this.state);
    let plan;
    try {
      plan = this.engine.experimentPlan(spec);
    } catch (err) {
      showMessage(`Experiment: ${err.message}`);
      this.setStatus('error', `Not started: ${err.message}`);
      return null;
    }
    showMessage('');
    this.result = null;
    this.shown = null;
    this.fig = null;
    $('exp-figure').replaceChildren();
    $('exp-table').tBodies[0].replaceChildren();
    $('exp-table').hidden = true;
    $('exp-paired').tBodies[0].replaceChildren();
    $('exp-paired-box').hidden = true;
    setText('exp-title', `${plan.experiment.title}: running…`);
    setText('exp-caption', '');
    const bar = $('exp-progress');
    bar.max = plan.totalUnits;
    bar.value = 0;
    const workers = this.runner.workers;
    const live = { spec, plan, lastDraw: performance.now(), gap: LIVE_MS, drawn: 0 };
    this.live = live;
    const t0 = performance.now();
    const plural = `${workers} worker${workers > 1 ? 's' : ''}`;
    this.setStatus('running', `Starting ${plan.totalUnits} trials on ${plural}…`);
    try {
      const out = await this.runner.run(spec, {
        onProgress: (p) => {
          bar.value = p.done;
          setText('exp-status', `${p.done} / ${p.total} trials · ${fmtDuration(p.seconds)} · about ${fmtDuration(p.eta)} left · ${plural}`);
          this.liveDraw(live, p.done);
        },
      });
      const data = JSON.parse(out.text);
      this.result = { text: out.text, data, source: 'run' };
      this.lastRun = { seconds: out.seconds, workers: out.workers, units: plan.totalUnits, name: spec.name };
      this.live = null;
      await this.show(data);
      this.setStatus('done', `${plan.totalUnits} trials in ${fmtDuration(out.seconds)} on ${plural} (${(plan.totalUnits / out.seconds).toFixed(1)} trials/s).`);
      return out.text;
    } catch (err) {
      this.live = null;
      if (err.message === 'stopped') {
        const k = live.drawn;
        this.setStatus('cancelled', `Cancelled after ${fmtDuration((performance.now() - t0) / 1000)}${k ? `; the chart shows the ${k} trials done by then` : ''}. Nothing to save.`);
      } else {
        showMessage(`Experiment failed: ${err.message}`);
        this.setStatus('error', `Failed: ${err.message}`);
      }
      return null;
    }
  }

  /**
   * Redraws the chart from the trials finished so far (the engine's
   * statistics of any subset of rows), at most once a second, and less
   * often if that takes long: while the page's thread computes them, no
   * worker gets its next chunk, so they may take at most LIVE_SHARE of it.
   */
  liveDraw(live, done) {
    const now = performance.now();
    if (this.live !== live || done <= live.drawn || done === live.plan.totalUnits || now - live.lastDraw < live.gap) return;
    const rows = this.runner.finishedRows();
    if (!rows) return;
    live.drawn = done;
    const data = JSON.parse(this.engine.experimentResult(live.spec, rows));
    live.lastDraw = performance.now();
    live.gap = Math.max(LIVE_MS, (live.lastDraw - now) / LIVE_SHARE);
    this.show(data, `${done} of ${live.plan.totalUnits} trials so far`);
  }

  cancel() {
    if (this.live) this.runner.cancel();
  }

  /** Draws a result: the chart, its caption, the table of points. */
  show(data, partial = '') {
    // Another experiment starts from the chart its header names; the same one keeps the chart chosen.
    const same = this.modeOf === data.experiment.name;
    this.modeOf = data.experiment.name;
    this.shown = data;
    const modes = chartModes(data);
    if (!same || !modes.includes(this.mode)) this.mode = modes[0];
    fillSelect($('exp-chart'), modes.map((m) => [m, MODE_LABELS[m]]));
    $('exp-chart').value = this.mode;
    // Empty until there is a result to chart.
    $('exp-chart').disabled = false;
    const e = data.experiment;
    setText('exp-title', `${e.title}${partial ? ` (running: ${partial})` : ''}`);
    this.fillTable(data);
    return this.redraw(this.mode);
  }

  /** What the chart of `data` drawn as `mode` shows, in words. */
  caption(data, mode) {
    const e = data.experiment;
    const s = data.spec;
    const bound = mode !== 'excess' && mode !== 'hist' && data.points.some((p) => p.lower_bound !== null && p.lower_bound !== undefined);
    return [
      `${mode === 'excess' ? 'steps − optimal steps' : e.y.label}; seed ${s.seed}, ${s.trials} ${e.kind === 'targets' ? 'samples' : 'trials'} per point, preset ${s.preset ?? 'none'}; engine ${data.version}.`,
      mode === 'box' ? 'Boxes: quartiles; thick tick: median; ◇: mean; whiskers: the last values within 1.5 IQR; red numbers: capped trials (kept at the cap, never dropped).' : '',
      mode === 'mean' || mode === 'excess' ? 'Bands and bars: 95% intervals of the mean (a seeded bootstrap, BCa with expanded tails: they stay within the trials\' range).' : '',
      bound ? `Grey dashes: the lower bound on the expected ${e.metric === 'excess' ? 'excess steps' : 'steps'} of any searcher.` : '',
      ...(mode !== 'excess' && mode !== 'hist' ? (e.references ?? []).map((r) => `×: ${r.label}.`) : []),
      e.note ? `Note: ${e.note}.` : '',
      'Click a point (or Open in the table) to watch its configuration in the live view.',
    ].filter(Boolean).join(' ');
  }

  /** Draws the shown result as `mode` (drawings are serialised: a late one never overwrites a newer one). */
  redraw(mode) {
    if (!this.shown) return this.drawing;
    this.mode = mode;
    const data = this.shown;
    setText('exp-caption', this.caption(data, mode));
    this.drawing = this.drawing.then(async () => {
      if (data !== this.shown) return;
      try {
        this.fig = await drawExperiment($('exp-figure'), data, mode, { onPoint: (p) => this.openPoint(p.index, data) });
        this.drawnWidth = $('exp-figure').clientWidth;
        $('exp-figure').dataset.mode = mode;
      } catch (err) {
        showMessage(`Could not draw the chart: ${err.message}`);
      }
    });
    return this.drawing;
  }

  fillTable(data) {
    const body = $('exp-table').tBodies[0];
    const rows = data.points.map((p) => {
      const tr = document.createElement('tr');
      for (const v of [p.series, p.x, String(p.n), interval(p.mean), interval(p.median), String(p.capped), num(p.lower_bound, 2)]) {
        tr.insertCell().textContent = v;
      }
      const b = document.createElement('button');
      b.type = 'button';
      b.textContent = 'Open';
      b.title = pointSummary(data, p);
      b.addEventListener('click', () => this.openPoint(p.index, data));
      tr.insertCell().append(b);
      return tr;
    });
    body.replaceChildren(...rows);
    setText('exp-table-x', xName(data) || 'x');
    $('exp-table').hidden = false;
    this.fillPaired(data);
  }

  /** The paired comparisons (the engine's, series − reference over the trials both have). */
  fillPaired(data) {
    const paired = data.paired ?? [];
    const rows = paired.map((c) => {
      const tr = document.createElement('tr');
      for (const v of [c.series, c.reference, c.x, String(c.n), interval(c.difference), `${c.wins} / ${c.ties} / ${c.losses}`]) tr.insertCell().textContent = v;
      return tr;
    });
    $('exp-paired').tBodies[0].replaceChildren(...rows);
    setText('exp-paired-x', xName(data) || 'x');
    const what = data.experiment.metric === 'excess' ? 'excess steps' : data.experiment.metric;
    setText('exp-paired-summary', `Paired comparisons (${paired.length}): ${what}, series − reference, over the same trials`);
    $('exp-paired-box').hidden = paired.length === 0;
  }

  /**
   * Opens point `index` of `data` in the live view: its configuration, with
   * the seed of its trial 0 (the live view runs trial 0 of a config).
   */
  openPoint(index, data = this.shown) {
    const p = data?.points.find((q) => q.index === index);
    if (!p) return Promise.resolve(false);
    const at = data.experiment.x.values.length > 1 ? ` at ${xName(data)} = ${p.x}` : '';
    return this.onOpen(p.config, `Opened ${p.series}${at} from “${data.experiment.title}”: trial 0 of the point (seed ${p.config.seed}).`);
  }

  /** The text of a download, or a blob. */
  async exported(kind) {
    const r = this.result;
    if (!r) throw new Error('no finished result to save');
    if (kind === 'json') return new Blob([r.text], { type: 'application/json' });
    if (kind === 'csv') return new Blob([this.engine.experimentCsv(r.text)], { type: 'text/csv' });
    if (kind === 'trials-csv') return new Blob([this.engine.experimentTrialsCsv(r.text)], { type: 'text/csv' });
    if (kind === 'paired-csv') return new Blob([this.engine.experimentPairedCsv(r.text)], { type: 'text/csv' });
    await this.drawing;
    if (!this.fig) throw new Error('no chart drawn');
    const svg = standaloneSvg(this.fig, r.data.experiment.title);
    if (kind === 'svg') return new Blob([svg], { type: 'image/svg+xml' });
    return svgToPng(svg);
  }

  async save(kind) {
    try {
      const blob = await this.exported(kind);
      const name = this.result.data.experiment.name;
      const suffix = Object.values(DOWNLOADS).find(([k]) => k === kind)[1];
      download(blob, `${name}${kind === 'svg' || kind === 'png' ? `-${this.mode}` : ''}${suffix}`);
    } catch (err) {
      showMessage(`Could not save ${kind.replace('-', ' ').toUpperCase()}: ${err.message}`);
    }
  }

  /**
   * Loads a results file (from this page or the CLI). A file the engine
   * refuses changes nothing and gets a message. Resolves to true if loaded.
   */
  async loadFile(file) {
    if (file.size > MAX_RESULT_BYTES) {
      showMessage(`${file.name}: ${file.size} bytes is more than the ${MAX_RESULT_BYTES >> 20} MiB a results file may have. Nothing changed.`);
      return false;
    }
    return this.loadText(await file.text(), file.name);
  }

  async loadText(text, name = 'the file') {
    if (this.live) {
      showMessage(`${name}: a run is under way; cancel it first. Nothing changed.`);
      return false;
    }
    let data;
    try {
      data = this.engine.experimentRead(text);
    } catch (err) {
      showMessage(`${name} is not a results file this page can read: ${err.message}. Nothing changed.`);
      return false;
    }
    showMessage('');
    this.result = { text, data, source: name };
    await this.show(data);
    this.setStatus('loaded', `Loaded ${name}: ${data.experiment.title}, ${data.points.length} points.`);
    return true;
  }
}
