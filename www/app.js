// The page's entry: it loads the engine and wires the modules together.
// State it holds: the engine config (edited only through the engine), the
// view parameters (speed, autoplay, race), and an import being replayed.
// Commands go one way, to the controller; frames come back as events.

import { loadEngine, engineModule, schema as engineSchema, describeError } from './shared/engine.js';
import { readUrl, writeUrl, raceOptions, splitView, readExperimentUrl, defaultExperiment, presetChoices } from './shared/url-state.js';
import { Controller } from './live/controller.js';
import { SearchSession } from './live/search-session.js';
import { Controls } from './live/controls.js';
import { ViewState } from './live/view-state.js';
import { Boards } from './live/boards.js';
import { Painter } from './live/paint.js';
import { Legend } from './live/panels/legend.js';
import { updateStats } from './live/panels/stats.js';
import { updateDecision } from './live/panels/decision.js';
import { StepsChart } from './live/steps-chart.js';
import { BatchPanel } from './workers/batch.js';
import { ExperimentsView } from './experiments/view.js';
import { bindShare, replayVerdict } from './live/share.js';
import { PRESETS } from './live/presets.js';
import { installTestHook } from './shared/test-hook.js';
import { $, setText, showMessage } from './shared/ui.js';

/** Least time between text-panel updates while running (ms): more is unreadable and costs the canvas frames. */
const PANEL_MS = 100;

