// Wires the page: controls <-> URL config, the controller's frame loop, the
// renderers, the stats / decision / legend panels, race mode, export/import.
// No game logic: every number shown comes from the wasm engine, which runs
// the search in a worker (www/search-worker.js).

import { loadEngine, engineModule, coreConfig, RACE, describeError } from './engine.js';
import { SearchSession } from './search-session.js';
import { parseParams, parseValue, serializeConfig, defaults, describeSearcher, encodePaint, decodePaint, SPECS } from './url-state.js';
import { Renderer, drawColorbar, drawNotice, MOVE_NAMES } from './renderer.js';
import { Controller } from './controller.js';
import { StepsChart } from './charts.js';
import { WorkerPool } from './worker-pool.js';

const SPEEDS = [1, 2, 5, 10, 20, 50, 100, 200, 500, 1000, 2000, 5000, 20000, 'max'];
const SPEC = Object.fromEntries(SPECS.map((s) => [s.key, s]));
const $ = (id) => document.getElementById(id);

/** Heatmap layers, bottom to top. `dep`: what makes a cached rendering stale. */
const LAYER_DEFS = [
  { id: 'layer-prior', name: 'prior', label: 'Prior mass', palette: 'viridis', alphaLo: 255, alphaHi: 255, counts: false, dep: 'static' },
  { id: 'layer-posterior', name: 'posterior', label: 'Posterior mass', palette: 'cividis', alphaLo: 60, alphaHi: 255, counts: false, dep: 'steps' },
  { id: 'layer-searched', name: 'searched', label: 'Searched', palette: 'ember', alphaLo: 0, alphaHi: 70, counts: false, dep: 'steps', binary: true },
  { id: 'layer-visits', name: 'visits', label: 'MCTS visits', palette: 'ember', alphaLo: 0, alphaHi: 235, counts: true, dep: 'loops' },
  { id: 'layer-walker', name: 'walker', label: 'NSARW counts', palette: 'ember', alphaLo: 0, alphaHi: 235, counts: true, dep: 'steps' },
];

const page = {
  wasm: null,
  config: defaults(),
  paint: null, // Uint8Array of n*n levels 0..15 when prior=paint
  painting: null, // preview RGBA while a stroke is under way
  renderers: [],
  controller: null,
  chart: null,
  runTime: 0, // seconds spent running (for the chart)
  lastTs: 0,
  luts: {},
  replay: null, // { path, speed } while an imported episode replays
  legendKey: '',
  keepTraces: 1,
  trapped: false,
  panelsTs: 0, // when the text panels were last updated
};
/** Least time between text-panel updates while running (ms). */
const PANEL_MS = 100;
window.torusPage = page; // for tests and the console
page.WorkerPool = WorkerPool;

// ---------------------------------------------------------------- messages

function showMessage(text, { append = false } = {}) {
  const el = $('message');
  el.textContent = append && !el.hidden && el.textContent ? `${el.textContent}\n${text}` : text;
  el.hidden = !text;
}

// ----------------------------------------------------------------- config

function updateUrl() {
  const q = serializeConfig(page.config);
  history.replaceState(null, '', `${location.pathname}${q ? `?${q}` : ''}`);
}

function weightsFromPaint() {
  if (page.config.prior !== 'paint' || !page.paint) return null;
  return Float64Array.from(page.paint, (lv) => lv);
}

function keepTraces() {
  const k = Number($('rollout-k').value) || 1;
  if ($('layer-rollouts').checked) return Math.min(64, Math.max(1, k));
  return $('layer-practice').checked ? 1 : 0;
}

/** The worker's reset request for the current config (race mode adds a second run). */
function resetSpec() {
  const cfg = page.config;
  const weights = weightsFromPaint();
  page.keepTraces = keepTraces();
  const runs = [{ core: coreConfig(cfg, { weights, keepTraces: page.keepTraces }), label: describeSearcher(cfg) }];
  if (cfg.race && RACE[cfg.race]) {
    const override = RACE[cfg.race];
    runs.push({ core: coreConfig(cfg, { weights, keepTraces: page.keepTraces, override }), label: describeSearcher({ ...cfg, ...override }) });
  }
  return { runs, seed: String(cfg.seed) };
}

function onRuns(runs) {
  page.runTime = 0;
  page.chart?.reset(runs.map((r, i) => (runs.length > 1 ? `${i === 0 ? 'A' : 'B'}: ${r.label}` : r.label)));
  setupBoards(runs);
}

function setupBoards(runs) {
  const race = runs.length > 1;
  $('boards').classList.toggle('race', race);
  $('board-1').hidden = !race;
  $('scoreboard').hidden = !race;
  runs.forEach((r, i) => {
    $(`board-${i}`).querySelector('.board-title').textContent = race ? `${i === 0 ? 'A' : 'B'}: ${r.label}` : '';
  });
  requestAnimationFrame(() => page.renderers.forEach((r) => r.fitToElement()));
}

