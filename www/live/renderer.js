// Pure drawing: no engine calls, no game logic. Everything it draws is handed
// to it in a `scene` object (typed arrays the worker sent, and plain numbers).
//
// The heat layer: one RGBA buffer (coloured in Rust, src/display/view.rs)
// goes through ONE putImageData into an N×N offscreen canvas when its key
// changes, which drawImage scales onto the view with smoothing off. A
// second quantity is never a second colour ramp: the searched cells are a
// hatch (their mask is the searched layer's pixels). Paths and trails are
// wrap-aware (paths.js). Each frame records which marks it drew (`drawn`),
// so the legend can be held to naming all of them.

import { COLORS, SHARED_DASH, hatchTile, paintArrow, paintBranch, paintPractice, paintPulse, paintSearcher, paintSelected, paintStart, paintTarget, paintVision, INK } from './marks.js';
import { PathLayer, appendWrapPath, cellXY, forEachTile } from './paths.js';
import { drawTrail } from './trails.js';

export { PATH_POINTS_PER_FRAME, appendWrapPath, wrapSegments } from './paths.js';
export { COLORS } from './marks.js';

const MOVE_NAMES = ['Up', 'Right', 'Down', 'Left'];
const MOVE_DELTAS = [[0, -1], [1, 0], [0, 1], [-1, 0]];
/** A heat layer whose nonzero cells are all equal (a uniform prior) is drawn at this opacity, not at full brightness. */
export const FLAT_ALPHA = 0.25;

