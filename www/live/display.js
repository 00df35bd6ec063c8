// What the live view shows of the controller's events (it makes the legend
// and the steps chart): fresh runs set up the boards and the chart; each frame draws the boards and (at most every
// PANEL_MS while running) the text panels, legend and chart; the state
// shows in the badge and the play button; an error, in the message.

import { describeError } from '../shared/engine.js';
import { $, setText, showMessage } from '../shared/ui.js';
import { updateStats } from './panels/stats.js';
import { updateDecision } from './panels/decision.js';
import { Legend } from './panels/legend.js';
import { StepsChart } from './steps-chart.js';

/** Least time between text-panel updates while running (ms): more is unreadable and costs the canvas frames. */
const PANEL_MS = 100;

/**
 * @param {object} o
 * @param {object} o.engine, o.schema   the wasm module (palettes) and its schema (layers)
 * @param {object} o.controller   the playback state machine (its events)
 * @param {object} o.boards, o.viewState, o.painter, o.controls   what it draws and updates
 */
export function bindDisplay({ engine, schema, controller, boards, viewState, painter, controls }) {
  const legend = new Legend(schema, (p) => engine.paletteLut(p));
  const chart = new StepsChart($('chart'));
  let runTime = 0; // seconds spent running, the chart's x axis
  let lastTs = 0;
  let panelsTs = 0;
  controller.on('runs', (runs) => {
    runTime = 0;
    chart.reset(runs.map((r, i) => (runs.length > 1 ? `${i === 0 ? 'A' : 'B'}: ${r.label}` : r.label)));
    boards.setup(runs);
    controls.setDeliberates(runs[0].deliberates);
  });
  controller.on('state', (s) => {
    setText('state-badge', s);
    setText('play', s === 'running' ? 'Pause' : 'Play');
  });
  controller.on('error', (err) => {
    showMessage(describeError(err));
    setText('state-badge', 'error');
    setText('play', 'Restart');
    boards.notice('Stopped: see the message above. Restart to try again.');
  });
  controller.on('frame', ({ state, meter, runs }) => {
    const ts = performance.now();
    if (state === 'running' && lastTs) runTime += Math.min(0.25, (ts - lastTs) / 1000);
    lastTs = state === 'running' ? ts : 0;
    if (!runs.length) return;
    const opts = viewState.options();
    const requested = viewState.layerRequests();
    if (boards.draw(runs, requested, opts, painter.preview)) controller.dispatch({ type: 'redraw' });
    if (state === 'running' && ts - panelsTs < PANEL_MS) return;
    panelsTs = ts;
    updateStats(runs, meter, opts);
    updateDecision(runs[0]);
    // A plan made in slices can be stepped a slice at a time.
    controls.setDeliberates(runs[0].deliberates || !!runs[0].frame.planning);
    legend.update(runs[0].drawnLayers(requested));
    const known = (r) => r.frame.status === 'found' || opts.reveal;
    chart.push(runTime, runs.map((r) => r.frame.steps), runs.map((r) => (known(r) ? r.optimal : null)), state !== 'running');
  });
}