/** Restarts the run(s) from the current config (same seed). */
function restart({ autoplay } = {}) {
  if (page.trapped) {
    // A trap in the page's own wasm instance (not the search worker's, which
    // is replaced at the next reset) leaves it untrustworthy: reload.
    location.reload();
    return;
  }
  const play = autoplay ?? (page.controller.state === 'running' || page.config.autoplay);
  page.replay = null;
  if (!['error'].includes(page.controller.state)) showMessage('');
  page.controller.reset({ autoplay: play });
}

/** Applies one parameter from a control, validated like the URL. */
function setParam(key, raw) {
  const spec = SPEC[key];
  const r = parseValue(spec, raw, page.config.n);
  if (!r.ok) {
    const allowed = spec.kind === 'enum' ? `one of ${spec.values.join(', ')}` : spec.help;
    showMessage(`Invalid ${key} ${JSON.stringify(String(raw).slice(0, 40))}: allowed ${allowed}. Keeping ${key}=${formatParam(key)}.`);
    syncControls();
    return false;
  }
  page.config[key] = r.value;
  return true;
}

function formatParam(key) {
  const v = page.config[key];
  return Array.isArray(v) ? v.join(',') : String(v);
}

function onConfigChange(key, raw) {
  if (!setParam(key, raw)) return;
  const cfg = page.config;
  if (key === 'n') {
    if (cfg.start[0] > cfg.n || cfg.start[1] > cfg.n) cfg.start = [Math.min(cfg.start[0], cfg.n), Math.min(cfg.start[1], cfg.n)];
    if (page.paint) resizePaint(cfg.n);
  }
  if (key === 'prior' && cfg.prior === 'paint') {
    if (!page.paint || page.paint.length !== cfg.n * cfg.n) {
      page.paint = new Uint8Array(cfg.n * cfg.n);
      // Seed the canvas with a blob at the centre so the prior is valid at once.
      paintAt(Math.floor(cfg.n / 2) * cfg.n + Math.floor(cfg.n / 2), Math.max(1, Math.round(cfg.n / 10)), false);
    }
    cfg.paint = encodePaint(page.paint);
    $('click-start').checked = false;
  }
  syncControls();
  updateUrl();
  restart();
}

// --------------------------------------------------------------- controls

function speedIndex(speed) {
  if (speed === 'max') return SPEEDS.length - 1;
  let best = 0;
  SPEEDS.forEach((s, i) => {
    if (s !== 'max' && Math.abs(Math.log(s) - Math.log(speed)) < Math.abs(Math.log(SPEEDS[best]) - Math.log(speed))) best = i;
  });
  return best;
}

function speedLabel(speed) {
  return speed === 'max' ? 'as fast as possible' : `${speed} loop${speed === 1 ? '' : 's'}/frame`;
}

function syncControls() {
  const c = page.config;
  $('n').value = c.n;
  $('prior').value = c.prior;
  $('sigma').max = String(Math.max(5, c.n));
  $('sigma').value = c.sigma;
  $('sigma-out').value = c.prior === 'gaussian' ? `${c.sigma}` : '';
  $('sigma-row').hidden = c.prior !== 'gaussian';
  $('paint-tools').hidden = c.prior !== 'paint';
  $('rv').value = c.rv;
  $('start').value = `${c.start[0]},${c.start[1]}`;
  $('searcher').value = c.searcher;
  $('variant').value = c.variant;
  $('rollout').value = c.rollout;
  $('belief').value = c.belief;
  $('budget').value = c.ms > 0 ? 'ms' : 'loops';
  $('loops').value = c.loops;
  $('ms').value = c.ms > 0 ? c.ms : '';
  $('loops-row').hidden = c.ms > 0;
  $('ms-row').hidden = !(c.ms > 0);
  $('c').value = +c.c.toFixed(6);
  $('mu').value = c.mu;
  $('final').value = c.final;
  $('seed').value = String(c.seed);
  $('race').value = c.race;
  const mcts = c.searcher === 'mcts';
  for (const id of ['variant', 'rollout', 'belief', 'budget', 'loops', 'ms', 'c', 'final']) $(id).disabled = !mcts;
  $('mu').disabled = !(c.searcher === 'levy' || (mcts && c.rollout === 'levy'));
  $('step-loop').disabled = !mcts;
  $('speed').value = speedIndex(c.speed);
  $('speed-label').value = speedLabel(c.speed);
}

