// Motion on the board: the searcher gliding along its path between frames,
// the pulse at a found target, and the visitor's wish for less motion
// (prefers-reduced-motion: no autoplay, no glide, no pulse, no fading trails).
// Pure timing: it says where to draw, never what the search did.

import { cellXY, wrapDelta } from './paths.js';

const query = typeof matchMedia === 'function' ? matchMedia('(prefers-reduced-motion: reduce)') : null;

/** True when the visitor asked for reduced motion. */
export function reducedMotion() {
  return !!query?.matches;
}

/** Whether the page may start playing by itself: not under reduced motion, unless the URL says autoplay=1. */
export function autoplayAllowed(search) {
  return !reducedMotion() || new URLSearchParams(search).has('autoplay');
}

/** A glide lasts at most this long (ms), and at least this short. */
const GLIDE_MAX_MS = 220;
const GLIDE_MIN_MS = 60;
/** Further behind than this many moves, the searcher jumps to one move behind and glides the last one. */
const MAX_BEHIND = 3;

/**
 * Where to draw the searcher: a fractional index along its path that
 * follows the newest position over about the time between frames.
 */
export class Glide {
  constructor() {
    this.reset(null);
  }

  reset(key) {
    this.key = key;
    this.shown = -1; // fractional path index drawn
    this.target = -1;
    this.rate = 0; // path indices per ms
    this.lastArrival = 0;
    this.lastNow = 0;
  }

  /** Moves on to `now`; `last` is the newest path index. Returns the index to draw. */
  at(key, last, now, still) {
    if (key !== this.key || last < this.target || this.shown < 0) {
      this.reset(key);
      this.shown = this.target = last;
      this.lastArrival = this.lastNow = now;
      return last;
    }
    if (last !== this.target) {
      const gap = now - this.lastArrival;
      this.lastArrival = now;
      this.target = last;
      if (last - this.shown > MAX_BEHIND) this.shown = last - 1;
      this.rate = (last - this.shown) / Math.min(GLIDE_MAX_MS, Math.max(GLIDE_MIN_MS, gap));
    }
    if (still) this.shown = this.target;
    else this.shown = Math.min(this.target, this.shown + this.rate * Math.max(0, now - this.lastNow));
    this.lastNow = now;
    return this.shown;
  }

  /** True while the searcher is between cells (more frames are needed). */
  moving() {
    return this.shown >= 0 && this.shown < this.target;
  }
}

/**
 * The searcher's point in cell units (centre of a cell at x + 0.5) at
 * fractional path index `f`: between two cells it is on the step joining
 * them, which can lie beyond an edge of the grid mid-wrap.
 */
export function pointAt(path, len, f, n) {
  const i = Math.max(0, Math.min(len - 1, Math.floor(f)));
  const [ax, ay] = cellXY(path[i], n);
  if (i + 1 >= len) return [ax + 0.5, ay + 0.5];
  const t = f - i;
  const [bx, by] = cellXY(path[i + 1], n);
  return [ax + 0.5 + t * wrapDelta(ax, bx, n), ay + 0.5 + t * wrapDelta(ay, by, n)];
}

/** The found pulse: rings at the target for PULSE_MS after the run is found. */
export const PULSE_MS = 1500;
const PULSE_PERIOD = 500;

export class Pulse {
  constructor() {
    this.key = null;
    this.start = 0;
  }

  /** Rings to draw now (each a phase in [0, 1)); `found` true once the run is found. */
  rings(key, found, now, still) {
    if (!found) {
      this.key = null;
      return [];
    }
    if (this.key !== key) {
      this.key = key;
      this.start = now;
    }
    const t = now - this.start;
    if (still || t >= PULSE_MS) return [];
    const out = [];
    for (let k = 0; k * (PULSE_PERIOD / 2) <= t; k++) {
      const phase = (t - (k * PULSE_PERIOD) / 2) / PULSE_PERIOD;
      if (phase < 1) out.push(phase);
    }
    return out;
  }

  /** True while the pulse plays. */
  playing(now) {
    return this.key !== null && now - this.start < PULSE_MS;
  }
}
