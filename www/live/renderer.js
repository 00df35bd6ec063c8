// Pure drawing: no engine calls, no game logic. Everything it draws is handed
// to it in a `scene` object (typed arrays the worker sent, and plain numbers).
//
// Heatmaps: one RGBA buffer per layer (coloured in Rust, src/view.rs) goes
// through ONE putImageData into an N×N offscreen canvas, which drawImage
// scales onto the view with smoothing off. Paths are wrap-aware: a step that
// crosses the boundary is drawn to the edge and continues from the opposite
// edge, so no line ever crosses the grid.

const MOVE_NAMES = ['Up', 'Right', 'Down', 'Left'];
const MOVE_DELTAS = [[0, -1], [1, 0], [0, 1], [-1, 0]];

export const COLORS = {
  background: '#101418',
  grid: 'rgba(255,255,255,0.10)',
  frame: 'rgba(255,255,255,0.45)',
  path: '#f2f5f7',
  pathHalo: 'rgba(0,0,0,0.65)',
  rollout: 'rgba(120,200,255,0.55)',
  searcher: '#ffffff',
  start: '#7fd4ff',
  target: '#ff5fa2',
  practice: '#7fd4ff',
  intent: '#ffd166',
  chosen: '#ffd166',
  arrow: 'rgba(255,255,255,0.85)',
  fade: 'rgba(16,20,24,0.62)',
};

function cellXY(idx, n) {
  return [idx % n, (idx / n) | 0];
}

/** Signed shortest displacement from a to b on a ring of size n. */
function wrapDelta(a, b, n) {
  let d = b - a;
  if (d > n / 2) d -= n;
  else if (d < -n / 2) d += n;
  return d;
}

/**
 * Appends the wrap-aware segments of a cell path (indices) to a Path2D, in
 * cell units (cell centres at x+0.5). A step whose shortest displacement
 * leaves the grid is drawn from its start to beyond the edge, then again from
 * beyond the opposite edge to its end (the caller clips to the grid).
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
      // Leaves the grid: draw to the (unwrapped) end point, which is clipped
      // at the edge, then re-enter from the opposite side.
      p2d.lineTo(ux + 0.5, uy + 0.5);
      p2d.moveTo(x - dx + 0.5, y - dy + 0.5);
    }
    p2d.lineTo(x + 0.5, y + 0.5);
    px = x;
    py = y;
  }
}

/**
 * Splits a path into the visible segments, for tests: returns a list of
 * [x0,y0,x1,y1] in cell units after clipping to [0,n]², as appendWrapPath draws them.
 */
export function wrapSegments(cells, n) {
  // Records what appendWrapPath draws, so the tests check the drawing code itself.
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
  appendWrapPath(pen, cells, 0, cells.length, n);
  return segs;
}

/**
 * Calls fn(tx, ty) once per tile, with `ctx` transformed to that tile's cell
 * units (tiles: [0], or [−1, 0, 1] for the 3×3 periodic view).
 */
