// The page's side of the search worker (www/search-worker.js): a request /
// answer channel, and a RunView per episode that holds what the page last
// received (counters, the path so far, heatmap renderings, traces). The page
// reads run views synchronously and never touches the worker's memory.

/** One episode as the page sees it: static facts plus the latest frame. */
export class RunView {
  constructor(info) {
    Object.assign(this, info); // label, core, isMcts, n, startCell, targetCell, optimalSteps, seed, serial
    this.snap = {
      status: 'running',
      steps: 0,
      position: info.startCell,
      loopsDone: 0,
      loopsTotal: 0,
      rollouts: 0,
      rolloutSteps: 0,
      truncated: 0,
      decisionRollouts: 0,
      decisionRolloutSteps: 0,
      decision: null,
    };
    this.pathBuf = new Uint32Array(256);
    this.pathLen = 0;
    this.layers = new Map(); // name -> { key, rgba, min, max, sum }
    this.traces = [];
    this.practice = -1;
  }

  /** The frame request for this run: which layers, and what the page already holds. */
  request(layers, traces) {
    const have = {};
    for (const l of layers) {
      const got = this.layers.get(l.name);
      if (got) have[l.name] = got.key;
    }
    return { layers, have, pathHave: this.pathLen, traces };
  }

  /** Takes in one frame from the worker. */
  apply(f) {
    const { path, pathFrom, layers, traces, practice, ...snap } = f;
    this.snap = snap;
    const len = pathFrom + path.length;
    if (len > this.pathBuf.length) {
      const grown = new Uint32Array(Math.max(len, 2 * this.pathBuf.length));
      grown.set(this.pathBuf.subarray(0, pathFrom));
      this.pathBuf = grown;
    }
    this.pathBuf.set(path, pathFrom);
    this.pathLen = len;
    for (const l of layers) {
      if (!l.same) this.layers.set(l.name, l);
    }
    if (traces !== null) {
      this.traces = traces;
      this.practice = practice;
    } else {
      this.traces = [];
      this.practice = -1;
    }
  }

  status() {
    return this.snap.status;
  }

  steps() {
    return this.snap.steps;
  }

  /** Loops so far (moves for a walker). */
  loopsDone() {
    return this.snap.loopsTotal;
  }

  rolloutSteps() {
    return this.snap.rolloutSteps;
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
 * The request / answer channel to one search worker. Requests are answered
 * in order. After a trap the worker is replaced by a fresh one at the next
 * reset.
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
    this.worker = new Worker(new URL('./search-worker.js', import.meta.url), { type: 'module' });
    this.worker.onmessage = (e) => this.receive(e.data);
    this.worker.onerror = (e) => {
      e.preventDefault?.();
      const err = new EngineError(`the search worker failed: ${e.message || 'could not load www/search-worker.js'}`, false);
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
  request(type, payload = {}, transfer = []) {
    const id = this.nextId++;
    return new Promise((resolve, reject) => {
      this.pending.set(id, { resolve, reject });
      this.worker.postMessage({ type, id, ...payload }, transfer);
    });
  }

  /** Builds fresh runs; resolves to their RunViews (the controller drops overtaken ones). */
  async reset(spec) {
    if (this.trapped) this.spawn();
    await this.ready;
    const gen = ++this.gen;
    const answer = await this.request('reset', { gen, ...spec });
    return answer.runs.map((info) => new RunView(info));
  }

  /** True if an answer belongs to the current runs. */
  current(answer) {
    return answer.gen === this.gen;
  }

  terminate() {
    this.worker?.terminate();
    this.worker = null;
  }
}
