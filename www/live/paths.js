// Wrap-aware polylines of cells on the torus, and the searcher's path kept
// drawn on its own canvases. A step whose shortest displacement leaves the
// grid is drawn to the edge and continues from the opposite edge, so no line
// ever crosses the board.

import { COLORS } from './marks.js';

export function cellXY(idx, n) {
  return [idx % n, (idx / n) | 0];
}

/** Signed shortest displacement from a to b on a ring of size n. */
export function wrapDelta(a, b, n) {
  let d = b - a;
  if (d > n / 2) d -= n;
  else if (d < -n / 2) d += n;
  return d;
}

/**
 * Appends the wrap-aware segments of cells[from..to) (indices) to a Path2D,
 * in cell units (cell centres at x+0.5). A step whose shortest displacement
 * leaves the grid is drawn from its start to beyond the edge, then again
 * from beyond the opposite edge to its end (the caller clips to the grid).
 */
export function appendWrapPath(p2d, cells, from, to, n) {
  if (to - from < 1) return;
  let [px, py] = cellXY(cells[from], n);
  p2d.moveTo(px + 0.5, py + 0.5);
  for (let i = from + 1; i < to; i++) {
    const [x, y] = cellXY(cells[i], n);
    const dx = wrapDelta(px, x, n);
    const dy = wrapDelta(py, y, n);
    const ux = px + dx;
    const uy = py + dy;
    if (ux < 0 || ux >= n || uy < 0 || uy >= n) {
      p2d.lineTo(ux + 0.5, uy + 0.5);
      p2d.moveTo(x - dx + 0.5, y - dy + 0.5);
    }
    p2d.lineTo(x + 0.5, y + 0.5);
    px = x;
    py = y;
  }
}

/**
 * The visible segments of a polyline of cells, for tests: [x0,y0,x1,y1] in
 * cell units after clipping to [0,n]², as appendWrapPath draws them.
 */
export function wrapSegments(cells, n, from = 0, to = cells.length) {
  const c = (v) => Math.min(n, Math.max(0, v));
  const segs = [];
  let at = [0, 0];
  const pen = {
    moveTo(x, y) {
      at = [x, y];
    },
    lineTo(x, y) {
      segs.push([c(at[0]), c(at[1]), c(x), c(y)]);
      at = [x, y];
    },
  };
  appendWrapPath(pen, cells, from, to, n);
  return segs;
}

/**
 * Calls fn(tx, ty) once per tile, with `ctx` transformed to that tile's cell
 * units (tiles: [0], or [−1, 0, 1] for the 3×3 periodic view).
 */
export function forEachTile(ctx, cell, origin, gridPx, tiles, fn) {
  for (const ty of tiles) {
    for (const tx of tiles) {
      ctx.setTransform(cell, 0, 0, cell, origin + tx * gridPx, origin + ty * gridPx);
      fn(tx, ty);
    }
  }
}

/**
 * Path points drawn per frame at most. A frame draws only the path's new
 * segments; after a resize or a new run the whole path is drawn again, and a
 * long one fills in over a few frames rather than blocking one.
 */
export const PATH_POINTS_PER_FRAME = 20000;

/**
 * The searcher's path, kept drawn on two canvases the size of the view (halo
 * below, line above), so a frame strokes only the new segments and blits the
 * two: stroking the whole path every frame cost about 2 ms per 1000 moves.
 */
export class PathLayer {
  constructor() {
    this.halo = document.createElement('canvas');
    this.line = document.createElement('canvas');
    this.sig = '';
    this.key = undefined; // the run the drawing belongs to (compared by identity)
    this.done = 0; // path points drawn; the next segment starts at done − 1
  }

  /** Drops the drawing (the next update starts over). */
  forget() {
    this.sig = '';
    this.done = 0;
  }

  /**
   * Draws cells[done−1..len) (at most PATH_POINTS_PER_FRAME points) in every
   * tile, starting over when the view's geometry, the run or the width
   * changed, or the path got shorter. Returns true once the path is drawn
   * to its end.
   */
  update(cells, len, n, view) {
    const { width, height, cell, origin, gridPx, tiles, key, lineWidth } = view;
    const sig = [width, height, n, cell, origin, tiles.length, lineWidth].join('|');
    if (sig !== this.sig || key !== this.key || len < this.done) {
      for (const c of [this.halo, this.line]) {
        // Setting the size clears the canvas, even to the same size.
        c.width = width;
        c.height = height;
      }
      this.sig = sig;
      this.key = key;
      this.done = 0;
    }
    const from = Math.max(0, this.done - 1);
    const to = Math.min(len, from + PATH_POINTS_PER_FRAME);
    if (to - from >= 2) {
      const p = new Path2D();
      appendWrapPath(p, cells, from, to, n);
      for (const [canvas, color, px] of [
        [this.halo, COLORS.pathHalo, lineWidth + 2.5],
        [this.line, COLORS.path, lineWidth],
      ]) {
        const ctx = canvas.getContext('2d');
        ctx.save();
        if (tiles.length === 1) {
          ctx.beginPath();
          ctx.rect(origin, origin, gridPx, gridPx);
          ctx.clip();
        }
        ctx.lineCap = 'round';
        ctx.lineJoin = 'round';
        ctx.strokeStyle = color;
        ctx.lineWidth = px / cell;
        forEachTile(ctx, cell, origin, gridPx, tiles, () => ctx.stroke(p));
        ctx.restore();
      }
    }
    this.done = Math.max(this.done, to);
    return this.done >= len;
  }
}