function bindControls() {
  const change = (id, key, get = (el) => el.value) => {
    $(id).addEventListener('change', (e) => onConfigChange(key, get(e.target)));
  };
  change('n', 'n');
  change('prior', 'prior');
  change('rv', 'rv');
  change('start', 'start');
  change('searcher', 'searcher');
  change('variant', 'variant');
  change('rollout', 'rollout');
  change('belief', 'belief');
  change('loops', 'loops');
  change('c', 'c');
  change('mu', 'mu');
  change('final', 'final');
  change('seed', 'seed');
  change('race', 'race');
  change('ms', 'ms');
  $('sigma').addEventListener('input', (e) => {
    $('sigma-out').value = e.target.value;
  });
  change('sigma', 'sigma');
  $('budget').addEventListener('change', (e) => {
    if (e.target.value === 'ms') onConfigChange('ms', page.config.ms > 0 ? page.config.ms : 20);
    else onConfigChange('ms', 0);
  });

  $('play').addEventListener('click', () => togglePlay());
  $('step-move').addEventListener('click', () => page.controller.stepMove());
  $('step-loop').addEventListener('click', () => page.controller.stepLoop());
  $('reset').addEventListener('click', () => restart({ autoplay: page.config.autoplay }));
  $('new-seed').addEventListener('click', () => {
    const r = crypto.getRandomValues(new Uint32Array(1))[0];
    page.config.seed = BigInt(r);
    syncControls();
    updateUrl();
    restart({ autoplay: true });
  });
  $('speed').addEventListener('input', (e) => {
    const s = SPEEDS[Number(e.target.value)];
    page.config.speed = s;
    page.controller.setSpeed(s);
    $('speed-label').value = speedLabel(s);
    updateUrl();
  });

  // View options: redraw only; trace count changes need a fresh run.
  for (const def of LAYER_DEFS) $(def.id).addEventListener('change', () => page.controller.requestDraw());
  for (const id of ['layer-path', 'layer-grid', 'reveal', 'tiling', 'log-scale', 'layer-arrows']) {
    $(id).addEventListener('change', () => page.controller.requestDraw());
  }
  for (const id of ['layer-rollouts', 'rollout-k', 'layer-practice']) {
    $(id).addEventListener('change', () => {
      if (keepTraces() !== page.keepTraces) {
        showMessage('Rollout traces are recorded from the start of a run: restarting with the same seed.');
        restart();
      } else page.controller.requestDraw();
    });
  }

  $('batch-run').addEventListener('click', runBatch);
  $('batch-stop').addEventListener('click', () => page.pool?.terminate());
  $('teaching').addEventListener('click', () => applyPreset('teaching'));
  $('defaults').addEventListener('click', () => applyPreset('default'));
  $('copy-link').addEventListener('click', copyLink);
  $('export-png').addEventListener('click', exportPng);
  $('export-json').addEventListener('click', exportJson);
  $('import-json').addEventListener('change', importJson);
  $('paint-clear').addEventListener('click', () => {
    page.paint = new Uint8Array(page.config.n * page.config.n);
    page.painting = null;
    showMessage('Paint a prior on the grid (drag with the mouse or a finger).');
    page.controller.requestDraw();
  });

  document.addEventListener('keydown', (e) => {
    const t = e.target;
    if (e.ctrlKey || e.metaKey || e.altKey) return;
    if (t instanceof HTMLElement && t.closest('input, select, textarea, [contenteditable]')) return;
    if (e.key === ' ') {
      e.preventDefault();
      if (!(t instanceof HTMLButtonElement)) togglePlay();
      else togglePlay();
    } else if (e.key === 'ArrowRight') {
      e.preventDefault();
      page.controller.stepMove();
    } else if (e.key === 'ArrowUp') {
      e.preventDefault();
      page.controller.stepLoop();
    } else if (e.key === 'r' || e.key === 'R') {
      restart({ autoplay: page.config.autoplay });
    }
  });
  // Space on a focused button would also "click" it; keep one toggle.
  $('play').addEventListener('keydown', (e) => {
    if (e.key === ' ') e.stopPropagation();
  });

  bindCanvas();
}

function togglePlay() {
  const c = page.controller;
  if (c.state === 'error') restart({ autoplay: true });
  else c.toggle();
}

function applyPreset(name) {
  const d = defaults();
  if (name === 'teaching') {
    Object.assign(d, { n: 11, sigma: 2, loops: 40, speed: 1, seed: 3n, start: [2, 2] });
    $('layer-rollouts').checked = true;
    $('rollout-k').value = '3';
    $('layer-practice').checked = true;
    $('layer-visits').checked = true;
    $('layer-prior').checked = true;
    $('layer-arrows').checked = true;
    $('layer-grid').checked = true;
  }
  page.config = d;
  page.paint = null;
  syncControls();
  updateUrl();
  page.controller.setSpeed(d.speed);
  restart({ autoplay: true });
  if (name === 'teaching') {
    showMessage('Teaching view: one MCTS loop per frame. Each loop draws a practice target (◇) from the belief (the prior, or the posterior: the prior with searched cells removed), picks the neighbour with the highest UCT value, runs a random rollout from it until the rollout finds the practice target, then adds one visit to every cell the loop passed and credits each with 1/(its own steps to the practice target): the picked neighbour gets 1/τ. Pause and press ↑ to step a single loop.');
  }
}

// ----------------------------------------------------------- canvas input

function resizePaint(n) {
  const old = page.paint;
  const m = Math.round(Math.sqrt(old.length));
  const out = new Uint8Array(n * n);
  for (let y = 0; y < n; y++) {
    for (let x = 0; x < n; x++) out[y * n + x] = old[Math.floor((y * m) / n) * m + Math.floor((x * m) / n)];
  }
  page.paint = out;
  page.config.paint = encodePaint(out);
}

