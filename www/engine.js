// The page's only door into the wasm engine (www/pkg, built from src/wasm.rs).
// It translates the URL-level config (www/url-state.js) into the core's
// Config object, wraps one episode handle per run, and reads the engine's
// buffers zero-copy. No game logic lives here.

import init, * as wasm from './pkg/torus_search.js';

let exports = null;

/** Loads and instantiates the wasm module once; resolves to the module namespace. */
export async function loadEngine() {
  if (!exports) exports = await init();
  return wasm;
}

/** The wasm memory's current buffer (re-read it after any wasm call: growth detaches it). */
export function memoryBuffer() {
  return exports.memory.buffer;
}

/** Turns a caught exception into a readable message, using the Rust panic text if there is one. */
export function describeError(err) {
  const isTrap = err instanceof WebAssembly.RuntimeError;
  if (isTrap && exports) {
    let panic = null;
    try {
      panic = wasm.lastPanic();
    } catch {
      /* the module may be unusable after a trap */
    }
    return `The engine crashed (wasm panic): ${(panic || err.message).replace(/\s*\n\s*/g, " ")}. Restart to try again; if it persists please report it with the copied link.`;
  }
  return err && err.message ? err.message : String(err);
}

/**
 * Maps a URL config (+ optional painted weights) to the core's Config fields.
 * `override` replaces searcher/variant (race mode).
 */
export function coreConfig(cfg, { weights = null, keepTraces = 0, override = null } = {}) {
  let prior;
  if (cfg.prior === 'uniform') prior = { kind: 'uniform' };
  else if (cfg.prior === 'delta' || (cfg.prior === 'gaussian' && cfg.sigma === 0)) prior = { kind: 'delta', cell: null };
  else if (cfg.prior === 'paint' && weights) prior = { kind: 'weights', weights: Array.from(weights) };
  else prior = { kind: 'gaussian', sigma: cfg.sigma };
  const out = {
    n: cfg.n,
    prior,
    rv: cfg.rv,
    start: [cfg.start[0], cfg.start[1]],
    searcher: cfg.searcher,
    variant: cfg.variant,
    rollout: cfg.rollout,
    belief: cfg.belief,
    loops: cfg.loops,
    decision_ms: cfg.ms > 0 ? cfg.ms : null,
    c: cfg.c,
    mu: cfg.mu,
    final_rule: cfg.final,
    keep_traces: keepTraces,
  };
  if (override) Object.assign(out, override);
  return out;
}

/** Race opponents by name. */
export const RACE = {
  'mcts-cells': { searcher: 'mcts', variant: 'cells' },
  'mcts-tree': { searcher: 'mcts', variant: 'tree' },
  rw: { searcher: 'rw' },
  levy: { searcher: 'levy' },
  nsarw: { searcher: 'nsarw' },
};

/** One episode in the page. */
export class Run {
  static count = 0;

  constructor(core, seed, label) {
    this.h = new wasm.Episode(core, BigInt(seed));
    this.core = core;
    this.label = label;
    this.isMcts = core.searcher === 'mcts';
    this.n = this.h.n();
    this.startCell = this.h.start();
    this.targetCell = this.h.target();
    this.optimalSteps = this.h.optimal();
    this.walkerMoves = 0;
    this.pacer = null; // () => max steps allowed now (race pacing), or null
    this.serial = ++Run.count; // distinguishes cached layer pixels across runs
  }

  free() {
    try {
      this.h.free();
    } catch {
      /* already freed */
    }
  }

  status() {
    return this.h.status();
  }

  /** k loops (k moves for a walker); continues across decisions. Returns moves made. */
  stepLoops(k) {
    let moves = 0;
    if (!this.isMcts) {
      // Paced by an MCTS opponent in a race: never more real moves than it.
      const limit = this.pacer ? Math.min(k, this.pacer() - this.h.steps()) : k;
      for (let i = 0; i < limit && this.h.status() === 'running'; i++) {
        if (this.h.stepLoops(1)) moves++;
      }
      this.walkerMoves += moves;
      return moves;
    }
    let left = k;
    while (left > 0 && this.h.status() === 'running') {
      const before = this.h.rolloutsTotal();
      const moved = this.h.stepLoops(left);
      const did = this.h.rolloutsTotal() - before;
      left -= did;
      if (moved) moves++;
      else if (did === 0) break;
    }
    return moves;
  }

  stepMove() {
    this.h.stepMove();
    if (!this.isMcts) this.walkerMoves++;
  }

  loopsDone() {
    return this.isMcts ? this.h.rolloutsTotal() : this.walkerMoves;
  }

  rolloutSteps() {
    return this.h.rolloutStepsTotal();
  }

  path() {
    return Array.from(this.h.path());
  }

  /**
   * All wasm calls a frame needs, returning only numbers (pointers, lengths
   * and stats). Call views() afterwards, once per frame, for typed arrays.
   * layers: [{ name, palette, scale, alphaLo, alphaHi }]
   */
  snapshot(layers, { traces = false } = {}) {
    const h = this.h;
    const out = {
      n: this.n,
      status: h.status(),
      steps: h.steps(),
      optimal: this.optimalSteps,
      target: this.targetCell,
      start: this.startCell,
      position: h.position(),
      pathPtr: h.pathPtr(),
      pathLen: h.pathLen(),
      loopsDone: h.loopsDone(),
      rollouts: h.rolloutsTotal(),
      rolloutSteps: h.rolloutStepsTotal(),
      truncated: h.truncatedTotal(),
      decisionRollouts: h.decisionRollouts(),
      decisionRolloutSteps: h.decisionRolloutSteps(),
      layers: [],
      traceCount: 0,
    };
    for (const l of layers) {
      const ptr = h.renderLayer(l.name, l.palette, l.scale, l.alphaLo, l.alphaHi);
      out.layers.push({ ...l, ptr, max: h.layerMax(), min: h.layerMin(), sum: h.layerSum() });
    }
    if (this.isMcts) out.decision = h.decision();
    if (traces) {
      out.traceCount = h.collectTraces();
      out.traceCellsPtr = h.traceCellsPtr();
      out.traceOffsetsPtr = h.traceOffsetsPtr();
      out.traceTargetsPtr = h.traceTargetsPtr();
    }
    return out;
  }
}

/** Typed-array views for a snapshot; valid until the next wasm call. */
export function views(snap) {
  const buf = memoryBuffer();
  const n2 = snap.n * snap.n;
  const v = {
    path: new Uint32Array(buf, snap.pathPtr, snap.pathLen),
    layers: snap.layers.map((l) => (l.ptr ? { ...l, rgba: new Uint8ClampedArray(buf, l.ptr, 4 * n2) } : null)),
    traces: [],
    practice: -1,
  };
  if (snap.traceCount > 0) {
    const offs = new Uint32Array(buf, snap.traceOffsetsPtr, snap.traceCount + 1);
    const cells = new Uint32Array(buf, snap.traceCellsPtr, offs[snap.traceCount]);
    const targets = new Uint32Array(buf, snap.traceTargetsPtr, snap.traceCount);
    // Oldest first, so the newest is drawn on top.
    for (let i = snap.traceCount - 1; i >= 0; i--) v.traces.push(cells.subarray(offs[i], offs[i + 1]));
    v.practice = targets[0];
  }
  return v;
}
