// The page's entry: loads the engine and wires the modules together
// (www/README.md says what each does). No logic of its own.

import { loadEngine, engineModule, schema as engineSchema } from './shared/engine.js';
import { readPage, raceOptions } from './shared/url-state.js';
import { PageViews } from './shared/views.js';
import { installTestHook } from './shared/test-hook.js';
import { $, showBuild, showFatal } from './shared/ui.js';
import { Controller } from './live/controller.js';
import { SearchSession } from './live/search-session.js';
import { LiveState } from './live/live-state.js';
import { ConfigForm } from './live/config-form.js';
import { Controls } from './live/controls.js';
import { ViewState } from './live/view-state.js';
import { Boards } from './live/boards.js';
import { Painter } from './live/paint.js';
import { gridInput, clearPainting } from './live/grid-input.js';
import { bindDisplay } from './live/display.js';
import { bindReplay } from './live/replay.js';
import { bindPresets } from './live/presets.js';
import { autoplayAllowed } from './live/motion.js';
import { BatchPanel } from './workers/batch.js';
import { ExperimentsView } from './experiments/view.js';

async function boot() {
  const engine = await loadEngine().catch((err) => showFatal(`Could not load the wasm engine (www/pkg): ${err.message}. Run \`make build\` and reload.`));
  if (!engine) return;
  const schema = engineSchema();
  const races = raceOptions(engine, schema);
  const start = readPage(engine, schema, location.search, races);
  const autoplay = start.view.autoplay && autoplayAllowed(location.search); // (reduced motion: a Play button)
  showBuild(engine);
  const controller = new Controller({ session: new SearchSession(engineModule()) });
  const painter = new Painter(engine);
  const form = new ConfigForm({ schema, onParam: (key, raw) => live.edit(key, raw), onPaintClear: () => clearPainting(painter, live) });
  const viewState = new ViewState(schema, { redraw: () => (controller.dispatch({ type: 'view', view: viewState.frameView() }), views.updateUrl()), traces: () => (live.tracesChanged(), views.updateUrl()) });
  const controls = new Controls({ races, onRace: (race) => live.change({ view: race }), onSpeed: (speed) => live.change({ view: { speed }, restart: false }), onPlayback: (action) => live.playback(action) });
  const views = new PageViews({ page: start.page, controller, query: { live: () => live.query(), experiments: () => experiments.query() }, autoplay });
  const live = new LiveState({ engine, schema, races, controller, painter, form, controls, viewState, config: start.config, view: start.view, onUrl: () => views.updateUrl() });
  const boards = new Boards(gridInput({ form, painter, live, controller, boards: () => boards, revealed: () => viewState.options().reveal }));
  const { tree } = bindDisplay({ engine, schema, races, controller, live, boards, viewState, painter, controls });
  bindReplay({ engine, schema, races, controller, live, boards, link: () => (views.updateUrl(), location.href) });
  bindPresets({ engine, schema, live, viewState });
  const batch = new BatchPanel(engine, schema, () => live.config, () => live.opponent());
  const experiments = new ExperimentsView({
    engine, schema, state: start.experiment, module: engineModule(),
    onUrl: () => views.page === 'experiments' && views.updateUrl(),
    onOpen: (config, note) => live.open(config, note, () => views.show('live', { play: false })),
  });
  $('exp-from-live').addEventListener('click', () => experiments.useLiveConfig(engine.configParams(live.config, false)));

  installTestHook({ controller, engine, batch, experiments, boards, tree, showView: (v) => views.show(v) });
  controller.dispatch({ type: 'view', view: viewState.frameView() });
  views.show(start.page);
  live.change({ view: start.view, autoplay: autoplay && start.page === 'live', note: start.messages.join('\n') }); // (the Experiments view needs the cores)
}

boot();
