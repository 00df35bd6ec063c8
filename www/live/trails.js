// Rollouts that can be followed. A rollout (an imagined search, a cell
// path the engine sent) is drawn as a trail that brightens from its start
// to its end, with a ring at the start and a dot at the end, wrap-aware,
// decimated when long. The TraceKeeper decides which rollouts are on the
// board: while the search runs it takes up at most one set every HOLD_MS
// and lets each fade out after that, so a trail stays long enough to be
// followed and nothing strobes; when paused it shows the frame's rollouts
// as they are.

import { appendWrapPath, cellXY } from './paths.js';
import { INK, paintTrailEnd } from './marks.js';

/** A trail is shown at full strength this long (ms) before it starts fading. */
export const HOLD_MS = 400;
/** ... and fades out over this long (ms). */
export const FADE_MS = 900;
/** At most this many trails on the board at once. */
export const MAX_TRAILS = 2;
/** A longer rollout is decimated to about this many points. */
export const MAX_TRAIL_POINTS = 4000;
/** Brightness steps along a trail, from start to end. */
const CHUNKS = 10;

/**
 * Keeps about `max` points of `cells` (every k-th, the first and the last
 * always); a polyline through them is still wrap-aware, since each kept
 * step is short next to the board (a walk strays about √k cells in k steps).
 */
export function decimate(cells, max = MAX_TRAIL_POINTS) {
  const len = cells.length;
  if (len <= max) return cells;
  const k = Math.ceil((len - 1) / (max - 1));
  const out = new Uint32Array(Math.ceil((len - 1) / k) + 1);
  let j = 0;
  for (let i = 0; i < len - 1; i += k) out[j++] = cells[i];
  out[j++] = cells[len - 1];
  return out.subarray(0, j);
}

/** Names a trace by its length and a few cells (the worker sends fresh copies each frame). */
function traceKey(t) {
  return `${t.length}:${t[0]}:${t[t.length >> 1]}:${t[t.length - 1]}`;
}

export class TraceKeeper {
  constructor() {
    this.reset();
  }

  /** Forgets every trail (a new run). */
  reset() {
    this.held = []; // { key, cells, born } oldest first
    this.lastTaken = -Infinity;
    this.clock = 0; // ms of running time: trails age only while the search runs
    this.lastNow = null;
    this.shownPractice = -1;
  }

  /** The practice target that goes with the trails shown (−1: none). */
  practice() {
    return this.shownPractice;
  }

  /**
   * Takes in the frame's rollouts (oldest first) and the practice target of
   * the newest. `live`: the search runs on its own (trails age and fade);
   * else the frame's rollouts are shown as they are. `still`: no fading
   * (reduced motion): a new set replaces the old one at most once a second.
   */
  update(traces, practice, now, { live, still = false }) {
    const dt = this.lastNow === null ? 0 : Math.max(0, Math.min(100, now - this.lastNow));
    this.lastNow = now;
    const entry = (cells) => ({ key: traceKey(cells), cells: decimate(cells), born: this.clock });
    if (!live) {
      // The same trails keep their entries (the board keeps their drawings).
      this.held = traces.map((t) => this.held.find((h) => h.key === traceKey(t)) ?? entry(t));
      this.shownPractice = practice;
      return;
    }
    this.clock += dt;
    const hold = still ? 1000 : HOLD_MS;
    const fresh = traces.filter((t) => t.length > 1 && !this.held.some((h) => h.key === traceKey(t)));
    if ((fresh.length || practice !== this.shownPractice) && this.clock - this.lastTaken >= hold) {
      this.lastTaken = this.clock;
      if (still) this.held = [];
      for (const cells of fresh.slice(-MAX_TRAILS)) this.held.push(entry(cells));
      // The practice target shown is the one of the newest trail on the board.
      this.shownPractice = practice;
    }
    if (!still) this.held = this.held.filter((h) => this.alpha(h) > 0);
    this.held = this.held.slice(-MAX_TRAILS);
  }

  alpha(h) {
    const age = this.clock - h.born;
    return age <= HOLD_MS ? 1 : Math.max(0, 1 - (age - HOLD_MS) / FADE_MS);
  }

  /** The trails to draw, oldest first: [{ cells, alpha }]. */
  visible({ live, still = false }) {
    const k = this.held.length;
    return this.held.map((h, i) => ({
      cells: h.cells,
      // Older trails are fainter; while running they also fade with age.
      alpha: (live && !still ? this.alpha(h) : 1) * (0.25 + (0.6 * (i + 1)) / k),
    }));
  }

  /** True while trails are on the board (they age while the search runs). */
  busy() {
    return this.held.length > 0;
  }
}

/**
 * Draws one trail in cell units (ctx already transformed), `alpha` its
 * overall strength, `px` one device pixel in cell units.
 */
export function drawTrail(ctx, cells, n, alpha, px) {
  const len = cells.length;
  if (len < 2) return;
  const chunks = Math.min(CHUNKS, len - 1);
  ctx.strokeStyle = INK.rollout;
  const wide = Math.max(1.4 * px, Math.min(0.15, 2.4 * px));
  for (let j = 0; j < chunks; j++) {
    const a = Math.floor((j * (len - 1)) / chunks);
    const b = Math.floor(((j + 1) * (len - 1)) / chunks);
    const p = new Path2D();
    appendWrapPath(p, cells, a, b + 1, n);
    // Faint and thin at the start, strong at the end: the eye follows it to where it ended.
    const t = (j + 1) / chunks;
    ctx.globalAlpha = alpha * (0.06 + 0.94 * t * t);
    ctx.lineWidth = wide * (0.5 + 0.5 * t);
    ctx.stroke(p);
  }
  ctx.globalAlpha = alpha;
  const r = Math.max(2.5 * px, Math.min(0.3, 5 * px));
  const [x0, y0] = cellXY(cells[0], n);
  const [x1, y1] = cellXY(cells[len - 1], n);
  paintTrailEnd(ctx, x0 + 0.5, y0 + 0.5, r, px, false);
  paintTrailEnd(ctx, x1 + 0.5, y1 + 0.5, r, px, true);
  ctx.globalAlpha = 1;
}
