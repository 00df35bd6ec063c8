// The tree view: the decision's search tree drawn as a node-link diagram on
// its own canvas (the root is the searcher's cell now, an edge is a move).
// An edge's width is proportional to its visits, a node's colour is its
// mean value Q/N on a ramp shown in its legend, and nodes wide enough are
// labelled with N and Q/N. Over it, the loop stepped phase by phase: the
// selection path, the node expanded (a ring), the rollout as a dashed tail
// from the leaf, and the back-up as a pulse up the path. The hovered or
// focused node is ringed; nodes whose cell is hovered on the lattice are
// marked. Layout comes from tree-layout.js (once per tree); a frame skips
// subtrees narrower than a pixel, so its cost follows what can be seen.

import { layoutTree } from './tree-layout.js';

/** Subtrees narrower than this (device px) are drawn as one stub. */
const MIN_SPAN_PX = 1.5;
/** The widest edge (CSS px), for the root's visits. */
const MAX_EDGE_PX = 10;
/** Nodes this wide (CSS px) or wider get N and Q/N labels. */
const LABEL_PX = 46;
/** The tallest row (CSS px). */
const MAX_ROW_PX = 110;
/** How long the back-up pulse takes to climb the path (ms). */
const PULSE_MS = 900;
const WIDTH_BUCKETS = 8;
const COLOUR_BUCKETS = 32;
const MOVES = ['up', 'right', 'down', 'left'];
const INK = { edge: 'rgba(200,210,220,0.55)', path: '#ffd166', text: '#e6edf3', muted: '#8b98a5', ring: '#ffffff', unvisited: '#4a5560', bg: '#101418' };

export class TreeView {
  /**
   * @param {HTMLCanvasElement} canvas
   * @param {Uint8Array} lut  the value ramp: a palette's 256×RGBA table
   */
  constructor(canvas, lut) {
    this.canvas = canvas;
    this.ctx = canvas.getContext('2d');
    this.lut = lut;
    this.cols = null;
    this.layout = null;
    this.hover = -1; // preorder index of the hovered or focused node
    this.marked = []; // nodes whose cell is hovered on the lattice
    this.pulse = { key: '', start: 0 };
    this.pos = null; // per node: its drawn [x, y] (device px), NaN when not drawn
    this.drawnCount = 0;
  }

  /** Takes a fresh tree (the engine's columns); null for none. */
  setTree(cols) {
    this.cols = cols;
    this.layout = cols ? layoutTree(cols) : null;
    this.pos = cols ? new Float64Array(2 * cols.id.length).fill(NaN) : null;
    let lo = Infinity;
    let hi = -Infinity;
    if (cols) {
      for (const v of cols.value) {
        if (Number.isFinite(v)) {
          if (v < lo) lo = v;
          if (v > hi) hi = v;
        }
      }
    }
    this.range = Number.isFinite(lo) ? [Math.min(0, lo), hi > lo ? hi : lo + 1e-9] : [0, 1];
    if (this.hover >= (cols?.id.length ?? 0)) this.hover = -1;
  }

  /** Index of the node with engine id `id`, or −1. */
  indexOf(id) {
    const at = this.layout?.at;
    return at && id >= 0 && id < at.length ? at[id] : -1;
  }

  /** The CSS colour of a value on the ramp. */
  colour(v) {
    if (!Number.isFinite(v)) return INK.unvisited;
    const [lo, hi] = this.range;
    const k = Math.max(0, Math.min(255, Math.round((255 * (v - lo)) / (hi - lo))));
    const b = Math.round(k / (256 / COLOUR_BUCKETS)) * (256 / COLOUR_BUCKETS);
    const i = 4 * Math.min(255, b);
    return `rgb(${this.lut[i]},${this.lut[i + 1]},${this.lut[i + 2]})`;
  }

  /** Fits the canvas's pixels to its CSS box. */
  fit() {
    const dpr = window.devicePixelRatio || 1;
    const r = this.canvas.getBoundingClientRect();
    const w = Math.max(1, Math.round(r.width * dpr));
    const h = Math.max(1, Math.round(r.height * dpr));
    if (this.canvas.width !== w || this.canvas.height !== h) {
      this.canvas.width = w;
      this.canvas.height = h;
    }
    this.dpr = dpr;
  }

