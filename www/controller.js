// The playback state machine. It owns the requestAnimationFrame loop: each
// frame gives the engine a bounded work budget (loops in chunks, checking
// performance.now()), then asks the page to draw. It holds no game logic.
//
// States: idle | running | paused | found | capped | error, mirrored to
// document.body.dataset.state for tests.
//
// A "run" (www/engine.js) is one episode handle; race mode has two. The
// controller only calls:
//   run.stepLoops(k) -> number of real moves made (0 or more)
//   run.stepMove()
//   run.status()     -> 'running' | 'found' | 'capped'
//   run.loopsDone()  -> loops executed so far (a counter)
//   run.rolloutSteps() -> rollout lattice steps so far (a counter)

export const STATES = ['idle', 'running', 'paused', 'found', 'capped', 'error'];

const TRANSITIONS = {
  idle: ['running', 'paused', 'found', 'capped', 'error', 'idle'],
  running: ['paused', 'found', 'capped', 'error', 'idle'],
  paused: ['running', 'paused', 'found', 'capped', 'error', 'idle'],
  found: ['idle', 'error'],
  capped: ['idle', 'error'],
  error: ['idle', 'error'],
};

/** Default per-frame wasm budget in ms (the frame still has to draw). */
export const FRAME_BUDGET_MS = 8;

export class Controller {
  /**
   * @param {object} o
   * @param {() => object[]} o.createRuns   builds fresh runs from the current config
   * @param {(info) => void} o.draw          draws the runs (called once per frame)
   * @param {(state, prev) => void} [o.onState]
   * @param {(err) => void} [o.onError]
   * @param {() => number} [o.now]           clock in ms
   */
  constructor({ createRuns, draw, onState = () => {}, onError = () => {}, now = () => performance.now() }) {
    this.createRuns = createRuns;
    this.drawFn = draw;
    this.onState = onState;
    this.onError = onError;
    this.now = now;
    this.runs = [];
    this.state = 'idle';
    this.speed = 10; // loops per frame, or 'max'
    this.budgetMs = FRAME_BUDGET_MS;
    this.loopMs = 0.05; // measured cost of one loop (ms), sizes the chunks
    this.rafId = 0;
    this.dirty = true;
    this.meter = { frames: [], loops: [], steps: [], fps: 0, loopsPerS: 0, stepsPerS: 0, workMs: 0 };
    this.frame = this.frame.bind(this);
    this.setState('idle');
  }

  setState(next) {
    const prev = this.state;
    if (prev !== next && !TRANSITIONS[prev].includes(next)) {
      throw new Error(`invalid state transition ${prev} → ${next}`);
    }
    this.state = next;
    if (typeof document !== 'undefined') document.body.dataset.state = next;
    this.onState(next, prev);
    this.dirty = true;
  }

  /** Wraps engine calls: any exception (a wasm panic too) puts the page in `error`. */
  guard(fn) {
    try {
      return fn();
    } catch (err) {
      this.fail(err);
      return undefined;
    }
  }

  fail(err) {
    this.runs = [];
    if (this.state !== 'error') this.setState('error');
    this.onError(err);
    this.requestDraw();
  }

  /** (Re)builds the runs from the config; autoplay starts them. */
  reset({ autoplay = false } = {}) {
    for (const r of this.runs) r.free?.();
    this.runs = [];
    if (this.state !== 'idle') this.setState('idle');
    const runs = this.guard(() => this.createRuns());
    if (!runs) return false;
    this.runs = runs;
    this.meter.frames = [];
    this.meter.loops = [];
    this.meter.steps = [];
    this.settle();
    if (autoplay && this.isLive()) this.play();
    this.requestDraw();
    return true;
  }

  isLive() {
    return ['idle', 'running', 'paused'].includes(this.state);
  }

  play() {
    if (!this.isLive() || !this.runs.length) return;
    this.setState('running');
    this.requestDraw();
  }

  pause() {
    if (this.state === 'running' || this.state === 'idle') this.setState('paused');
  }

  toggle() {
    if (this.state === 'running') this.pause();
    else if (this.state === 'found' || this.state === 'capped') {
      this.reset({ autoplay: true });
    } else this.play();
  }