function forEachTile(ctx, cell, origin, gridPx, tiles, fn) {
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
class PathLayer {
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
        [this.halo, COLORS.pathHalo, lineWidth + 2],
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

export class Renderer {
  /**
   * @param {HTMLCanvasElement} canvas the view
   */
  constructor(canvas) {
    this.canvas = canvas;
    this.ctx = canvas.getContext('2d', { alpha: false });
    this.offscreens = []; // one N×N canvas per layer slot
    this.pathLayer = new PathLayer();
    this.n = 0;
    this.tiling = false;
    this.layout();
  }

  /** The N×N offscreen canvas of layer slot `i`. */
  layerCanvas(i, n) {
    let off = this.offscreens[i];
    if (!off) {
      const canvas = document.createElement('canvas');
      off = this.offscreens[i] = { canvas, ctx: canvas.getContext('2d'), key: undefined };
    }
    if (off.canvas.width !== n || off.canvas.height !== n) {
      off.canvas.width = n;
      off.canvas.height = n;
      off.key = undefined;
    }
    return off;
  }

  /** Recomputes cell size from the canvas's pixel size. */
  layout() {
    const size = Math.min(this.canvas.width, this.canvas.height);
    const n = Math.max(this.n, 1);
    const tiles = this.tiling ? 3 : 1;
    this.cell = size / (n * tiles);
    this.origin = this.tiling ? n * this.cell : 0; // pixel offset of the main grid
    this.size = size;
  }

  /** Sizes the backing store to the element's CSS size × devicePixelRatio. */
  fitToElement() {
    const rect = this.canvas.getBoundingClientRect();
    const dpr = Math.min(window.devicePixelRatio || 1, 3);
    const side = Math.max(64, Math.round(Math.min(rect.width, rect.height || rect.width) * dpr));
    if (this.canvas.width !== side || this.canvas.height !== side) {
      this.canvas.width = side;
      this.canvas.height = side;
    }
    this.layout();
  }

  /** Maps a pointer position to a 0-based cell index, or -1. Tiles map onto the main grid. */
  cellAt(clientX, clientY) {
    const rect = this.canvas.getBoundingClientRect();
    if (!this.n || rect.width === 0) return -1;
    const sx = ((clientX - rect.left) / rect.width) * this.canvas.width;
    const sy = ((clientY - rect.top) / rect.height) * this.canvas.height;
    const tiles = this.tiling ? 3 : 1;
    let x = Math.floor(sx / this.cell);
    let y = Math.floor(sy / this.cell);
    if (x < 0 || y < 0 || x >= this.n * tiles || y >= this.n * tiles) return -1;
    x %= this.n;
    y %= this.n;
    return y * this.n + x;
  }

  /**
   * Draws one frame.
   * scene = {
   *   n, layers: [{ rgba: Uint8ClampedArray (4·n·n), key }] (same key = same pixels),
   *   path: Uint32Array, pathLen, pathKey (any value naming the run, compared by
   *   identity: a new key redraws the path),
   *   start, position, target (−1 = none), showTarget,
   *   rv, rollouts: [Uint32Array] (oldest first), practice (−1 = none),
   *   intent: Uint32Array | null (a planner's path ahead, from the position),
   *   decision: { visits: [4], leading: [4 bools] } | null, grid: bool, tiling: bool
   * }
   * Returns true while the path is not drawn to its end yet (a long path after
   * a resize or a new run): draw again next frame.
   */
  draw(scene) {
    const { n } = scene;
    if (n !== this.n || !!scene.tiling !== this.tiling) {
      this.n = n;
      this.tiling = !!scene.tiling;
      this.layout();
    }
    const ctx = this.ctx;
    const cs = this.cell;
    const gridPx = n * cs;
    const tiles = this.tiling ? [-1, 0, 1] : [0];
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.fillStyle = COLORS.background;
    ctx.fillRect(0, 0, this.canvas.width, this.canvas.height);

    // Heatmap layers: one putImageData each (skipped when a layer's `key`
    // says its pixels did not change), scaled by drawImage.
    ctx.imageSmoothingEnabled = false;
    scene.layers.forEach((layer, li) => {
      if (!layer || !layer.rgba || layer.rgba.length !== 4 * n * n) return;
      const off = this.layerCanvas(li, n);
      if (layer.key === undefined || off.key !== layer.key) {
        off.ctx.putImageData(new ImageData(layer.rgba, n, n), 0, 0);
        off.key = layer.key;
      }
      for (const ty of tiles) {
        for (const tx of tiles) {
          ctx.drawImage(off.canvas, 0, 0, n, n, this.origin + tx * gridPx, this.origin + ty * gridPx, gridPx, gridPx);
        }
      }
    });

    // Everything in cell units from here on, translated per tile.
    const lw = (px) => px / cs; // a width in device pixels, expressed in cell units
    const eachTile = (fn) => forEachTile(ctx, cs, this.origin, gridPx, tiles, fn);
    ctx.save();
    if (!this.tiling) {
      ctx.beginPath();
      ctx.rect(0, 0, gridPx, gridPx);
      ctx.clip();
    }
    ctx.lineCap = 'round';
    ctx.lineJoin = 'round';

    // Rollout traces (faint, oldest faintest).
    const rollouts = scene.rollouts || [];
    rollouts.forEach((trace, i) => {
      if (!trace || trace.length < 2) return;
      const p = new Path2D();
      appendWrapPath(p, trace, 0, trace.length, n);
      const a = 0.25 + 0.55 * ((i + 1) / rollouts.length);
      eachTile(() => {
        ctx.globalAlpha = a;
        ctx.strokeStyle = COLORS.rollout;
        ctx.lineWidth = lw(Math.max(1, cs * 0.12));
        ctx.stroke(p);
      });
    });
    ctx.globalAlpha = 1;

    // The searcher's path, with a dark halo so it reads on any heatmap.
    let pending = false;
    if (scene.path && scene.pathLen > 1) {
      const layer = this.pathLayer;
      pending = !layer.update(scene.path, scene.pathLen, n, {
        width: this.canvas.width,
        height: this.canvas.height,
        cell: cs,
        origin: this.origin,
        gridPx,
        tiles,
        key: scene.pathKey,
        lineWidth: Math.max(1.5, Math.min(cs * 0.28, 6)),
      });
      ctx.setTransform(1, 0, 0, 1, 0, 0);
      ctx.drawImage(layer.halo, 0, 0);
      ctx.drawImage(layer.line, 0, 0);
    } else {
      this.pathLayer.forget();
    }

    // A planner's path ahead: dashed, over the path it continues.
    if (scene.intent && scene.intent.length > 1) {
      const p = new Path2D();
      appendWrapPath(p, scene.intent, 0, scene.intent.length, n);
      eachTile(() => {
        ctx.setLineDash([lw(Math.max(3, cs * 0.5)), lw(Math.max(3, cs * 0.35))]);
        ctx.strokeStyle = COLORS.intent;
        ctx.lineWidth = lw(Math.max(1.5, Math.min(cs * 0.2, 4)));
        ctx.stroke(p);
        ctx.setLineDash([]);
      });
    }

    const markerR = Math.max(0.3, 5 / cs); // at least 5 device px
    const ring = (idx, r, color, width, dash) => {
      const [x, y] = cellXY(idx, n);
      ctx.beginPath();
      ctx.arc(x + 0.5, y + 0.5, r, 0, 2 * Math.PI);
      ctx.setLineDash(dash ? dash.map(lw) : []);
      ctx.strokeStyle = color;
      ctx.lineWidth = lw(width);
      ctx.stroke();
      ctx.setLineDash([]);
    };
    eachTile(() => {
      // Start: a square outline.
      if (scene.start >= 0) {
        const [x, y] = cellXY(scene.start, n);
        const h = Math.max(0.45, markerR);
        ctx.strokeStyle = COLORS.start;
        ctx.lineWidth = lw(2);
        ctx.strokeRect(x + 0.5 - h, y + 0.5 - h, 2 * h, 2 * h);
      }
      // Practice target of the current loop: a small diamond.
      if (scene.practice >= 0) {
        const [x, y] = cellXY(scene.practice, n);
        const h = Math.max(0.4, markerR * 0.9);
        ctx.beginPath();
        ctx.moveTo(x + 0.5, y + 0.5 - h);
        ctx.lineTo(x + 0.5 + h, y + 0.5);
        ctx.lineTo(x + 0.5, y + 0.5 + h);
        ctx.lineTo(x + 0.5 - h, y + 0.5);
        ctx.closePath();
        ctx.strokeStyle = COLORS.practice;
        ctx.lineWidth = lw(1.5);
        ctx.stroke();
      }
      // Target: a cross in a ring, only when found or revealed.
      if (scene.showTarget && scene.target >= 0) {
        const [x, y] = cellXY(scene.target, n);
        const h = Math.max(0.5, markerR * 1.2);
        ctx.beginPath();
        ctx.moveTo(x + 0.5 - h, y + 0.5 - h);
        ctx.lineTo(x + 0.5 + h, y + 0.5 + h);
        ctx.moveTo(x + 0.5 + h, y + 0.5 - h);
        ctx.lineTo(x + 0.5 - h, y + 0.5 + h);
        ctx.strokeStyle = '#000';
        ctx.lineWidth = lw(4);
        ctx.stroke();
        ctx.strokeStyle = COLORS.target;
        ctx.lineWidth = lw(2.2);
        ctx.stroke();
        ring(scene.target, h * 1.25, COLORS.target, 2);
      }
      // Searcher: a filled disc, plus its vision radius when visible.
      if (scene.position >= 0) {
        const [x, y] = cellXY(scene.position, n);
        if (scene.rv > 0 && scene.rv * cs >= 6) ring(scene.position, scene.rv + 0.5, 'rgba(255,255,255,0.5)', 1, [3, 3]);
        ctx.beginPath();
        ctx.arc(x + 0.5, y + 0.5, Math.max(0.3, markerR), 0, 2 * Math.PI);
        ctx.fillStyle = COLORS.searcher;
        ctx.fill();
        ctx.strokeStyle = '#000';
        ctx.lineWidth = lw(1.5);
        ctx.stroke();
      }
    });

    // Decision arrows around the searcher (main tile only).
    const d = scene.decision;
    if (d && scene.position >= 0 && d.visits) {
      ctx.setTransform(cs, 0, 0, cs, this.origin, this.origin);
      const total = d.visits.reduce((a, b) => a + b, 0) || 1;
      const [x, y] = cellXY(scene.position, n);
      const maxLen = Math.max(1.6, 28 / cs);
      for (let m = 0; m < 4; m++) {
        const share = d.visits[m] / total;
        if (share <= 0) continue;
        const [ddx, ddy] = MOVE_DELTAS[m];
        const len = 0.6 + maxLen * share;
        const x0 = x + 0.5 + ddx * 0.55;
        const y0 = y + 0.5 + ddy * 0.55;
        const x1 = x + 0.5 + ddx * len;
        const y1 = y + 0.5 + ddy * len;
        const chosen = d.leading[m];
        const w = lw(chosen ? 3.5 : 2);
        ctx.strokeStyle = '#000';
        ctx.lineWidth = w + lw(2);
        arrow(ctx, x0, y0, x1, y1, lw(7));
        ctx.strokeStyle = chosen ? COLORS.chosen : COLORS.arrow;
        ctx.lineWidth = w;
        arrow(ctx, x0, y0, x1, y1, lw(7));
      }
    }
    ctx.restore();

    // Faded copies around the main grid in the periodic view.
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    if (this.tiling) {
      ctx.fillStyle = COLORS.fade;
      ctx.fillRect(0, 0, this.size, this.origin);
      ctx.fillRect(0, this.origin + gridPx, this.size, this.size - this.origin - gridPx);
      ctx.fillRect(0, this.origin, this.origin, gridPx);
      ctx.fillRect(this.origin + gridPx, this.origin, this.size - this.origin - gridPx, gridPx);
    }

    // Grid lines when cells are big enough.
    if (scene.grid !== false && cs >= 7) {
      const p = new Path2D();
      const span = this.tiling ? 3 * n : n;
      const total = span * cs;
      for (let i = 0; i <= span; i++) {
        const v = Math.round(i * cs) + 0.5;
        p.moveTo(v, 0);
        p.lineTo(v, total);
        p.moveTo(0, v);
        p.lineTo(total, v);
      }
      ctx.strokeStyle = COLORS.grid;
      ctx.lineWidth = 1;
      ctx.stroke(p);
    }
    if (this.tiling) {
      ctx.strokeStyle = COLORS.frame;
      ctx.lineWidth = 2;
      ctx.strokeRect(this.origin, this.origin, gridPx, gridPx);
    }
    return pending;
  }
}

/** Dims the view and writes a short notice over it (e.g. after an engine error). */
export function drawNotice(canvas, text) {
  const ctx = canvas.getContext('2d');
  ctx.setTransform(1, 0, 0, 1, 0, 0);
  ctx.fillStyle = 'rgba(11,14,17,0.72)';
  ctx.fillRect(0, 0, canvas.width, canvas.height);
  ctx.fillStyle = '#ff8b8b';
  ctx.font = `600 ${Math.max(14, Math.round(canvas.width / 28))}px system-ui, sans-serif`;
  ctx.textAlign = 'center';
  ctx.textBaseline = 'middle';
  ctx.fillText(text, canvas.width / 2, canvas.height / 2, canvas.width * 0.9);
}

function arrow(ctx, x0, y0, x1, y1, head) {
  const ang = Math.atan2(y1 - y0, x1 - x0);
  ctx.beginPath();
  ctx.moveTo(x0, y0);
  ctx.lineTo(x1, y1);
  ctx.moveTo(x1 - head * Math.cos(ang - 0.5), y1 - head * Math.sin(ang - 0.5));
  ctx.lineTo(x1, y1);
  ctx.lineTo(x1 - head * Math.cos(ang + 0.5), y1 - head * Math.sin(ang + 0.5));
  ctx.stroke();
}

/** Draws a horizontal colour bar from a 256×4 RGBA lookup table into a small canvas. */
export function drawColorbar(canvas, lut) {
  const ctx = canvas.getContext('2d');
  canvas.width = 256;
  canvas.height = 1;
  ctx.putImageData(new ImageData(new Uint8ClampedArray(lut), 256, 1), 0, 0);
}

export { MOVE_NAMES, MOVE_DELTAS };