  /** Where row `depth` is drawn (device px), and the rows' spacing. */
  geometry() {
    const { width: W, height: H } = this.canvas;
    const pad = 14 * this.dpr;
    const rows = Math.max(1, this.layout.maxDepth);
    // Room under the deepest row for its labels; rows no taller than MAX_ROW_PX (a shallow tree stays compact).
    const below = 26 * this.dpr;
    const rowH = Math.max(6 * this.dpr, Math.min(MAX_ROW_PX * this.dpr, (H - 2 * pad - below) / rows));
    return { W, H, pad, rowH, y: (d) => pad + d * rowH, x: (u) => pad + u * (W - 2 * pad) };
  }

  /**
   * Draws the tree and, from the frame's phase record, the loop in flight.
   * @param {object} o
   * @param {object|null} o.phase   the frame's `phase` (or null)
   * @param {number} o.now          the clock (ms), for the pulse
   * @param {boolean} o.still       reduced motion: no pulse
   * @returns {boolean} true while the pulse plays (draw again next frame)
   */
  draw({ phase = null, now = performance.now(), still = false } = {}) {
    this.fit();
    const ctx = this.ctx;
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.fillStyle = INK.bg;
    ctx.fillRect(0, 0, this.canvas.width, this.canvas.height);
    if (!this.layout?.count) return false;
    const g = this.geometry();
    this.drawTree(g);
    const path = this.selectionPath(phase);
    this.drawPath(g, path);
    this.drawPhase(g, phase, path);
    const animating = this.drawPulse(g, phase, path, now, still);
    this.drawRings(g);
    return animating;
  }

  /** Edges batched by width, nodes by colour, labels where they fit; narrow subtrees as stubs. */
  drawTree(g) {
    const { cols, layout, pos } = this;
    const ctx = this.ctx;
    const dpr = this.dpr;
    const rootN = Math.max(1, cols.visits[0]);
    const edges = Array.from({ length: WIDTH_BUCKETS }, () => new Path2D());
    const dots = new Map();
    const labels = [];
    const r = Math.max(2 * dpr, Math.min(7 * dpr, g.rowH * 0.16));
    pos.fill(NaN);
    let drawn = 0;
    for (let i = 0; i < layout.count; ) {
      const x = g.x(layout.x[i]);
      const y = g.y(layout.depth[i]);
      const spanPx = layout.span[i] * (g.W - 2 * g.pad);
      const p = layout.parent[i];
      if (p >= 0) {
        const wb = Math.min(WIDTH_BUCKETS - 1, Math.floor((WIDTH_BUCKETS * cols.visits[i]) / rootN));
        const e = edges[wb];
        e.moveTo(pos[2 * p], pos[2 * p + 1]);
        e.lineTo(x, y);
      }
      pos[2 * i] = x;
      pos[2 * i + 1] = y;
      drawn++;
      if (spanPx < MIN_SPAN_PX && i > 0) {
        // Too narrow to see apart: the stub stands for the whole subtree.
        i = layout.end[i];
        continue;
      }
      // A node narrower than its dot gets a smaller one, down to 1.5 px.
      const ri = i === 0 ? r : Math.min(r, spanPx / 2.4);
      if (ri >= 1.5 * dpr) {
        const c = this.colour(cols.value[i]);
        if (!dots.has(c)) dots.set(c, new Path2D());
        const d = dots.get(c);
        d.moveTo(x + ri, y);
        d.arc(x, y, ri, 0, 2 * Math.PI);
        if (spanPx >= LABEL_PX * dpr && g.rowH >= 30 * dpr) labels.push(i);
      }
      i++;
    }
    this.drawnCount = drawn;
    ctx.lineCap = 'round';
    ctx.strokeStyle = INK.edge;
    edges.forEach((e, b) => {
      ctx.lineWidth = Math.max(0.75, ((b + 1) / WIDTH_BUCKETS) * MAX_EDGE_PX) * dpr;
      ctx.stroke(e);
    });
    ctx.lineWidth = 1 * dpr;
    ctx.strokeStyle = '#000';
    for (const [c, d] of dots) {
      ctx.fillStyle = c;
      ctx.fill(d);
      ctx.stroke(d);
    }
    this.drawLabels(labels, r);
  }

