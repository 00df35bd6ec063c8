// The boards: one canvas per run (two in a race), each drawn by a Renderer
// from the run's latest frame, the view options and the motion state (the
// gliding searcher, the trails on the board, the found pulse), and the
// pointer on them. A click or tap only selects a cell (or, in an explicit
// mode, sets one); a drag paints only in painting mode, and otherwise a
// swipe scrolls the page.

import { $, setText } from '../shared/ui.js';
import { Renderer, drawNotice } from './renderer.js';
import { Glide, Pulse, pointAt } from './motion.js';
import { TraceKeeper } from './trails.js';
import { cellsOf } from './panels/narrate.js';

/** A loop stepped phase by phase reveals its rollout one of the engine's chunks per this many ms. */
const REVEAL_MS = 30;

/** A pointer that moves further than this (CSS px) between down and up is a swipe, not a tap. */
const TAP_SLOP = 10;

export class Boards {
  /**
   * @param {object} o
   * @param {(idx, i, event) => void} o.onClick  a cell clicked or tapped (not painting)
   * @param {() => boolean} o.painting            true while the pointer paints
   * @param {(idx, first) => void} o.onStroke     a cell under a painting stroke
   * @param {() => void} o.onStrokeEnd            the stroke ended
   * @param {() => void} o.onResize               the boards changed size
   */
  constructor({ onClick, painting, onStroke, onStrokeEnd, onResize }) {
    this.renderers = [0, 1].map((i) => new Renderer($(`view-${i}`)));
    this.motion = [0, 1].map(() => ({ glide: new Glide(), trails: new TraceKeeper(), pulse: new Pulse() }));
    this.selected = -1;
    this.treeBoard = 0; // the board whose tree the tree view shows (tree-panel.js)
    this.treeLine = null; // cells of the tree node in focus, drawn on that board
    this.onHoverCell = null; // (cell | −1) => void: the pointer over that board's cells
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
    let down = null; // where a possible tap began
    canvas.addEventListener('pointerdown', (e) => {
      const idx = renderer.cellAt(e.clientX, e.clientY);
      if (idx < 0) return;
      if (painting()) {
        stroke = true;
        last = idx;
        canvas.setPointerCapture(e.pointerId);
        onStroke(idx, true);
      } else down = { x: e.clientX, y: e.clientY, idx };
    });
    let hovered = -1;
    const hover = (idx) => {
      if (i !== this.treeBoard || idx === hovered) return;
      hovered = idx;
      this.onHoverCell?.(idx);
    };
    canvas.addEventListener('pointerleave', () => hover(-1));
    canvas.addEventListener('pointermove', (e) => {
      if (!stroke) hover(renderer.cellAt(e.clientX, e.clientY));
      if (!stroke) return;
      const idx = renderer.cellAt(e.clientX, e.clientY);
      if (idx < 0 || idx === last) return;
      last = idx;
      onStroke(idx, false);
    });
    const end = (e) => {
      if (down && e.type === 'pointerup' && Math.hypot(e.clientX - down.x, e.clientY - down.y) <= TAP_SLOP) onClick(down.idx, i, e);
      down = null;
      if (!stroke) return;
      stroke = false;
      onStrokeEnd();
    };
    canvas.addEventListener('pointerup', end);
    // A swipe that scrolls the page cancels the pointer: no tap.
    canvas.addEventListener('pointercancel', end);
  }

  /** Marks the canvases for the pointer's mode: painting or picking takes the touch, else a swipe scrolls. */
  setPointerMode(mode) {
    for (const r of this.renderers) r.canvas.dataset.pointer = mode;
  }

  /** Shows one board, or two side by side with `titles` and the scoreboard. */
  setup(runs, titles = runs.map((r) => r.label)) {
    const race = runs.length > 1;
    $('boards').classList.toggle('race', race);
    $('board-1').hidden = !race;
    $('scoreboard').hidden = !race;
    this.selected = -1;
    runs.forEach((r, i) => {
      setText($(`board-${i}`).querySelector('.board-title'), race ? titles[i] : '');
      this.motion[i].trails.reset();
    });
    requestAnimationFrame(() => this.fit());
  }

  /**
   * Draws each run at time `now`: its heat layer (and the searched hatch),
   * path, trails, marks and decision arrows. `preview` replaces the main
   * board's prior while a prior is being painted; `live` says the search
   * runs on its own; `still` is reduced motion. Returns { pending } (a long
   * path still being drawn) and { animating } (the searcher gliding, trails
   * fading or the found pulse playing): either asks for another frame.
   */
  draw(runs, requested, opts, { preview = null, now = performance.now(), live = false, still = false } = {}) {
    let pending = false;
    let animating = false;
    runs.forEach((run, i) => {
      const scene = this.scene(run, i, requested, opts, { now, live, still });
      if (preview && i === 0) {
        // A preview changes every stroke: never reuse an upload for it (no key).
        scene.layers = [{ rgba: new Uint8ClampedArray(preview.buffer, preview.byteOffset, preview.length) }];
      }
      pending = this.renderers[i].draw(scene) || pending;
      const m = this.motion[i];
      animating = animating || m.glide.moving() || m.pulse.playing(now) || (live && m.trails.busy()) || scene.revealing;
    });
    return { pending, animating };
  }