  /** One MCTS loop (selection, rollout, backpropagation) on each unfinished run. */
  stepLoop() {
    if (!this.isLive()) return;
    this.pause();
    this.guard(() => {
      for (const r of this.runs) if (r.status() === 'running') r.stepLoops(1);
    });
    this.settle();
    this.requestDraw();
  }

  /** Finishes the current decision and makes the real move, on each unfinished run. */
  stepMove() {
    if (!this.isLive()) return;
    this.pause();
    this.guard(() => {
      for (const r of this.runs) if (r.status() === 'running') r.stepMove();
    });
    this.settle();
    this.requestDraw();
  }

  setSpeed(speed) {
    this.speed = speed;
  }

  /** Moves to found/capped once every run is done. */
  settle() {
    if (!this.isLive() || !this.runs.length) return;
    const st = this.guard(() => this.runs.map((r) => r.status()));
    if (!st) return;
    if (st.every((s) => s !== 'running')) {
      // The first run is the main one; in a race the state follows it.
      this.setState(st[0] === 'capped' ? 'capped' : 'found');
    }
  }

  requestDraw() {
    this.dirty = true;
    if (!this.rafId && typeof requestAnimationFrame !== 'undefined') this.rafId = requestAnimationFrame(this.frame);
  }

  /**
   * Runs engine work for at most about budgetMs; returns loops done. Loops
   * are issued in chunks sized from the measured cost per loop so that one
   * chunk takes about a millisecond (a loop's rollout length varies a lot,
   * but the rollout cap bounds it), and never more than the time left.
   */
  work() {
    const t0 = this.now();
    const deadline = t0 + this.budgetMs;
    const max = this.speed === 'max';
    let remaining = max ? Infinity : this.speed;
    let loops = 0;
    while (remaining > 0) {
      const active = this.runs.filter((r) => r.status() === 'running');
      if (!active.length) break;
      const left = deadline - this.now();
      if (left <= 0) break;
      const perLoop = this.loopMs * active.length;
      const fit = Math.floor(Math.min(1, left) / Math.max(perLoop, 1e-4));
      const k = Math.max(1, Math.min(remaining, fit, 1 << 14));
      const c0 = this.now();
      for (const r of active) r.stepLoops(k);
      const dt = this.now() - c0;
      // Exponential average of ms per loop per run (chunks of 1 are noisy).
      this.loopMs = 0.7 * this.loopMs + 0.3 * (dt / k / active.length);
      loops += k;
      remaining -= k;
    }
    this.meter.workMs = this.now() - t0;
    return loops;
  }

  frame(ts) {
    this.rafId = 0;
    const running = this.state === 'running';
    if (running) {
      this.guard(() => this.work());
      this.settle();
    }
    if (running || this.dirty) {
      this.dirty = false;
      this.measure(ts);
      // The draw callback makes its own wasm calls first and only then builds
      // typed-array views (memory growth detaches old views).
      this.guard(() => this.drawFn({ state: this.state, meter: this.meter }));
    }
    if (this.state === 'running') this.rafId = requestAnimationFrame(this.frame);
  }

  measure(ts) {
    const m = this.meter;
    const keep = (arr, v) => {
      arr.push(v);
      while (arr.length > 2 && arr[arr.length - 1][0] - arr[0][0] > 1000) arr.shift();
    };
    if (this.state !== 'running') {
      m.frames = [];
      m.loops = [];
      m.steps = [];
      return;
    }
    let loops = 0;
    let steps = 0;
    for (const r of this.runs) {
      loops += r.loopsDone();
      steps += r.rolloutSteps();
    }
    keep(m.frames, [ts, 0]);
    keep(m.loops, [ts, loops]);
    keep(m.steps, [ts, steps]);
    const rate = (arr) => {
      if (arr.length < 2) return 0;
      const dt = (arr[arr.length - 1][0] - arr[0][0]) / 1000;
      return dt > 0 ? (arr[arr.length - 1][1] - arr[0][1]) / dt : 0;
    };
    const span = m.frames.length > 1 ? (m.frames[m.frames.length - 1][0] - m.frames[0][0]) / 1000 : 0;
    m.fps = span > 0 ? (m.frames.length - 1) / span : 0;
    m.loopsPerS = rate(m.loops);
    m.stepsPerS = rate(m.steps);
  }
}
