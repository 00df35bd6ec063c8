// The door into the wasm engine (www/pkg, built from src/wasm.rs). It is
// loaded twice: by the page, for small helpers (palettes, config checks,
// batch summaries), and by the search worker (www/search-worker.js), which
// holds the episodes. It translates the URL-level config (www/url-state.js)
// into the core's Config object and wraps one episode handle per run. No game
// logic lives here.

import init, * as wasm from './pkg/torus_search.js';

let exports = null;
let compiled = null;

/**
 * Loads and instantiates the wasm module once; resolves to the module namespace.
 * `module`: an already compiled WebAssembly.Module (the page hands its own to
 * the search worker, so the bytes are fetched and compiled once).
 */
export async function loadEngine(module = null) {
  if (exports) return wasm;
  if (!module) {
    const url = new URL('./pkg/torus_search_bg.wasm', import.meta.url);
    const res = await fetch(url);
    if (!res.ok) throw new Error(`${url.pathname}: HTTP ${res.status}`);
    module = await WebAssembly.compile(await res.arrayBuffer());
  }
  compiled = module;
  exports = await init({ module_or_path: module });
  return wasm;
}

/** The compiled module (after loadEngine), to share with workers. */
export function engineModule() {
  return compiled;
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
   * Everything the page needs to draw this run, copied out of wasm memory
   * (the page's thread cannot see this worker's memory). Each view over wasm
   * memory is built right after the call that produced it and copied before
   * the next call, because memory growth detaches views.
   *
   * req = { layers: [{ name, palette, scale, alphaLo, alphaHi, dep }],
   *         have: { [name]: key } (renderings the page already holds),
   *         pathHave: path entries the page already holds, traces: bool }
   * Buffers to transfer (not clone) are pushed onto `transfer`. `playing`:
   * the worker is searching on its own, so big layers may lag a little.
   */
  frame(req, transfer, playing = false) {
    const h = this.h;
    const n2 = this.n * this.n;
    const steps = h.steps();
    const rollouts = h.rolloutsTotal();
    const out = {
      status: h.status(),
      steps,
      position: h.position(),
      loopsDone: h.loopsDone(),
      loopsTotal: this.loopsDone(),
      rollouts,
      rolloutSteps: h.rolloutStepsTotal(),
      truncated: h.truncatedTotal(),
      decisionRollouts: h.decisionRollouts(),
      decisionRolloutSteps: h.decisionRolloutSteps(),
      decision: this.isMcts ? h.decision() : null,
      pathFrom: 0,
      path: null,
      layers: [],
      traces: null,
      practice: -1,
    };
    const len = h.pathLen();
    out.pathFrom = req.pathHave <= len ? req.pathHave : 0;
    out.path = new Uint32Array(memoryBuffer(), h.pathPtr(), len).slice(out.pathFrom);
    transfer.push(out.path.buffer);
    // While the search runs at full tilt, layers that change with every loop
    // or move are recoloured at most ~30 times a second above 128×128 cells
    // and ~8 times above 362×362 (the canvas still redraws every frame):
    // recolouring and copying them out would take the worker's time from the
    // search. Paused or stepped, every change shows at once.
    const period = !playing ? 0 : n2 > 1 << 17 ? 120 : n2 > 1 << 14 ? 33 : 0;
    const tick = period ? `t${Math.floor(performance.now() / period)}` : null;
    for (const l of req.layers) {
      const exact = l.dep === 'steps' ? `${steps}` : `${steps}:${rollouts}`;
      const dep = l.dep === 'static' ? '' : (tick ?? exact);
      const key = `${this.serial}:${l.name}:${l.palette}|${l.scale}|${l.alphaLo}|${l.alphaHi}|${dep}`;
      if (req.have?.[l.name] === key) {
        out.layers.push({ name: l.name, key, same: true });
        continue;
      }
      const ptr = h.renderLayer(l.name, l.palette, l.scale, l.alphaLo, l.alphaHi);
      if (!ptr) continue;
      const rgba = new Uint8ClampedArray(memoryBuffer(), ptr, 4 * n2).slice();
      transfer.push(rgba.buffer);
      out.layers.push({ name: l.name, key, rgba, max: h.layerMax(), min: h.layerMin(), sum: h.layerSum() });
    }
    if (req.traces && this.isMcts) {
      const count = h.collectTraces();
      if (count > 0) {
        const offsPtr = h.traceOffsetsPtr();
        const cellsPtr = h.traceCellsPtr();
        const targetsPtr = h.traceTargetsPtr();
        const buf = memoryBuffer();
        const offs = new Uint32Array(buf, offsPtr, count + 1);
        const cells = new Uint32Array(buf, cellsPtr, offs[count]);
        out.practice = new Uint32Array(buf, targetsPtr, count)[0];
        // Oldest first, so the newest is drawn on top.
        out.traces = [];
        for (let i = count - 1; i >= 0; i--) out.traces.push(cells.slice(offs[i], offs[i + 1]));
        for (const t of out.traces) transfer.push(t.buffer);
      }
    }
    return out;
  }

  /** What the page's run view needs once, when the run is created. */
  describe() {
    return {
      label: this.label,
      core: this.core,
      isMcts: this.isMcts,
      n: this.n,
      startCell: this.startCell,
      targetCell: this.targetCell,
      optimalSteps: this.optimalSteps,
      seed: String(this.h.seed()),
      serial: this.serial,
    };
  }

  /** The episode for export: the engine's config and result, and the whole path. */
  exportData() {
    return { label: this.label, core_config: this.h.config(), path: this.path(), result: this.h.result(), status: this.status() };
  }
}