  /** The renderer's scene of one run (see Renderer.draw). */
  scene(run, i, requested, opts, { now, live, still }) {
    const f = run.frame;
    const running = f.status === 'running';
    const found = f.status === 'found';
    const m = this.motion[i];
    const drawn = run.drawnLayers(requested);
    const mask = drawn.find((l) => opts.masks.has(l.layer));
    const path = run.pathView();
    const shown = m.glide.at(run, run.pathLen - 1, now, still);
    m.trails.update(opts.rollouts ? run.traces : [], run.practice, now, { live: live && running, still });
    // A loop stepped phase by phase: its own selection and rollout instead of the kept trails.
    const loop = running ? this.loopScene(run, m, now, still) : null;
    return {
      revealing: !!loop?.animating,
      n: run.n,
      layers: drawn.filter((l) => l !== mask).map((l) => ({ ...l, flat: l.max > 0 && l.min_nonzero === l.max })),
      searched: mask ?? null,
      path: opts.path ? path : null,
      pathLen: run.pathLen,
      pathKey: run,
      highlight: found,
      start: run.start,
      position: f.position,
      at: run.pathLen > 0 ? pointAt(path, run.pathLen, shown, run.n) : null,
      target: run.target,
      showTarget: found || opts.reveal,
      pulses: m.pulse.rings(run, found, now, still),
      rv: run.config.rv,
      trails: loop ? (opts.rollouts ? loop.trails : []) : running ? m.trails.visible({ live, still }) : [],
      practice: opts.practice && running ? (loop ? loop.practice : m.trails.practice()) : -1,
      intent: opts.intent && running ? run.intent : null,
      decision: opts.arrows && f.decision && running ? { visits: f.decision.children.map((c) => c.selected), leading: f.decision.leading } : null,
      selected: i === 0 ? this.selected : -1,
      branchAt: opts.path ? run.branchAt : -1,
      treeLine: running ? (i === this.treeBoard && this.treeLine) || loop?.line || null : null,
      grid: opts.grid,
      tiling: opts.tiling,
    };
  }

  /**
   * The loop in flight of a run stepped phase by phase (its frame's phase
   * record): the tree path it selected (from the searcher), its practice
   * target, and its rollout revealed chunk by chunk as the engine cut it
   * (at once under reduced motion, whole once backed up). Null otherwise.
   */
  loopScene(run, m, now, still) {
    const rec = run.frame.phase;
    if (!rec?.phase) {
      m.reveal = null;
      return null;
    }
    const path = cellsOf(rec.path);
    const out = { trails: [], practice: rec.practice, line: path.length > 1 ? path : null, animating: false };
    if (rec.phase !== 'rollout' && rec.phase !== 'backup') return out;
    const key = `${rec.practice}|${rec.rollout_steps}|${path.join(',')}`;
    if (m.reveal?.key !== key) {
      const roll = cellsOf(rec.rollout);
      const cells = new Uint32Array(roll.length + 1);
      cells[0] = path[path.length - 1];
      cells.set(roll, 1);
      m.reveal = { key, start: now, cells, end: -1, shown: null };
    }
    const r = m.reveal;
    const all = rec.chunks.length;
    const k = rec.phase === 'backup' || still ? all : Math.min(all, Math.floor((now - r.start) / REVEAL_MS) + 1);
    const end = k ? rec.chunks[k - 1] : 0;
    // The same array while it does not grow: the trail's rendering is kept by it.
    if (end !== r.end) {
      r.end = end;
      r.shown = r.cells.subarray(0, end + 1);
    }
    out.trails = [{ cells: r.shown, alpha: 1 }];
    out.animating = k < all;
    return out;
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

  /** The marks the last frame drew on board `i` (MARKS keys). */
  drawnMarks(i = 0) {
    return [...this.renderers[i].drawn];
  }

  /** Where the searcher of run `run` is drawn on board `i`, in client px (for the tour). */
  searcherPoint(run, i = 0) {
    const r = this.renderers[i];
    const f = this.motion[i].glide.shown;
    const [x, y] = pointAt(run.pathView(), run.pathLen, Math.max(0, f), run.n);
    // Mid-wrap, the copy on the grid.
    const wrap = (v) => ((v % run.n) + run.n) % run.n;
    return r.clientPoint(wrap(x), wrap(y));
  }
}
