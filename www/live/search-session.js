// The page's side of the search worker (www/workers/search-worker.js): a request /
// answer channel, and a RunView per run that holds what the page was last
// sent (the frame header, the path so far, heatmap renderings, traces). The
// page reads run views synchronously and never touches the worker's memory.

import { scriptURL } from '../shared/trusted.js';

/** One run as the page sees it: fixed facts plus the latest frame. */
export class RunView {
  /** @param {object} info one entry of the engine's Race.describe() */
  constructor(info) {
    // label, config, searcher, deliberates, help, n, start, target, optimal, lower_bound
    Object.assign(this, info);
    this.frame = {
      status: 'running',
      steps: 0,
      position: info.start,
      loops_done: 0,
      work: 0,
      rollouts: 0,
      rollout_steps: 0,
      truncated: 0,
      decision_rollouts: 0,
      decision_rollout_steps: 0,
      ratio: null,
      searched_mass: 0,
      decision: null,
    };
    this.pathBuf = new Uint32Array(256);
    this.pathLen = 0;
    this.layers = new Map(); // layer name -> { key, rgba, min, min_nonzero, max, sum }
    this.traces = [];
    this.practice = -1;
    this.intent = null; // Uint32Array: the position, then the cells a planner means to enter
    // Where this run branched from the run before it (the engine's lineage), or −1.
    this.branchAt = info.lineage?.length ? info.lineage.at(-1).move : -1;
  }

  /**
   * This run's frame request for the page's view: which layers (with the
   * key of the rendering held, so unchanged ones are not resent), the path
   * from where it is held, and traces for a searcher that deliberates.
   * @param {{ layers: object[], traces: boolean, intent: boolean }} view
   */
  request(view) {
    return {
      layers: view.layers.map((l) => ({ ...l, have: this.layers.get(l.layer)?.key ?? null })),
      path_from: this.pathLen,
      traces: view.traces && this.deliberates,
      intent: !!view.intent,
    };
  }

  /**
   * The renderings held for `requested` layers, bottom to top, each with the
   * scale it was asked in (layers this run lacks are left out).
   */
  drawnLayers(requested) {
    return requested.flatMap((l) => (this.layers.has(l.layer) ? [{ ...this.layers.get(l.layer), scale: l.scale }] : []));
  }

  /** Takes in one frame from the worker. */
  apply(f) {
    const { path, path_from: from, layers, traces, practice, intent, ...header } = f;
    this.frame = header;
    const cells = new Uint32Array(path.buffer, path.byteOffset, path.byteLength / 4);
    const len = from + cells.length;
    if (len > this.pathBuf.length) {
      const grown = new Uint32Array(Math.max(len, 2 * this.pathBuf.length));
      grown.set(this.pathBuf.subarray(0, from));
      this.pathBuf = grown;
    }
    this.pathBuf.set(cells, from);
    this.pathLen = len;
    for (const l of layers) {
      if (l.same) continue;
      const rgba = new Uint8ClampedArray(l.rgba.buffer, l.rgba.byteOffset, l.rgba.byteLength);
      this.layers.set(l.layer, { ...l, rgba });
    }
    this.traces = (traces ?? []).map((t) => new Uint32Array(t.buffer, t.byteOffset, t.byteLength / 4));
    this.practice = practice ?? -1;
    if (intent && intent.byteLength) {
      // Drawn from where the searcher stands, so it joins the path.
      const cells = new Uint32Array(intent.byteLength / 4 + 1);
      cells[0] = header.position;
      cells.set(new Uint32Array(intent.buffer, intent.byteOffset, intent.byteLength / 4), 1);
      this.intent = cells;
    } else {
      this.intent = null;
    }
  }

  status() {
    return this.frame.status;
  }

  /** Work so far: loops, or moves for a walker. */
  work() {
    return this.frame.work;
  }

  rolloutSteps() {
    return this.frame.rollout_steps;
  }

  /** The path so far as received (cells, start first). */
  path() {
    return Array.from(this.pathBuf.subarray(0, this.pathLen));
  }

  pathView() {
    return this.pathBuf.subarray(0, this.pathLen);
  }
}

/** An error from the worker; `trap` marks a wasm trap (a Rust panic). */
export class EngineError extends Error {
  constructor(message, trap) {
    super(message);
    this.name = 'EngineError';
    this.trap = !!trap;
  }
}

/**
 * The request / answer channel to one search worker. Answers are matched to
 * requests by id: most come in order, but a Step move a planner has yet to
 * plan is answered after the requests sent while it was made. After a trap
 * the worker is replaced by a fresh one at the next reset.
 */
export class SearchSession {
  constructor(module) {
    this.module = module;
    this.worker = null;
    this.pending = new Map();
    this.nextId = 1;
    this.gen = 0;
    this.spawn();
  }

  spawn() {
    this.worker?.terminate();
    for (const p of this.pending.values()) p.reject(new EngineError('the search worker was restarted', false));
    this.pending.clear();
    this.worker = new Worker(scriptURL(new URL('../workers/search-worker.js', import.meta.url)), { type: 'module' });
    this.worker.onmessage = (e) => this.receive(e.data);
    this.worker.onerror = (e) => {
      e.preventDefault?.();
      const err = new EngineError(`the search worker failed: ${e.message || 'could not load www/workers/search-worker.js'}`, false);
      for (const p of this.pending.values()) p.reject(err);
      this.pending.clear();
    };
    this.trapped = false;
    this.ready = this.request('init', { module: this.module });
  }

  receive(msg) {
    const p = this.pending.get(msg.id);
    if (msg.ok === false && msg.trap) this.trapped = true;
    if (!p) return;
    this.pending.delete(msg.id);
    if (msg.ok) p.resolve(msg);
    else p.reject(new EngineError(msg.error, msg.trap));
  }

  /** Sends a request; resolves to the answer, rejects with an EngineError. */
  request(type, payload = {}) {
    const id = this.nextId++;
    return new Promise((resolve, reject) => {
      this.pending.set(id, { resolve, reject });
      this.worker.postMessage({ type, id, ...payload });
    });
  }

  /** Builds fresh runs from engine configs; resolves to their RunViews. */
  async reset(configs) {
    if (this.trapped) this.spawn();
    await this.ready;
    const gen = ++this.gen;
    const answer = await this.request('reset', { gen, configs });
    return answer.runs.map((info) => new RunView(info));
  }

  /**
   * Branches the runs at `move` with new engine configs; resolves to their
   * RunViews. The generation moves on only once the worker has branched
   * (it answers in order, so every answer before this one is the old
   * runs'); a refusal rejects and leaves the runs and generation as they were.
   */
  async branch(configs, move) {
    const gen = this.gen + 1;
    const answer = await this.request('branch', { gen, configs, move });
    this.gen = gen;
    return answer.runs.map((info) => new RunView(info));
  }

  /** True if an answer belongs to the current runs. */
  current(answer) {
    return answer.gen === this.gen;
  }
}
