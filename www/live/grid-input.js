// The pointer on the boards: a click sets the cell parameter the form's
// grid toggle names (the start by default); with a painting's toggle on, a
// drag paints (the run pauses, the preview shows) and the stroke's end
// sends the painting to the engine.

import { showMessage } from '../shared/ui.js';

/**
 * The Boards' pointer callbacks.
 * @param {object} o
 * @param {object} o.form        the ConfigForm (which parameter the grid edits, the brush)
 * @param {object} o.painter     the Painter
 * @param {object} o.live        the LiveState (edit(), config)
 * @param {object} o.controller  the playback state machine
 */
export function gridInput({ form, painter, live, controller }) {
  return {
    onClick: (idx) => {
      const n = live.config.n;
      if (form.pick && form.pickKind() !== 'paint') live.edit(form.pick, `${(idx % n) + 1},${Math.floor(idx / n) + 1}`);
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