  /** N and Q/N under the nodes wide enough. */
  drawLabels(labels, r) {
    const { ctx, cols, pos, dpr } = this;
    ctx.font = `${Math.round(10 * dpr)}px system-ui, sans-serif`;
    ctx.textAlign = 'center';
    ctx.textBaseline = 'top';
    // A halo of the background keeps labels legible over edges.
    ctx.strokeStyle = INK.bg;
    ctx.lineWidth = 3 * dpr;
    ctx.lineJoin = 'round';
    for (const i of labels) {
      const q = cols.value[i];
      // The root's label goes beside it, clear of its edges; the others under their node.
      const root = i === 0;
      ctx.textAlign = root ? 'left' : 'center';
      const [x, y] = root ? [pos[0] + r + 5 * dpr, pos[1] - 10 * dpr] : [pos[2 * i], pos[2 * i + 1] + r + 2 * dpr];
      const lines = [[`N ${cols.visits[i]}`, INK.text], [Number.isFinite(q) ? `Q ${fmtShort(q)}` : 'Q –', INK.muted]];
      lines.forEach(([t, c], k) => {
        ctx.strokeText(t, x, y + 11 * k * dpr);
        ctx.fillStyle = c;
        ctx.fillText(t, x, y + 11 * k * dpr);
      });
    }
  }

  /** The loop's selection path as preorder indices (root first), from the phase record. */
  selectionPath(phase) {
    if (!phase?.select?.length) return [];
    const out = [];
    for (const level of phase.select) {
      const i = this.indexOf(level.node);
      if (i >= 0) out.push(i);
    }
    const last = phase.select[phase.select.length - 1];
    const m = MOVES.indexOf(last.chosen);
    // The tables' star names a neighbour 1 + its move's index.
    const j = this.indexOf(last.candidates[m]?.node ?? (this.cols.shape === 'star' ? 1 + m : -1));
    if (j >= 0) out.push(j);
    return out;
  }

  drawPath(g, path) {
    if (path.length < 2) return;
    const { ctx, pos, dpr } = this;
    ctx.beginPath();
    path.forEach((i, k) => (k ? ctx.lineTo(pos[2 * i], pos[2 * i + 1]) : ctx.moveTo(pos[2 * i], pos[2 * i + 1])));
    ctx.strokeStyle = '#000';
    ctx.lineWidth = 6 * dpr;
    ctx.stroke();
    ctx.strokeStyle = INK.path;
    ctx.lineWidth = 3.5 * dpr;
    ctx.stroke();
  }

  /** The node expanded (a double ring) and the rollout (a dashed tail from the leaf, its steps beside it). */
  drawPhase(g, phase, path) {
    if (!phase) return;
    const { ctx, pos, dpr } = this;
    const added = this.indexOf(phase.expansion?.node ?? -1);
    if (added >= 0 && Number.isFinite(pos[2 * added])) {
      for (const [w, c] of [[5, '#000'], [2.5, INK.path]]) {
        ctx.beginPath();
        ctx.arc(pos[2 * added], pos[2 * added + 1], 9 * dpr, 0, 2 * Math.PI);
        ctx.lineWidth = w * dpr;
        ctx.strokeStyle = c;
        ctx.stroke();
      }
    }
    const leaf = added >= 0 ? added : path[path.length - 1];
    if (!(phase.phase === 'rollout' || phase.phase === 'backup') || leaf === undefined || !Number.isFinite(pos[2 * leaf])) return;
    const x = pos[2 * leaf];
    const y = pos[2 * leaf + 1];
    // Long enough to clear the leaf's own labels, longer for a longer rollout.
    const len = Math.min(g.H - y - 6 * dpr, (34 + 12 * Math.log10(1 + phase.rollout_steps)) * dpr);
    ctx.save();
    ctx.setLineDash([5 * dpr, 4 * dpr]);
    ctx.lineWidth = 2.5 * dpr;
    ctx.strokeStyle = '#7fd4ff';
    ctx.beginPath();
    ctx.moveTo(x, y);
    ctx.lineTo(x, y + len);
    ctx.stroke();
    ctx.restore();
    ctx.fillStyle = '#7fd4ff';
    ctx.font = `${Math.round(10 * dpr)}px system-ui, sans-serif`;
    const left = x > g.W / 2;
    ctx.textAlign = left ? 'right' : 'left';
    ctx.textBaseline = 'middle';
    const label = `rollout: ${phase.rollout_steps} steps${phase.detected ? ', found ◇' : ''}`;
    ctx.strokeStyle = INK.bg;
    ctx.lineWidth = 4 * dpr;
    ctx.strokeText(label, x + (left ? -6 : 6) * dpr, y + len - 4 * dpr);
    ctx.fillText(label, x + (left ? -6 : 6) * dpr, y + len - 4 * dpr);
  }