function paintAt(idx, radius, erase) {
  const n = page.config.n;
  const cx = idx % n;
  const cy = Math.floor(idx / n);
  const r = Math.max(0, radius);
  for (let dy = -r; dy <= r; dy++) {
    for (let dx = -r; dx <= r; dx++) {
      const d2 = dx * dx + dy * dy;
      if (d2 > r * r + r) continue;
      const x = (cx + dx + n) % n;
      const y = (cy + dy + n) % n;
      const i = y * n + x;
      const add = Math.max(1, Math.round(4 * (1 - Math.sqrt(d2) / (r + 1))));
      page.paint[i] = erase ? 0 : Math.min(15, page.paint[i] + add);
    }
  }
}

function bindCanvas() {
  for (let i = 0; i < 2; i++) {
    const canvas = $(`view-${i}`);
    let stroke = false;
    let lastIdx = -1;
    const paintMode = () => page.config.prior === 'paint' && !$('click-start').checked;
    canvas.addEventListener('pointerdown', (e) => {
      const idx = page.renderers[i].cellAt(e.clientX, e.clientY);
      if (idx < 0) return;
      if (paintMode()) {
        stroke = true;
        canvas.setPointerCapture(e.pointerId);
        page.controller.pause();
        if (!page.paint) page.paint = new Uint8Array(page.config.n * page.config.n);
        paintAt(idx, Number($('brush').value), $('erase').checked);
        lastIdx = idx;
        previewPaint();
      } else if ($('click-start').checked) {
        const n = page.config.n;
        onConfigChange('start', `${(idx % n) + 1},${Math.floor(idx / n) + 1}`);
      }
    });
    canvas.addEventListener('pointermove', (e) => {
      if (!stroke) return;
      const idx = page.renderers[i].cellAt(e.clientX, e.clientY);
      if (idx < 0 || idx === lastIdx) return;
      lastIdx = idx;
      paintAt(idx, Number($('brush').value), $('erase').checked);
      previewPaint();
    });
    const end = () => {
      if (!stroke) return;
      stroke = false;
      page.painting = null;
      if (!page.paint.some((v) => v > 0)) {
        showMessage('The painted prior is empty: paint some cells (the target is drawn from it).');
        return;
      }
      page.config.paint = encodePaint(page.paint);
      updateUrl();
      restart({ autoplay: false });
    };
    canvas.addEventListener('pointerup', end);
    canvas.addEventListener('pointercancel', end);
  }
}

function previewPaint() {
  const vals = Float64Array.from(page.paint);
  page.painting = page.wasm.colorizeValues(vals, 'viridis', 'linear', 60, 255);
  page.controller.requestDraw();
}

// ------------------------------------------------------------------- draw

function layerSpecs(run) {
  const log = $('log-scale').checked;
  const specs = [];
  for (const def of LAYER_DEFS) {
    if (!$(def.id).checked) continue;
    if (def.name === 'walker' && run.core.searcher !== 'nsarw') continue;
    if (def.name === 'visits' && !run.isMcts && run.core.searcher !== 'nsarw') continue;
    specs.push({ ...def, scale: def.counts ? (log ? 'log' : 'stretch') : 'linear' });
  }
  return specs;
}

/** What each run's next frame from the worker must carry. */
function frameViews(runs) {
  const traces = $('layer-rollouts').checked || $('layer-practice').checked;
  return runs.map((r) => r.request(layerSpecs(r), traces && r.isMcts));
}

function draw(info) {
  const runs = page.controller.runs;
  const ts = performance.now();
  if (info.state === 'running' && page.lastTs) page.runTime += Math.min(0.25, (ts - page.lastTs) / 1000);
  page.lastTs = info.state === 'running' ? ts : 0;
  if (!runs.length) return;
  const reveal = $('reveal').checked;
  const snaps = runs.map((run) => {
    // Bottom to top, as chosen now; a layer just switched on appears with the next frame.
    const layers = layerSpecs(run)
      .map((spec) => {
        const got = run.layers.get(spec.name);
        return got ? { ...spec, ...got } : null;
      })
      .filter(Boolean);
    return { ...run.snap, n: run.n, optimal: run.optimalSteps, target: run.targetCell, start: run.startCell, pathLen: run.pathLen, layers };
  });
  snaps.forEach((snap, i) => {
    const run = runs[i];
    const layers = snap.layers.slice();
    if (page.painting && i === 0) {
      const idx = layers.findIndex((l) => l.name === 'prior');
      const rgba = new Uint8ClampedArray(page.painting.buffer, page.painting.byteOffset, page.painting.length);
      // A preview changes every stroke: never reuse an upload for it (no key).
      if (idx >= 0) layers[idx] = { rgba };
      else layers.unshift({ rgba });
    }
    const found = snap.status === 'found';
    const more = page.renderers[i].draw({
      n: snap.n,
      layers,
      path: $('layer-path').checked ? run.pathView() : null,
      pathLen: snap.pathLen,
      pathKey: run,
      start: snap.start,
      position: snap.position,
      target: snap.target,
      showTarget: found || reveal,
      rv: run.core.rv,
      rollouts: $('layer-rollouts').checked ? run.traces : [],
      practice: $('layer-practice').checked && snap.status === 'running' ? run.practice : -1,
      decision: $('layer-arrows').checked && snap.decision && snap.status === 'running' ? arrowData(snap.decision) : null,
      grid: $('layer-grid').checked,
      tiling: $('tiling').checked,
    });
    // A long path drawn again (after a resize, say) fills in over frames.
    if (more) page.controller.requestDraw();
  });
  // Text panels and the chart change ~10 times a second while running: more
  // is unreadable, and each change costs the page's thread style, layout and
  // paint work that the canvas needs for 60 fps.
  if (info.state !== 'running' || ts - page.panelsTs >= PANEL_MS) {
    page.panelsTs = ts;
    updatePanels(snaps, runs, info);
  }
}

