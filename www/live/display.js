// What the live view shows of the controller's events (with the found
// card's next steps and the first-visit tour): fresh runs set up the
// boards, the heat switch and the chart; each frame draws the boards
// (asking for another animation frame while something on them moves) and,
// at most every PANEL_MS while running, the text panels, the legend, the
// explanation, the line under the board and the chart; the board's
// description for screen readers at most once a second; the state shows in
// the badge and the play button; an error, in the message.

import { describeError } from '../shared/engine.js';
import { $, setText, showMessage } from '../shared/ui.js';
import { updateStats, describeRun } from './panels/stats.js';
import { updateDecision } from './panels/decision.js';
import { updateExplanation } from './panels/explain.js';
import { Legend } from './panels/legend.js';
import { StepsChart } from './steps-chart.js';
import { reducedMotion } from './motion.js';
import { bindFound } from './panels/found.js';
import { Tour } from './tour.js';
import { updateNarration } from './panels/narrate.js';
import { TimelineBar } from './timeline-bar.js';
import { TreePanel } from './tree-panel.js';
import { BranchOffer } from './branch-offer.js';

/** Least time between text-panel updates while running (ms): more is unreadable and costs the canvas frames. */
const PANEL_MS = 100;
/** Least time between updates of the board's text description while running (ms). */
const DESCRIBE_MS = 1000;

/**
 * Each board's title: its label alone, or in a race "A: …" and "B: …"
 * naming what differs between the two (the engine's configDifferences),
 * with the searcher's label when the searchers differ.
 */
export function raceTitles(engine, runs) {
  if (runs.length < 2) return runs.map((r) => r.label);
  const diffs = engine.configDifferences(runs[0].config, runs[1].config).filter((d) => d.key !== 'keep_traces');
  // The searcher's label already names these.
  const named = new Set(['searcher', 'variant', 'rollout', 'loops']);
  const searcherDiffers = diffs.some((d) => d.key === 'searcher' || d.key === 'variant');
  return runs.map((r, i) => {
    const side = i === 0 ? 'a' : 'b';
    const what = diffs.filter((d) => !searcherDiffers || !named.has(d.key)).map((d) => `${d.key}=${shortValue(d[side])}`).join(' ');
    const text = searcherDiffers ? [r.label, what].filter(Boolean).join(' · ') : what ? `${what} — ${r.label}` : r.label;
    return `${i === 0 ? 'A' : 'B'}: ${text}`;
  });
}

/** A value as text, long decimals cut to 4 significant digits. */
const shortValue = (v) => (/^-?\d+\.\d{5,}$/.test(v) ? String(Number(Number(v).toPrecision(4))) : v);

/**
 * @param {object} o
 * @param {object} o.engine, o.schema   the wasm module (palettes) and its schema (layers)
 * @param {object} o.controller   the playback state machine (its events)
 * @param {object} o.live, o.races   the LiveState and the race options (the next steps after the end)
 * @param {object} o.boards, o.viewState, o.painter, o.controls   what it draws and updates
 */
export function bindDisplay({ engine, schema, races, controller, live, boards, viewState, painter, controls }) {
  bindFound({ controller, live, races });
  const legend = new Legend(schema, (p) => engine.paletteLut(p), $('legend'));
  const chart = new StepsChart($('chart'));
  const timelineBar = new TimelineBar((action, arg) => live.playback(action, arg));
  const tree = new TreePanel({
    controller, boards, lut: engine.paletteLut('viridis'), link: live.view.tree,
    onLink: (text) => live.change({ view: { tree: text }, restart: false }),
  });
  controller.on('message', (text) => showMessage(text));
  new BranchOffer({ engine, controller, live });
  const drawn = new Set(); // marks drawn since the last legend update
  let runTime = 0; // seconds spent running, the chart's x axis
  let lastTs = 0;
  let panelsTs = 0;
  let describedTs = -Infinity;
  controller.on('runs', (runs) => {
    runTime = 0;
    const titles = raceTitles(engine, runs);
    chart.reset(titles);
    tree.reset(runs);
    boards.setup(runs, titles);
    legend.reset();
    drawn.clear();
    describedTs = -Infinity;
    controls.setDeliberates(runs[0].deliberates);
    const heat = viewState.heat();
    viewState.setAvailable(runs[0].layer_names);
    if (viewState.heat() !== heat) controller.dispatch({ type: 'view', view: viewState.frameView() });
  });
  controller.on('state', (s, prev) => {
    setText('state-badge', s);
    setText('play', s === 'running' ? 'Pause' : 'Play');
    if (s !== prev) describedTs = -Infinity;
  });
  controller.on('error', (err) => {
    showMessage(describeError(err));
    setText('state-badge', 'error');
    setText('play', 'Restart');
    boards.notice('Stopped: see the message. Restart to try again.');
  });
  controller.on('frame', ({ state, meter, runs, timeline }) => {
    const ts = performance.now();
    if (state === 'running' && lastTs) runTime += Math.min(0.25, (ts - lastTs) / 1000);
    lastTs = state === 'running' ? ts : 0;
    if (!runs.length) return;
    const opts = viewState.options();
    const requested = viewState.layerRequests();
    const { pending, animating } = boards.draw(runs, requested, opts, { preview: painter.preview, now: ts, live: state === 'running', still: reducedMotion() });
    const growing = tree.update(runs, { running: state === 'running', now: ts, still: reducedMotion() });
    if (pending || animating || growing) controller.dispatch({ type: 'animate' });
    for (const m of boards.drawnMarks(0)) drawn.add(m);
    // The board's description for screen readers changes at most once a second.
    if (ts - describedTs >= (state === 'running' ? DESCRIBE_MS : 0)) {
      describedTs = ts;
      setText('board-desc', describeRun(runs[0]));
    }
    timelineBar.update(timeline, runs[0].deliberates);
    if (state === 'running' && ts - panelsTs < PANEL_MS) return;
    panelsTs = ts;
    updateNarration(runs[0]);
    setText('view-desc', describeRun(runs[0]));
    updateStats(runs, meter, opts);
    updateDecision(runs[0]);
    // A plan made in slices can be stepped a slice at a time.
    controls.setDeliberates(runs[0].deliberates || !!runs[0].frame.planning);
    const heat = runs[0].drawnLayers(requested).find((l) => !opts.masks.has(l.layer));
    legend.update(heat && { ...heat, flat: heat.max > 0 && heat.min_nonzero === heat.max }, drawn);
    drawn.clear();
    updateExplanation(runs[0], viewState.heat());
    const known = (r) => r.frame.status === 'found' || opts.reveal;
    chart.push(runTime, runs.map((r) => r.frame.steps), runs.map((r) => (known(r) ? r.optimal : null)), state !== 'running');
  });
  // After the drawing above: the tour points at where this frame drew the searcher.
  new Tour({ controller, boards });
  return { tree };
}
