// The boards: one canvas per run (two in a race), each drawn by a Renderer
// from the run's latest frame and the view options, and the pointer on
// them (clicking a cell, painting strokes).

import { $, setText } from '../shared/ui.js';
import { Renderer, drawNotice } from './renderer.js';

export class Boards {
  /**
   * @param {object} o
   * @param {(idx) => void} o.onClick            a cell clicked (not painting)
   * @param {() => boolean} o.painting            true while the pointer paints
   * @param {(idx, first) => void} o.onStroke     a cell under a painting stroke
   * @param {() => void} o.onStrokeEnd            the stroke ended
   * @param {() => void} o.onResize               the boards changed size
   */
  constructor({ onClick, painting, onStroke, onStrokeEnd, onResize }) {
    this.renderers = [0, 1].map((i) => new Renderer($(`view-${i}`)));
    const ro = new ResizeObserver(() => {
      this.fit();
      onResize();
    });
    this.renderers.forEach((r, i) => {
      ro.observe(r.canvas);
      this.bindPointer(r, i, { onClick, painting, onStroke, onStrokeEnd });
    });
  }

  fit() {
    this.renderers.forEach((r) => r.fitToElement());
  }

  bindPointer(renderer, i, { onClick, painting, onStroke, onStrokeEnd }) {
    const canvas = renderer.canvas;
    let stroke = false;
    let last = -1;
    canvas.addEventListener('pointerdown', (e) => {
      const idx = renderer.cellAt(e.clientX, e.clientY);
      if (idx < 0) return;
      if (painting()) {
        stroke = true;
        last = idx;
        canvas.setPointerCapture(e.pointerId);
        onStroke(idx, true);
      } else onClick(idx, i);
    });
    canvas.addEventListener('pointermove', (e) => {
      if (!stroke) return;
      const idx = renderer.cellAt(e.clientX, e.clientY);
      if (idx < 0 || idx === last) return;
      last = idx;
      onStroke(idx, false);
    });
    const end = () => {
      if (!stroke) return;
      stroke = false;
      onStrokeEnd();
    };
    canvas.addEventListener('pointerup', end);
    canvas.addEventListener('pointercancel', end);
  }

  /** Shows one board, or two side by side with titles and the scoreboard. */
  setup(runs) {
    const race = runs.length > 1;
    $('boards').classList.toggle('race', race);
    $('board-1').hidden = !race;
    $('scoreboard').hidden = !race;
    runs.forEach((r, i) => {
      setText($(`board-${i}`).querySelector('.board-title'), race ? `${i === 0 ? 'A' : 'B'}: ${r.label}` : '');
    });
    requestAnimationFrame(() => this.fit());
  }

  /**
   * Draws each run: its layers (those the frame request asked for and the
   * run has), path, traces, markers and decision arrows. `preview` replaces
   * the main board's prior while a prior is being painted. Returns true
   * while a long path is still being drawn (draw again next frame).
   */
  draw(runs, requested, opts, preview = null) {
    let more = false;
    runs.forEach((run, i) => {
      const f = run.frame;
      const running = f.status === 'running';
      const layers = run.drawnLayers(requested);
      if (preview && i === 0) {
        // A preview changes every stroke: never reuse an upload for it (no key).
        const at = layers.findIndex((l) => l.layer === 'prior');
        const rgba = new Uint8ClampedArray(preview.buffer, preview.byteOffset, preview.length);
        if (at >= 0) layers[at] = { rgba };
        else layers.unshift({ rgba });
      }
      more =
        this.renderers[i].draw({
          n: run.n,
          layers,
          path: opts.path ? run.pathView() : null,
          pathLen: run.pathLen,
          pathKey: run,
          start: run.start,
          position: f.position,
          target: run.target,
          showTarget: f.status === 'found' || opts.reveal,
          rv: run.config.rv,
          rollouts: opts.rollouts ? run.traces : [],
          practice: opts.practice && running ? run.practice : -1,
          intent: opts.intent && running ? run.intent : null,
          decision:
            opts.arrows && f.decision && running ? { visits: f.decision.children.map((c) => c.selected), leading: f.decision.leading } : null,
          grid: opts.grid,
          tiling: opts.tiling,
        }) || more;
    });
    return more;
  }

  /** Dims every board with a notice. */
  notice(text) {
    this.renderers.forEach((r) => drawNotice(r.canvas, text));
  }

  /** The canvases of the first `count` boards (for export). */
  canvases(count) {
    return this.renderers.slice(0, count).map((r) => r.canvas);
  }

  /** The cell under a pointer on board `i`, or −1. */
  cellAt(i, x, y) {
    return this.renderers[i].cellAt(x, y);
  }
}