async function boot() {
  let engine;
  try {
    engine = await loadEngine();
  } catch (err) {
    document.body.dataset.state = 'error';
    setText('state-badge', 'error');
    showMessage(`Could not load the wasm engine (www/pkg): ${err.message}. Run \`make build\` and reload.`);
    return;
  }
  const schema = engineSchema();
  const races = raceOptions(engine, schema);
  const app = { config: null, view: null, page: 'live', replay: null, trapped: false, runTime: 0, lastTs: 0, panelsTs: 0 };
  // The query describes the view shown: the live run's, or an experiment's.
  const split = splitView(location.search);
  app.page = split.view;
  const url = readUrl(engine, schema, app.page === 'live' ? split.query : '', races);
  url.messages.unshift(...split.messages);
  Object.assign(app, { config: url.config, view: url.view });
  const experimentList = engine.experimentList();
  const expUrl = app.page === 'experiments'
    ? readExperimentUrl(engine, schema, split.query, experimentList, presetChoices(engine, schema, experimentList))
    : { state: defaultExperiment(engine, schema, experimentList), messages: [] };
  url.messages.push(...expUrl.messages, ...(expUrl.conflict ? [expUrl.conflict] : []));
  setText('version', `v${engine.version()}`);

  const controller = new Controller({ session: new SearchSession(engineModule()) });
  const painter = new Painter(engine);
  const viewState = new ViewState(schema, { redraw: () => controller.dispatch({ type: 'view', view: viewState.frameView() }), traces: () => restart() });
  if (app.config.keep_traces > 0) viewState.setTraces(app.config.keep_traces);
  const legend = new Legend(schema, (p) => engine.paletteLut(p));
  const chart = new StepsChart($('chart'));
  const batch = new BatchPanel(engine, schema, () => app.config);
  const paintMode = () => app.config.prior === 'paint' && !$('click-start').checked;

  function updateUrl() {
    const q = app.page === 'experiments' ? experiments.query() : writeUrl(engine, app.config, app.view, { races });
    history.replaceState(null, '', `${location.pathname}${q ? `?${q}` : ''}`);
  }

  /** Shows the live view or the Experiments view; the live run pauses while experiments have the cores. */
  function showView(page) {
    app.page = page;
    document.body.dataset.view = page;
    $('live').hidden = page !== 'live';
    $('experiments').hidden = page !== 'experiments';
    $('tab-live').setAttribute('aria-pressed', String(page === 'live'));
    $('tab-experiments').setAttribute('aria-pressed', String(page === 'experiments'));
    if (page === 'experiments' && controller.state === 'running') controller.dispatch({ type: 'pause' });
    else controller.dispatch({ type: 'redraw' });
    if (page === 'live' && app.deferredPlay) {
      // Opened in the Experiments view with autoplay: the live run starts when first shown.
      app.deferredPlay = false;
      controller.whenReady().then(() => controller.dispatch({ type: 'play' }));
    }
    updateUrl();
  }

  /** Opens an engine config in the live view (a point of an experiment). */
  function openConfig(config, note) {
    try {
      app.config = engine.checkConfig(config);
    } catch (err) {
      showMessage(`Could not open that configuration: ${err.message}`);
      return Promise.resolve(false);
    }
    if (app.config.prior === 'paint') painter.load(app.config);
    app.view = { ...app.view, race: '' };
    app.deferredPlay = false;
    showView('live');
    sync();
    updateUrl();
    const ready = restart(true);
    showMessage(note);
    return ready;
  }

  function sync() {
    const text = new Map(engine.configParams(app.config, true));
    controls.sync({ config: app.config, text, view: app.view, applicable: new Set(engine.applicable(app.config)), preset: engine.presetOf(app.config) ?? null });
  }

  /** The engine configs of the runs: the config, and the race opponent's. */
  function runConfigs() {
    const k = String(viewState.keepTraces());
    viewState.usedTraces(Number(k));
    const main = engine.setParam(app.config, 'keep_traces', k);
    const race = races.find((r) => r.id === app.view.race);
    if (!race?.pairs.length) return [main];
    return [main, race.pairs.reduce((c, [key, v]) => engine.setParam(c, key, v), main)];
  }

  /** Fresh runs from the current config (same seed). */
  function restart(autoplay = controller.state === 'running' || app.view.autoplay) {
    if (app.trapped) {
      // A trap in the page's own wasm instance (not the search worker's,
      // which is replaced at the next reset) leaves it untrustworthy.
      location.reload();
      return Promise.resolve(false);
    }
    app.replay = null;
    if (controller.state !== 'error') showMessage('');
    return controller.dispatch({ type: 'reset', configs: runConfigs(), autoplay });
  }

  /** Applies one edited parameter through the engine; a bad value keeps the old one. */
  function onParam(key, raw) {
    try {
      let cfg = app.config;
      if (key === 'prior' && raw === 'paint' && !app.config.paint) {
        cfg = engine.setParam(cfg, 'paint', painter.blob(cfg.n));
        $('click-start').checked = false;
      }
      app.config = engine.setParam(cfg, key, raw);
    } catch (err) {
      showMessage(`Invalid ${key} ${JSON.stringify(String(raw).slice(0, 40))}: ${err.message}. Keeping ${key}=${engine.configParams(app.config, true).find(([k]) => k === key)?.[1]}.`);
      sync();
      return;
    }
    if (app.config.prior === 'paint') painter.load(app.config);
    sync();
    updateUrl();
    restart();
  }

  function applyPreset(name) {
    const p = PRESETS[name];
    app.config = engine.parseParams(p.pairs).config;
    app.view = { ...app.view, ...p.view };
    if (name === 'teaching') viewState.teaching();
    controller.dispatch({ type: 'speed', speed: app.view.speed });
    sync();
    updateUrl();
    restart(true).then(() => p.note && showMessage(p.note));
  }

  const controls = new Controls({
    schema,
    races,
    onParam,
    onRace: (id) => {
      app.view.race = id;
      updateUrl();
      restart();
    },
    onSpeed: (speed) => {
      app.view.speed = speed;
      controller.dispatch({ type: 'speed', speed });
      updateUrl();
    },
    onPlayback: (action) => {
      if (action === 'restart') restart(app.view.autoplay);
      else if (action === 'newSeed') onParam('seed', String(crypto.getRandomValues(new Uint32Array(1))[0]));
      else if (action === 'toggle' && controller.state === 'error') restart(true);
      else controller.dispatch({ type: action });
    },
  });

  const boards = new Boards({
    onClick: (idx) => $('click-start').checked && onParam('start', `${(idx % app.config.n) + 1},${Math.floor(idx / app.config.n) + 1}`),
    painting: paintMode,
    onStroke: (idx, first) => {
      if (first) controller.dispatch({ type: 'pause' });
      painter.stamp(idx, Number($('brush').value), $('erase').checked);
      controller.dispatch({ type: 'redraw' });
    },
    onStrokeEnd: () => {
      painter.preview = null;
      if (!painter.painted()) showMessage('The painted prior is empty: paint some cells (the target is drawn from it).');
      else onParam('paint', painter.encode());
    },
    onResize: () => controller.dispatch({ type: 'redraw' }),
  });

  controller.on('runs', (runs) => {
    app.runTime = 0;
    chart.reset(runs.map((r, i) => (runs.length > 1 ? `${i === 0 ? 'A' : 'B'}: ${r.label}` : r.label)));
    boards.setup(runs);
    controls.setDeliberates(runs[0].deliberates);
  });
  controller.on('state', (s) => {
    setText('state-badge', s);
    setText('play', s === 'running' ? 'Pause' : 'Play');
    if (app.replay && (s === 'found' || s === 'capped')) finishReplay(controller.runs[0].path());
  });
  controller.on('error', (err) => {
    app.trapped = err instanceof WebAssembly.RuntimeError;
    showMessage(describeError(err));
    setText('state-badge', 'error');
    setText('play', 'Restart');
    boards.notice('Stopped: see the message above. Restart to try again.');
  });
  controller.on('frame', ({ state, meter, runs }) => {
    const ts = performance.now();
    if (state === 'running' && app.lastTs) app.runTime += Math.min(0.25, (ts - app.lastTs) / 1000);
    app.lastTs = state === 'running' ? ts : 0;
    if (!runs.length) return;
    const opts = viewState.options();
    const requested = viewState.layerRequests();
    if (boards.draw(runs, requested, opts, painter.preview)) controller.dispatch({ type: 'redraw' });
    if (state === 'running' && ts - app.panelsTs < PANEL_MS) return;
    app.panelsTs = ts;
    updateStats(runs, meter, opts);
    updateDecision(runs[0]);
    // A plan made in slices can be stepped a slice at a time.
    controls.setDeliberates(runs[0].deliberates || !!runs[0].frame.planning);
    legend.update(runs[0].drawnLayers(requested));
    const known = (r) => r.frame.status === 'found' || opts.reveal;
    chart.push(app.runTime, runs.map((r) => r.frame.steps), runs.map((r) => (known(r) ? r.optimal : null)), state !== 'running');
  });

  function finishReplay(got) {
    const { path: want, speed, timed } = app.replay;
    app.replay = null;
    app.view.speed = speed;
    controller.dispatch({ type: 'speed', speed });
    const { same, message } = replayVerdict(got, want, timed);
    showMessage(message);
    document.body.dataset.replay = same ? 'match' : 'differ';
  }

  $('teaching').addEventListener('click', () => applyPreset('teaching'));
  $('defaults').addEventListener('click', () => applyPreset('default'));
  $('paint-clear').addEventListener('click', () => {
    painter.clear(app.config.n);
    showMessage('Paint a prior on the grid (drag with the mouse or a finger).');
  });
  bindShare({
    link: () => {
      updateUrl();
      return location.href;
    },
    name: () => `torus-${app.config.searcher}-n${app.config.n}-seed${app.config.seed}`,
    canvases: () => boards.canvases(controller.runs.length),
    episode: async () => {
      const runs = await controller.dispatch({ type: 'export' });
      return runs && { engineVersion: engine.version(), query: writeUrl(engine, app.config, app.view, { full: true, races }), runs };
    },
    replay: async (query, path) => {
      const got = readUrl(engine, schema, query, races);
      if (got.messages.length) throw new Error(got.messages.join(' '));
      Object.assign(app, { config: got.config, view: got.view });
      if (app.config.prior === 'paint') painter.load(app.config);
      sync();
      updateUrl();
      controller.dispatch({ type: 'speed', speed: 'max' });
      const ready = restart(true);
      // Set after restart() clears it, before the replay can end.
      app.replay = { path, speed: got.view.speed, timed: got.config.ms !== null };
      showMessage(`Replaying the imported episode (seed ${got.config.seed}, ${path.length - 1} steps)…`);
      await ready;
    },
  });

  const experiments = new ExperimentsView({
    engine,
    schema,
    state: expUrl.state,
    module: engineModule(),
    onUrl: () => app.page === 'experiments' && updateUrl(),
    onOpen: (config, note) => openConfig(config, note),
  });
  $('exp-from-live').addEventListener('click', () => experiments.useLiveConfig(engine.configParams(app.config, false)));
  $('tab-live').addEventListener('click', () => showView('live'));
  $('tab-experiments').addEventListener('click', () => showView('experiments'));

  if (app.config.prior === 'paint') painter.load(app.config);
  installTestHook({ controller, engine, batch, experiments, showView });
  if (url.messages.length) showMessage(url.messages.join('\n'));
  controller.dispatch({ type: 'speed', speed: app.view.speed });
  controller.dispatch({ type: 'view', view: viewState.frameView() });
  sync();
  // In the Experiments view the live run waits (it would take a core from the workers).
  app.deferredPlay = app.view.autoplay && app.page !== 'live';
  showView(app.page);
  controller.dispatch({ type: 'reset', configs: runConfigs(), autoplay: app.view.autoplay && app.page === 'live' });
}

boot();