export class Renderer {
  /**
   * @param {HTMLCanvasElement} canvas the view
   */
  constructor(canvas) {
    this.canvas = canvas;
    this.ctx = canvas.getContext('2d', { alpha: false });
    this.offscreens = []; // one N×N canvas per layer slot
    this.pathLayer = new PathLayer();
    this.hatch = { canvas: null, sig: '' };
    this.trailCache = new Map(); // trail cells (by identity) -> { sig, canvas }
    this.n = 0;
    this.tiling = false;
    this.dpr = 1;
    this.drawn = new Set(); // marks drawn by the last frame (MARKS keys)
    this.drawnLayers = []; // layer names drawn by the last frame
    this.at = null; // where the last frame drew the searcher, in cell units
    this.uploads = 0; // putImageData calls so far (the benchmark reads it)
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

  /** Uploads a layer's pixels into slot `i` unless its key says they are there already. */
  upload(i, layer, n) {
    const off = this.layerCanvas(i, n);
    if (layer.key === undefined || off.key !== layer.key) {
      off.ctx.putImageData(new ImageData(layer.rgba, n, n), 0, 0);
      off.key = layer.key;
      this.uploads++;
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
    this.dpr = Math.min(window.devicePixelRatio || 1, 3);
    const side = Math.max(64, Math.round(Math.min(rect.width, rect.height || rect.width) * this.dpr));
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

  /** The client (CSS px) point of a point in cell units of the main grid. */
  clientPoint(x, y) {
    const rect = this.canvas.getBoundingClientRect();
    const k = rect.width / this.canvas.width;
    return [rect.left + (this.origin + x * this.cell) * k, rect.top + (this.origin + y * this.cell) * k];
  }

  /**
   * Draws one frame.
   * scene = {
   *   n, layers: [{ rgba: Uint8ClampedArray (4·n·n), key, flat }] (same key = same
   *   pixels; flat: every nonzero cell equal), searched: { rgba, key } | null (a mask, hatched),
   *   path: Uint32Array, pathLen, pathKey (any value naming the run, compared by
   *   identity: a new key redraws the path), highlight (the found path),
   *   start, position, at: [x, y] | null (the searcher's point in cell units, gliding),
   *   target (−1 = none), showTarget, pulses: [phase in 0..1) (found rings),
   *   rv, trails: [{ cells, alpha }] (oldest first), practice (−1 = none),
   *   intent: Uint32Array | null (a planner's path ahead, from the position),
   *   decision: { visits: [4], leading: [4 bools] } | null, selected (−1 = none),
   *   branchAt: the moves shared with the run this one branched from (−1: none),
   *   grid: bool, tiling: bool
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
    this.drawn = new Set();
    this.drawnLayers = [];
    this.at = null;
    const ctx = this.ctx;
    const cs = this.cell;
    const gridPx = n * cs;
    const tiles = this.tiling ? [-1, 0, 1] : [0];
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.fillStyle = COLORS.background;
    ctx.fillRect(0, 0, this.canvas.width, this.canvas.height);
    ctx.imageSmoothingEnabled = false;
    const blit = (img, alpha = 1) => {
      ctx.globalAlpha = alpha;
      for (const ty of tiles) for (const tx of tiles) ctx.drawImage(img, 0, 0, img.width, img.height, this.origin + tx * gridPx, this.origin + ty * gridPx, gridPx, gridPx);
      ctx.globalAlpha = 1;
    };
    scene.layers.forEach((layer, li) => {
      if (!layer?.rgba || layer.rgba.length !== 4 * n * n) return;
      blit(this.upload(li, layer, n).canvas, layer.flat ? FLAT_ALPHA : 1);
      this.drawnLayers.push(layer.layer ?? 'preview');
    });
    if (scene.searched?.rgba?.length === 4 * n * n) {
      ctx.drawImage(this.hatched(scene.searched, n, gridPx, tiles), 0, 0);
      this.drawn.add('searched');
      this.drawnLayers.push(scene.searched.layer);
    }

    // Everything in cell units from here on, translated per tile.
    const px = this.dpr / cs; // one CSS pixel, in cell units
    const eachTile = (fn) => forEachTile(ctx, cs, this.origin, gridPx, tiles, fn);
    ctx.save();
    if (!this.tiling) {
      ctx.beginPath();
      ctx.rect(0, 0, gridPx, gridPx);
      ctx.clip();
    }
    ctx.lineCap = 'round';
    ctx.lineJoin = 'round';
    this.drawTrails(scene, px);
    const pending = this.drawPath(scene, gridPx, tiles);
    this.drawBranch(scene, eachTile, px);
    this.drawIntent(scene, eachTile, px);
    this.drawTreeLine(scene, eachTile, px);
    // Once found, the target (and its pulse) goes over the searcher beside it.
    if (scene.highlight) this.drawSearcher(scene, px);
    this.drawMarks(scene, eachTile, px);
    if (!scene.highlight) this.drawSearcher(scene, px);
    ctx.restore();
    this.drawFrame(scene, gridPx);
    return pending;
  }

  /** The hatch over the searched cells, view-sized, remade when the mask or the geometry changes. */
  hatched(mask, n, gridPx, tiles) {
    const h = this.hatch;
    const sig = [mask.key, n, this.canvas.width, this.origin, tiles.length].join('|');
    if (mask.key === undefined || sig !== h.sig) {
      const off = this.upload(7, mask, n);
      h.canvas ??= document.createElement('canvas');
      h.canvas.width = this.canvas.width;
      h.canvas.height = this.canvas.height;
      const c = h.canvas.getContext('2d');
      c.imageSmoothingEnabled = false;
      for (const ty of tiles) for (const tx of tiles) c.drawImage(off.canvas, 0, 0, n, n, this.origin + tx * gridPx, this.origin + ty * gridPx, gridPx, gridPx);
      c.globalCompositeOperation = 'source-in';
      c.fillStyle = c.createPattern(hatchTile(Math.round(6 * this.dpr)), 'repeat');
      c.fillRect(0, 0, h.canvas.width, h.canvas.height);
      h.sig = sig;
    }
    return h.canvas;
  }

  /**
   * The rollout trails. Each is rastered once into a view-sized canvas of
   * its own (a trail is kept on the board for several hundred ms) and
   * blitted at its current strength: stroking thousands of segments again
   * every frame cost more than the frame had without a GPU.
   */
  drawTrails(scene, px) {
    const trails = (scene.trails || []).filter((t) => t.cells.length > 1);
    const cache = this.trailCache;
    const sig = [this.canvas.width, scene.n, this.origin, this.tiling].join('|');
    for (const key of cache.keys()) if (!trails.some((t) => t.cells === key)) cache.delete(key);
    if (!trails.length) return;
    this.drawn.add('rollout');
    const ctx = this.ctx;
    ctx.save();
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    for (const t of trails) {
      let c = cache.get(t.cells);
      if (!c || c.sig !== sig) {
        c = { sig, canvas: c?.canvas ?? document.createElement('canvas') };
        c.canvas.width = this.canvas.width;
        c.canvas.height = this.canvas.height;
        const tc = c.canvas.getContext('2d');
        tc.lineCap = 'round';
        tc.lineJoin = 'round';
        const gridPx = scene.n * this.cell;
        if (!this.tiling) {
          tc.beginPath();
          tc.rect(this.origin, this.origin, gridPx, gridPx);
          tc.clip();
        }
        forEachTile(tc, this.cell, this.origin, gridPx, this.tiling ? [-1, 0, 1] : [0], () => drawTrail(tc, t.cells, scene.n, 1, px));
        cache.set(t.cells, c);
      }
      ctx.globalAlpha = t.alpha;
      ctx.drawImage(c.canvas, 0, 0);
    }
    ctx.restore();
  }

  /** The searcher's path, with a dark halo so it reads on any heat layer (glowing once found). */
  drawPath(scene, gridPx, tiles) {
    const ctx = this.ctx;
    const layer = this.pathLayer;
    if (!scene.path || scene.pathLen < 2) {
      layer.forget();
      return false;
    }
    const cs = this.cell;
    const pending = !layer.update(scene.path, scene.pathLen, scene.n, {
      width: this.canvas.width,
      height: this.canvas.height,
      cell: cs,
      origin: this.origin,
      gridPx,
      tiles,
      key: scene.pathKey,
      lineWidth: Math.max(2 * this.dpr, Math.min(cs * 0.28, 6 * this.dpr)),
    });
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.drawImage(layer.halo, 0, 0);
    if (scene.highlight) ctx.filter = `drop-shadow(0 0 ${Math.round(4 * this.dpr)}px ${INK.white})`;
    ctx.drawImage(layer.line, 0, 0);
    ctx.filter = 'none';
    this.drawn.add('path');
    return pending;
  }

  /**
   * A branched run: dashes over the path it shares with the run it
   * branched from, and a triangle at the branch point (once reached).
   */
  drawBranch(scene, eachTile, px) {
    const at = scene.branchAt ?? -1;
    if (at < 0 || !scene.path || !scene.pathLen) return;
    const ctx = this.ctx;
    const n = scene.n;
    const len = Math.min(at + 1, scene.pathLen);
    const c = this.shared;
    if (c?.key !== scene.pathKey || c.len !== len || c.n !== n) {
      const p = new Path2D();
      if (len > 1) appendWrapPath(p, scene.path, 0, len, n);
      this.shared = { key: scene.pathKey, len, n, path: p };
    }
    const lw = Math.max(2 * this.dpr, Math.min(this.cell * 0.28, 6 * this.dpr)) / this.cell;
    const mark = at < scene.pathLen ? cellXY(scene.path[at], n).map((v) => v + 0.5) : null;
    eachTile(() => {
      if (len > 1) {
        ctx.setLineDash([Math.max(3 * px, 0.3), Math.max(3 * px, 0.3)]);
        ctx.strokeStyle = SHARED_DASH;
        ctx.lineWidth = 0.55 * lw;
        ctx.stroke(this.shared.path);
        ctx.setLineDash([]);
      }
      if (mark) paintBranch(ctx, ...mark, Math.max(0.3, 5 * px), px);
    });
    if (len > 1) this.drawn.add('shared');
    if (mark) this.drawn.add('branch');
  }

  /** The tree node in focus: its moves from the searcher, dotted white, ending in a ring. */
  drawTreeLine(scene, eachTile, px) {
    const cells = scene.treeLine;
    if (!cells?.length) return;
    const ctx = this.ctx;
    const p = new Path2D();
    if (cells.length > 1) appendWrapPath(p, cells, 0, cells.length, scene.n);
    const last = cells[cells.length - 1];
    const [x, y] = [(last % scene.n) + 0.5, Math.floor(last / scene.n) + 0.5];
    this.drawn.add('treeLine');
    eachTile(() => {
      ctx.setLineDash([Math.max(1.5 * px, 0.08), Math.max(4 * px, 0.2)]);
      ctx.strokeStyle = COLORS.rim;
      ctx.lineWidth = 6 * px;
      ctx.stroke(p);
      ctx.strokeStyle = INK.white;
      ctx.lineWidth = 3.5 * px;
      ctx.stroke(p);
      ctx.setLineDash([]);
      ctx.beginPath();
      ctx.arc(x, y, 0.36, 0, 2 * Math.PI);
      ctx.strokeStyle = COLORS.rim;
      ctx.lineWidth = 5 * px;
      ctx.stroke();
      ctx.strokeStyle = INK.white;
      ctx.lineWidth = 2.5 * px;
      ctx.stroke();
    });
  }

  drawIntent(scene, eachTile, px) {
    if (!scene.intent || scene.intent.length < 2) return;
    const ctx = this.ctx;
    const p = new Path2D();
    appendWrapPath(p, scene.intent, 0, scene.intent.length, scene.n);
    this.drawn.add('planned');
    eachTile(() => {
      const w = Math.max(1.5 * px, Math.min(0.2, 4 * px));
      ctx.setLineDash([Math.max(4 * px, 0.5), Math.max(3 * px, 0.35)]);
      ctx.strokeStyle = COLORS.rim;
      ctx.lineWidth = w + 2 * px;
      ctx.stroke(p);
      ctx.strokeStyle = INK.next;
      ctx.lineWidth = w;
      ctx.stroke(p);
      ctx.setLineDash([]);
    });
  }

  /** Start, practice target, target (with the found pulse) and the selected cell, in every tile. */
  drawMarks(scene, eachTile, px) {
    const ctx = this.ctx;
    const n = scene.n;
    const h = Math.max(0.42, 6 * px);
    const at = (idx) => cellXY(idx, n).map((v) => v + 0.5);
    eachTile(() => {
      if (scene.start >= 0) paintStart(ctx, ...at(scene.start), h, px);
      if (scene.practice >= 0) paintPractice(ctx, ...at(scene.practice), h * 1.1, px);
      if (scene.showTarget && scene.target >= 0) {
        paintTarget(ctx, ...at(scene.target), h, px);
        for (const t of scene.pulses || []) paintPulse(ctx, ...at(scene.target), h, t, px);
      }
      if (scene.selected >= 0) paintSelected(ctx, ...at(scene.selected), Math.max(0.5, 7 * px), px);
    });
    if (scene.start >= 0) this.drawn.add('start');
    if (scene.practice >= 0) this.drawn.add('practice');
    if (scene.showTarget && scene.target >= 0) this.drawn.add('target');
    if (scene.selected >= 0) this.drawn.add('selected');
  }

  /**
   * The searcher at its (gliding) point, with its vision disc and decision
   * arrows: on the main grid, plus a ghost across each edge it overlaps, so
   * at a wrap it leaves one edge and enters the other.
   */
  drawSearcher(scene, px) {
    if (scene.position < 0) return;
    const ctx = this.ctx;
    const n = scene.n;
    const [x, y] = scene.at ?? cellXY(scene.position, n).map((v) => v + 0.5);
    this.at = [x, y];
    const r = Math.max(0.32, 6 * px);
    const vision = scene.rv > 0 && scene.rv * this.cell >= 6 * this.dpr;
    const reach = Math.max(r + 5 * px, vision ? scene.rv + 0.5 : 0, 2);
    ctx.setTransform(this.cell, 0, 0, this.cell, this.origin, this.origin);
    const shifts = this.tiling ? [0] : [-n, 0, n];
    for (const oy of shifts) {
      for (const ox of shifts) {
        const cx = x + ox;
        const cy = y + oy;
        if (cx < -reach || cy < -reach || cx > n + reach || cy > n + reach) continue;
        if (vision) paintVision(ctx, cx, cy, scene.rv + 0.5, px);
        if (ox === 0 && oy === 0) this.drawArrows(scene.decision, cx, cy, px);
        paintSearcher(ctx, cx, cy, r, px);
      }
    }
    if (vision) this.drawn.add('vision');
    this.drawn.add('searcher');
  }

  /** Decision arrows around the searcher: length by the share of picks, the leading move thick. */
  drawArrows(d, x, y, px) {
    if (!d?.visits) return;
    const total = d.visits.reduce((a, b) => a + b, 0) || 1;
    const maxLen = Math.max(1.6, 28 * px);
    for (let m = 0; m < 4; m++) {
      const share = d.visits[m] / total;
      if (share <= 0) continue;
      const [dx, dy] = MOVE_DELTAS[m];
      const len = 0.6 + maxLen * share;
      paintArrow(this.ctx, x + dx * 0.55, y + dy * 0.55, x + dx * len, y + dy * len, d.leading[m], px);
      this.drawn.add('arrows');
    }
  }

  /** The periodic view's faded copies, grid lines and frame. */
  drawFrame(scene, gridPx) {
    const ctx = this.ctx;
    const cs = this.cell;
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    if (this.tiling) {
      ctx.fillStyle = COLORS.fade;
      ctx.fillRect(0, 0, this.size, this.origin);
      ctx.fillRect(0, this.origin + gridPx, this.size, this.size - this.origin - gridPx);
      ctx.fillRect(0, this.origin, this.origin, gridPx);
      ctx.fillRect(this.origin + gridPx, this.origin, this.size - this.origin - gridPx, gridPx);
    }
    if (scene.grid !== false && cs >= 7) {
      const p = new Path2D();
      const span = this.tiling ? 3 * scene.n : scene.n;
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

/** Draws a horizontal colour bar from a 256×4 RGBA lookup table into a small canvas. */
export function drawColorbar(canvas, lut) {
  const ctx = canvas.getContext('2d');
  canvas.width = 256;
  canvas.height = 1;
  ctx.putImageData(new ImageData(new Uint8ClampedArray(lut), 256, 1), 0, 0);
}

export { MOVE_NAMES, MOVE_DELTAS };