function arrowData(d) {
  const visits = d.children.map((c) => c.selected);
  return { visits, chosen: leading(d) };
}

/** The move the final rule would pick now (display only; ties show the first). */
function leading(d) {
  const rule = page.config.final;
  const val = (c) => (rule === 'visits' ? c.selected : rule === 'mean' ? (c.visits ? c.mean : -Infinity) : c.uct ?? Infinity);
  let best = -1;
  d.children.forEach((c, i) => {
    if (best < 0 || val(c) > val(d.children[best])) best = i;
  });
  return d.children.every((c) => c.selected === 0) ? -1 : best;
}

// ----------------------------------------------------------------- panels

const INT_FORMAT = new Intl.NumberFormat('en-US', { maximumFractionDigits: 0 });
const fmtInt = (v) => INT_FORMAT.format(Math.round(v));
function fmtRate(v) {
  if (v >= 1e9) return `${(v / 1e9).toFixed(2)} G`;
  if (v >= 1e6) return `${(v / 1e6).toFixed(2)} M`;
  if (v >= 1e4) return `${(v / 1e3).toFixed(1)} k`;
  return v.toFixed(0);
}
function fmtNum(v, digits = 4) {
  if (v === null || v === undefined) return '∞';
  if (!Number.isFinite(v)) return '∞';
  if (v === 0) return '0';
  if (Math.abs(v) < 1e-3) return v.toExponential(2);
  return v.toFixed(digits);
}
function setText(id, text) {
  const el = typeof id === 'string' ? $(id) : id;
  if (el.textContent !== text) el.textContent = text;
}

function resultLine(snap) {
  const ratio = snap.optimal > 0 ? (snap.steps / snap.optimal).toFixed(2) : '—';
  if (snap.status === 'found') return `Found in ${snap.steps} steps (optimal ${snap.optimal}, ratio ${ratio})`;
  if (snap.status === 'capped') return `Step cap reached after ${snap.steps} steps: not found`;
  return '';
}

function updatePanels(snaps, runs, info) {
  const s = snaps[0];
  const reveal = $('reveal').checked;
  const known = s.status === 'found' || reveal;
  setText('steps', fmtInt(s.steps));
  setText('optimal', known ? String(s.optimal) : '?');
  setText('ratio', s.status === 'found' ? (s.optimal > 0 ? (s.steps / s.optimal).toFixed(2) : '— (optimal 0)') : '–');
  const cfg = page.config;
  const budget = runs[0].isMcts ? (cfg.ms > 0 ? `${cfg.ms} ms` : fmtInt(cfg.loops)) : '—';
  setText('decision-loops', runs[0].isMcts ? `${fmtInt(s.loopsDone)} / ${budget}` : '—');
  setText('rollouts', `${fmtInt(s.decisionRollouts)} / ${fmtInt(s.rollouts)}`);
  setText('rollout-steps', `${fmtRate(s.decisionRolloutSteps)} / ${fmtRate(s.rolloutSteps)}`);
  setText('truncated', fmtInt(s.truncated));
  const m = info.meter;
  setText('loops-per-s', fmtRate(m.loopsPerS));
  setText('steps-per-s', fmtRate(m.stepsPerS));
  setText('fps', m.fps.toFixed(0));
  setText('state-badge', page.controller.state);
  setText('play', page.controller.state === 'running' ? 'Pause' : 'Play');

  snaps.forEach((snap, i) => {
    const banner = $(`board-${i}`).querySelector('.banner');
    const line = resultLine(snap);
    banner.hidden = !line;
    banner.classList.toggle('capped', snap.status === 'capped');
    setText(banner, line);
  });

  updateDecision(s, runs[0]);
  updateLegend(s);
  if (snaps.length > 1) updateScoreboard(snaps, runs);
  page.chart?.push(
    page.runTime,
    snaps.map((x) => x.steps),
    snaps.map((x) => (x.status === 'found' || reveal ? x.optimal : null)),
    info.state !== 'running',
  );
}

function updateScoreboard(snaps, runs) {
  const body = $('score-rows');
  while (body.rows.length < snaps.length) {
    const tr = body.insertRow();
    for (let k = 0; k < 5; k++) tr.insertCell();
  }
  const done = snaps.every((x) => x.status !== 'running');
  const found = snaps.filter((x) => x.status === 'found');
  const best = found.length ? Math.min(...found.map((x) => x.steps)) : -1;
  snaps.forEach((snap, i) => {
    const tr = body.rows[i];
    const known = snap.status === 'found' || $('reveal').checked;
    const cells = [
      `${i === 0 ? 'A' : 'B'}: ${runs[i].label}`,
      fmtInt(snap.steps),
      known ? String(snap.optimal) : '?',
      snap.status === 'found' && snap.optimal > 0 ? (snap.steps / snap.optimal).toFixed(2) : '–',
      snap.status,
    ];
    cells.forEach((t, k) => setText(tr.cells[k], t));
    tr.classList.toggle('winner', done && snap.status === 'found' && snap.steps === best);
  });
}