  /** The back-up: a ring climbing the path from the leaf to the root (still: every node ringed). */
  drawPulse(g, phase, path, now, still) {
    if (phase?.phase !== 'backup' || !path.length) return false;
    const key = `${phase.practice}|${phase.reward}|${phase.rollout_steps}|${path.join(',')}`;
    if (key !== this.pulse.key) this.pulse = { key, start: now };
    const t = still ? 1 : Math.min(1, (now - this.pulse.start) / PULSE_MS);
    const upTo = Math.floor((1 - t) * (path.length - 1));
    const { ctx, pos, dpr } = this;
    for (let k = path.length - 1; k >= upTo; k--) {
      const i = path[k];
      ctx.beginPath();
      ctx.arc(pos[2 * i], pos[2 * i + 1], 7 * dpr, 0, 2 * Math.PI);
      ctx.lineWidth = 2 * dpr;
      ctx.strokeStyle = '#ffffff';
      ctx.stroke();
    }
    return t < 1;
  }

  /** The hovered or focused node (a white ring and its line) and the nodes marked from the lattice (squares). */
  drawRings(g) {
    const { ctx, pos, dpr } = this;
    for (const i of this.marked) {
      if (!Number.isFinite(pos[2 * i])) continue;
      ctx.lineWidth = 2 * dpr;
      ctx.strokeStyle = INK.ring;
      ctx.strokeRect(pos[2 * i] - 7 * dpr, pos[2 * i + 1] - 7 * dpr, 14 * dpr, 14 * dpr);
    }
    const h = this.hover;
    if (h < 0 || !Number.isFinite(pos[2 * h])) return;
    ctx.beginPath();
    for (let k = h; k >= 0; k = this.layout.parent[k]) {
      if (k === h) ctx.moveTo(pos[2 * k], pos[2 * k + 1]);
      else ctx.lineTo(pos[2 * k], pos[2 * k + 1]);
    }
    ctx.strokeStyle = INK.ring;
    ctx.lineWidth = 2 * dpr;
    ctx.setLineDash([2 * dpr, 3 * dpr]);
    ctx.stroke();
    ctx.setLineDash([]);
    ctx.beginPath();
    ctx.arc(pos[2 * h], pos[2 * h + 1], 10 * dpr, 0, 2 * Math.PI);
    ctx.lineWidth = 3 * dpr;
    ctx.stroke();
  }

  /** The drawn node nearest a client point (within 16 CSS px), or −1. */
  nodeAt(clientX, clientY) {
    if (!this.pos) return -1;
    const rect = this.canvas.getBoundingClientRect();
    const k = this.canvas.width / Math.max(1, rect.width);
    const x = (clientX - rect.left) * k;
    const y = (clientY - rect.top) * k;
    let best = -1;
    let bestD = (16 * k) ** 2;
    for (let i = 0; i < this.layout.count; i++) {
      const dx = this.pos[2 * i] - x;
      const dy = this.pos[2 * i + 1] - y;
      const d = dx * dx + dy * dy;
      if (d < bestD) {
        bestD = d;
        best = i;
      }
    }
    return best;
  }

  /** Marks the nodes whose cell is `cell` (−1: none); returns how many. */
  markCell(cell) {
    this.marked = [];
    if (cell < 0 || !this.cols) return 0;
    const cells = this.cols.cell;
    for (let i = 0; i < cells.length; i++) if (cells[i] === cell) this.marked.push(i);
    return this.marked.length;
  }

  /** The cells of node `i`'s line from the root (root first). */
  cellsOf(i) {
    const out = [];
    for (let k = i; k >= 0; k = this.layout.parent[k]) out.push(this.cols.cell[k]);
    return Uint32Array.from(out.reverse());
  }
}

/** A value in 4 significant digits or fewer. */
function fmtShort(v) {
  if (v === 0) return '0';
  return Math.abs(v) < 1e-3 ? v.toExponential(1) : Number(v.toPrecision(3)).toString();
}
