// The pointer on the boards. A click or tap never changes the run: it
// selects a cell and says what is there. Setting a cell parameter is an
// explicit mode: the form's "Pick on grid" toggle (one click, then the mode
// ends) or Shift+click for the start. With a painting's toggle on, a drag
// paints (the run pauses, the preview shows) and the stroke's end sends the
// painting to the engine. Outside those modes a swipe on a touch screen
// scrolls the page (the canvases' touch-action follows the mode).

import { setText, showMessage } from '../shared/ui.js';
import { cellText } from './panels/stats.js';

/** What a selected cell is, from the run's data: "(3, 4): the start · walked at step 2". */
export function inspectText(run, idx, showTarget) {
  const facts = [];
  if (idx === run.start) facts.push('the start');
  if (idx === run.frame.position) facts.push('the searcher is here');
  if (showTarget && idx === run.target) facts.push('the target');
  const path = run.pathView();
  let first = -1;
  let times = 0;
  for (let i = 0; i < run.pathLen; i++) {
    if (path[i] !== idx) continue;
    if (first < 0) first = i;
    times++;
  }
  if (first > 0) facts.push(`walked at step ${first}${times > 1 ? ` (${times} visits)` : ''}`);
  else if (first < 0) facts.push('not walked yet');
  return `${cellText(idx, run.n)}: ${facts.join(' · ')}`;
}

/**
 * The Boards' pointer callbacks.
 * @param {object} o
 * @param {object} o.form        the ConfigForm (which parameter the grid edits, the brush)
 * @param {object} o.painter     the Painter
 * @param {object} o.live        the LiveState (edit(), config)
 * @param {object} o.controller  the playback state machine
 * @param {() => object} o.boards  the Boards (made after these callbacks)
 * @param {() => boolean} o.revealed  whether the target is shown
 */
export function gridInput({ form, painter, live, controller, boards, revealed }) {
  form.onPickChange = (kind) => {
    for (const c of document.querySelectorAll('canvas.view')) c.dataset.pointer = kind ?? 'inspect';
  };
  const cellParam = (idx) => `${(idx % live.config.n) + 1},${Math.floor(idx / live.config.n) + 1}`;
  return {
    onClick: (idx, board, e) => {
      const b = boards();
      if (form.pick && form.pickKind() !== 'paint') {
        const key = form.pick;
        form.clearPick();
        live.edit(key, cellParam(idx));
      } else if (e.shiftKey && board === 0 && form.startKey) {
        live.edit(form.startKey, cellParam(idx));
      } else {
        b.selected = b.selected === idx ? -1 : idx;
        const run = controller.runs[0];
        setText('inspect', b.selected >= 0 && run ? inspectText(run, idx, revealed() || run.status() === 'found') : '');
        controller.dispatch({ type: 'animate' });
      }
    },
    painting: () => form.pickKind() === 'paint',
    onStroke: (idx, first) => {
      if (first) controller.dispatch({ type: 'pause' });
      const { radius, erase } = form.brush(form.pick);
      painter.stamp(idx, radius, erase);
      controller.dispatch({ type: 'redraw' });
    },
    onStrokeEnd: () => {
      painter.preview = null;
      if (!painter.painted()) showMessage('The painted prior is empty: paint some cells (the target is drawn from it).');
      else live.edit(form.pick, painter.encode());
    },
    onResize: () => controller.dispatch({ type: 'redraw' }),
  };
}

/** A painting's Clear button: an empty grid to paint on (the run keeps its painting until the next stroke). */
export function clearPainting(painter, live) {
  painter.clear(live.config.n);
  showMessage('Paint a prior on the grid (drag with the mouse or a finger).');
}