function updateDecision(snap, run) {
  const body = $('decision').tBodies[0];
  if (!body.rows.length) {
    for (let m = 0; m < 4; m++) {
      const tr = body.insertRow();
      for (let k = 0; k < 5; k++) tr.insertCell();
      tr.cells[0].className = 'move';
    }
  }
  const d = snap.decision;
  if (!d) {
    for (const tr of body.rows) for (const td of tr.cells) setText(td, '–');
    const how = {
      rw: 'each step is one of the four moves, uniformly at random',
      levy: 'it flies a power-law distributed length in a uniformly random direction, walked as unit moves',
      nsarw: 'each step goes to a least-visited neighbour, ties broken at random',
    }[run.core.searcher];
    setText('decision-note', run.isMcts ? '' : `${run.label} does not deliberate: ${how}.`);
    return;
  }
  const lead = snap.status === 'running' ? leading(d) : -1;
  const totalSel = d.children.reduce((a, c) => a + c.selected, 0) || 1;
  const arrows = ['↑', '→', '↓', '←'];
  d.children.forEach((c, m) => {
    const tr = body.rows[m];
    tr.classList.toggle('chosen', m === lead);
    setText(tr.cells[0], `${arrows[m]} ${MOVE_NAMES[m]}`);
    // Visits: picks this decision (bar) and N(vᵢ) of the child.
    const td = tr.cells[1];
    // A run without a decision yet (or a walker) left plain text here.
    if (td.childNodes.length !== 3) {
      td.replaceChildren();
      td.append(document.createTextNode(''), document.createElement('span'), document.createElement('span'));
      td.childNodes[1].className = 'split';
      td.childNodes[2].className = 'bar';
    }
    td.childNodes[0].nodeValue = fmtInt(c.visits);
    td.childNodes[1].textContent = `picked ${fmtInt(c.selected)}`;
    td.childNodes[2].style.width = `${Math.round((100 * c.selected) / totalSel)}%`;
    setText(tr.cells[2], c.visits ? fmtNum(c.mean) : '–');
    setText(tr.cells[3], c.visits ? fmtNum(c.explore) : '∞');
    setText(tr.cells[4], c.visits ? fmtNum(c.uct) : '∞');
  });
  const rule = { visits: 'most picks', mean: 'best mean', uct: 'best UCT' }[page.config.final];
  let note = `N(v) = ${fmtInt(d.parent_visits)}, c = ${fmtNum(d.c, 3)}. Final move: ${rule}.`;
  if (lead >= 0) {
    const c = d.children[lead];
    if (c.visits) {
      note += ` ${MOVE_NAMES[lead]}: ${fmtNum(c.mean)} + ${fmtNum(d.c, 3)}·√(ln ${fmtInt(d.parent_visits)} / ${fmtInt(c.visits)}) = ${fmtNum(c.mean)} + ${fmtNum(c.explore)} = ${fmtNum(c.uct)}.`;
    }
  }
  if (run.core.variant === 'cells') note += ' (cells: N(vᵢ) counts every rollout that passed through the neighbour.)';
  setText('decision-note', note);
}

function lut(palette) {
  if (!page.luts[palette]) page.luts[palette] = page.wasm.paletteLut(palette);
  return page.luts[palette];
}

function fmtLegend(v, counts) {
  if (counts) return fmtInt(v);
  if (v === 0) return '0';
  return v < 0.01 ? v.toExponential(1) : v.toFixed(3);
}

function updateLegend(snap) {
  const el = $('legend');
  // Rebuild the DOM only when the set of layers changes; otherwise update the ticks.
  const key = snap.layers.map((l) => `${l.name}:${l.scale}`).join('|');
  if (key !== page.legendKey) {
    page.legendKey = key;
    const frag = document.createDocumentFragment();
    for (const l of snap.layers) {
      const entry = document.createElement('div');
      entry.className = 'entry';
      const name = document.createElement('span');
      name.textContent = l.binary ? l.label : `${l.label}${l.scale === 'log' ? ' (log)' : ''}`;
      const bar = document.createElement('canvas');
      if (l.binary) {
        // Two swatches: the background, and the top colour at the layer's alpha over it.
        const top = lut(l.palette).slice(1020, 1024);
        const a = l.alphaHi / 255;
        const bg = [16, 20, 24];
        const mix = bg.map((c, k) => Math.round(c * (1 - a) + top[k] * a));
        drawColorbar(bar, Uint8Array.from([...Array(128)].flatMap(() => [...bg, 255]).concat([...Array(128)].flatMap(() => [...mix, 255]))));
      } else {
        drawColorbar(bar, lut(l.palette));
      }
      const ticks = document.createElement('div');
      ticks.className = 'ticks';
      ticks.append(document.createElement('span'), document.createElement('span'));
      entry.append(name, bar, ticks);
      frag.append(entry);
    }
    const marks = document.createElement('div');
    marks.className = 'marks';
    for (const [cls, label] of [['m-searcher', 'searcher'], ['m-start', 'start'], ['m-target', 'target'], ['m-practice', 'practice target'], ['m-path', 'path'], ['m-rollout', 'rollout']]) {
      const m = document.createElement('span');
      m.className = cls;
      m.textContent = label;
      marks.append(m);
    }
    frag.append(marks);
    el.replaceChildren(frag);
  }
  snap.layers.forEach((l, i) => {
    const [lo, hi] = el.children[i].querySelector('.ticks').children;
    if (l.binary) {
      setText(lo, 'no');
      setText(hi, 'within rᵥ of the path');
    } else {
      setText(lo, l.scale === 'stretch' ? fmtLegend(l.min, true) : '0');
      setText(hi, `${fmtLegend(l.max, l.counts)}${l.counts ? '' : ' per cell'}`);
    }
  });
}

// --------------------------------------------------------- share / export

async function copyLink() {
  updateUrl();
  const link = location.href;
  try {
    await navigator.clipboard.writeText(link);
    showMessage('Link copied: it reproduces this exact run.');
  } catch {
    showMessage(`Copy this link to share the run: ${link}`);
  }
}

function download(blob, name) {
  const url = URL.createObjectURL(blob);
  const a = document.createElement('a');
  a.href = url;
  a.download = name;
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 5000);
}

function baseName() {
  const c = page.config;
  return `torus-${c.searcher}${c.searcher === 'mcts' ? `-${c.variant}` : ''}-n${c.n}-seed${c.seed}`;
}

function exportPng() {
  const canvases = page.controller.runs.map((_, i) => $(`view-${i}`));
  const w = canvases.reduce((a, c) => a + c.width, 0) + 8 * (canvases.length - 1);
  const h = Math.max(...canvases.map((c) => c.height));
  const out = document.createElement('canvas');
  out.width = w;
  out.height = h;
  const ctx = out.getContext('2d');
  ctx.fillStyle = '#0b0e11';
  ctx.fillRect(0, 0, w, h);
  let x = 0;
  for (const c of canvases) {
    ctx.drawImage(c, x, 0);
    x += c.width + 8;
  }
  out.toBlob((blob) => blob && download(blob, `${baseName()}.png`), 'image/png');
}

async function episodeJson() {
  const answer = await page.controller.send('export');
  if (!answer) throw new Error('the engine is not available');
  const [main, race] = answer.runs;
  return {
    format: 'torus-search-episode',
    version: 1,
    engine: page.wasm.version(),
    url_query: serializeConfig(page.config, { full: true }),
    seed: String(page.config.seed),
    cells: 'path entries are 0-based cell indices y*n + x; users see (x+1, y+1)',
    episode: main,
    race: race ?? null,
  };
}

async function exportJson() {
  if (!page.controller.runs.length) return;
  let data;
  try {
    data = await episodeJson();
  } catch (err) {
    showMessage(`Could not export: ${err.message}`);
    return;
  }
  const text = JSON.stringify(data, null, 1);
  download(new Blob([text], { type: 'application/json' }), `${baseName()}.json`);
}

/** Imports an exported episode and replays it, checking the path move by move. */
async function importJson(e) {
  const file = e.target.files?.[0];
  e.target.value = '';
  if (!file) return;
  try {
    importEpisode(JSON.parse(await file.text()));
  } catch (err) {
    showMessage(`Could not import ${file.name}: ${err.message}`);
  }
}

function importEpisode(data) {
  if (!data || data.format !== 'torus-search-episode' || typeof data.url_query !== 'string' || !data.episode || !Array.isArray(data.episode.path)) {
    throw new Error('not a torus-search episode file');
  }
  const { config, messages } = parseParams(data.url_query);
  if (messages.length) throw new Error(messages.join(' '));
  page.config = config;
  page.paint = config.prior === 'paint' ? decodePaint(config.paint, config.n) : null;
  syncControls();
  updateUrl();
  page.controller.setSpeed('max');
  restart({ autoplay: true });
  page.replay = { path: data.episode.path.map(Number), speed: config.speed, timed: config.ms > 0 };
  showMessage(`Replaying the imported episode (seed ${config.seed}, ${data.episode.path.length - 1} steps)…`);
}

function onState(state) {
  if (!page.replay || (state !== 'found' && state !== 'capped')) return;
  const run = page.controller.runs[0];
  const got = run.path();
  const want = page.replay.path;
  const same = got.length === want.length && got.every((v, i) => v === want[i]);
  page.controller.setSpeed(page.replay.speed);
  const note = page.replay.timed ? ' (this run used a time budget per move, so the machine’s speed changes the loops per move)' : '';
  showMessage(same ? `Replayed exactly: the path matches the imported episode (${got.length - 1} steps).` : `The replay differs from the imported episode (${got.length - 1} vs ${want.length - 1} steps)${note}.`);
  document.body.dataset.replay = same ? 'match' : 'differ';
  page.replay = null;
}

// ------------------------------------------------------------------ batch

async function runBatch() {
  const trials = Number($('batch-trials').value);
  const cap = Number($('batch-cap').value);
  if (!Number.isInteger(trials) || trials < 1 || trials > 100000) return showMessage('Batch trials must be an integer 1–100000.');
  if (!Number.isInteger(cap) || cap < 1 || cap > 1000000) return showMessage('Batch step cap must be an integer 1–1000000.');
  const core = coreConfig(page.config, { weights: weightsFromPaint(), keepTraces: 0 });
  core.step_cap = cap;
  try {
    page.wasm.checkConfig(core);
  } catch (err) {
    return showMessage(`Batch: ${err.message}`);
  }
  page.pool ??= new WorkerPool();
  $('batch-run').disabled = true;
  $('batch-stop').disabled = false;
  $('batch-summary').hidden = true;
  const t0 = performance.now();
  const progress = $('batch-progress');
  setText(progress, `Running ${trials} trials on ${page.pool.size} worker${page.pool.size > 1 ? 's' : ''}…`);
  document.body.dataset.batch = 'running';
  try {
    const results = await page.pool.run(core, page.config.seed, trials, (_, __, done) => {
      setText(progress, `${done} / ${trials} trials (${page.pool.size} workers, ${((performance.now() - t0) / 1000).toFixed(1)} s)`);
    });
    const secs = (performance.now() - t0) / 1000;
    page.lastBatch = results;
    showBatchSummary(page.wasm.summarizeTrials(Float64Array.from(results.flat())), secs);
    setText(progress, `${trials} trials in ${secs.toFixed(2)} s on ${page.pool.size} worker${page.pool.size > 1 ? 's' : ''} (${(trials / secs).toFixed(1)} trials/s).`);
    document.body.dataset.batch = 'done';
  } catch (err) {
    setText(progress, err.message === 'stopped' ? 'Stopped.' : `Batch failed: ${err.message}`);
    document.body.dataset.batch = err.message === 'stopped' ? 'stopped' : 'error';
  } finally {
    $('batch-run').disabled = false;
    $('batch-stop').disabled = true;
  }
}

function showBatchSummary(s, secs) {
  const ci = (m, d = 1) => `${m.mean.toFixed(d)} [${m.lo.toFixed(d)}, ${m.hi.toFixed(d)}]`;
  const rows = [
    ['Trials', String(s.trials)],
    ['Mean steps [95% CI]', ci(s.steps)],
    ['Mean optimal', s.optimal.mean.toFixed(1)],
    ['ASOO = mean(steps − optimal)', ci(s.asoo)],
    ['Mean steps/optimal', Number.isFinite(s.ratio.mean) ? ci(s.ratio, 2) : '—'],
    ['Mean steps / mean optimal', s.steps_over_mean_optimal.toFixed(2)],
    ['Median steps (q1–q3)', `${s.median_steps} (${s.q1_steps}–${s.q3_steps})`],
    ['Capped (not found)', String(s.capped)],
    ['Optimal = 0 (excluded from ratio)', String(s.zero_optimal)],
    ['Truncated rollouts', fmtInt(s.counters.truncated)],
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

// ------------------------------------------------------------------- boot

async function boot() {
  const { config, messages } = parseParams(location.search);
  page.config = config;
  if (config.prior === 'paint') {
    page.paint = decodePaint(config.paint, config.n);
    if (!page.paint || !page.paint.some((v) => v > 0)) {
      messages.push('Invalid paint: it does not describe a non-empty n×n grid. Using prior=gaussian.');
      page.config.prior = 'gaussian';
      page.paint = null;
    }
  }
  if (messages.length) showMessage(messages.join('\n'));
  try {
    page.wasm = await loadEngine();
  } catch (err) {
    document.body.dataset.state = 'error';
    $('state-badge').textContent = 'error';
    showMessage(`Could not load the wasm engine (www/pkg): ${err.message}. Run \`make build\` and reload.`);
    return;
  }
  setText('version', `v${page.wasm.version()}`);
  page.renderers = [new Renderer($('view-0')), new Renderer($('view-1'))];
  const ro = new ResizeObserver(() => {
    page.renderers.forEach((r) => r.fitToElement());
    page.controller?.requestDraw();
  });
  ro.observe($('view-0'));
  ro.observe($('view-1'));
  page.chart = new StepsChart($('chart'));
  page.session = new SearchSession(engineModule());
  page.controller = new Controller({
    session: page.session,
    spec: resetSpec,
    views: frameViews,
    onRuns,
    draw,
    onState: (s, prev) => {
      setText('state-badge', s);
      setText('play', s === 'running' ? 'Pause' : 'Play');
      if (page.controller) onState(s, prev);
    },
    onError: (err) => {
      // A trap in the search worker is handled by the session (a fresh worker
      // at the next reset); one in the page's own instance needs a reload.
      page.trapped = err instanceof WebAssembly.RuntimeError;
      showMessage(describeError(err));
      setText('state-badge', 'error');
      setText('play', 'Restart');
      for (let i = 0; i < 2; i++) drawNotice($(`view-${i}`), 'Stopped: see the message above. Restart to try again.');
    },
  });
  page.controller.setSpeed(config.speed);
  syncControls();
  bindControls();
  page.controller.reset({ autoplay: config.autoplay });
}

boot();
