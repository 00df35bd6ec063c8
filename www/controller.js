// The playback state machine. It owns the requestAnimationFrame loop. The
// search itself runs in a worker (www/search-worker.js, reached through
// www/search-session.js): each frame the controller draws the latest frame
// the worker sent and asks for the next one, so the page's thread only draws
// and never blocks on the search. It holds no game logic.
//
// States: idle | running | paused | found | capped | error, mirrored to
// document.body.dataset.state for tests.
//
// A run is a RunView (www/search-session.js); race mode has two. The
// controller reads run.status(), run.loopsDone(), run.rolloutSteps() and
// feeds run.apply(frame).

export const STATES = ['idle', 'running', 'paused', 'found', 'capped', 'error'];

const TRANSITIONS = {
  idle: ['running', 'paused', 'found', 'capped', 'error', 'idle'],
  running: ['paused', 'found', 'capped', 'error', 'idle'],
  paused: ['running', 'paused', 'found', 'capped', 'error', 'idle'],
  found: ['idle', 'error'],
  capped: ['idle', 'error'],
  error: ['idle', 'error'],
};

export class Controller {
  /**
   * @param {object} o
   * @param {object} o.session              a SearchSession (or a stand-in with reset/request/current)
   * @param {() => object} o.spec            the reset request for the current config: { runs: [{ core, label }], seed }
   * @param {(runs) => object[]} o.views     the frame request for each run (layers, what the page holds)
   * @param {(runs) => void} [o.onRuns]      called with fresh runs, before their first frame is drawn
   * @param {(info) => void} o.draw          draws the runs (called once per frame that has news)
   * @param {(state, prev) => void} [o.onState]
   * @param {(err) => void} [o.onError]
   * @param {(fn) => number} [o.raf]          requestAnimationFrame
   */
  constructor({ session, spec, views, onRuns = () => {}, draw, onState = () => {}, onError = () => {}, raf = null }) {
    this.session = session;
    this.spec = spec;
    this.views = views;
    this.onRuns = onRuns;
    this.drawFn = draw;
    this.onState = onState;
    this.onError = onError;
    this.raf = raf ?? (typeof requestAnimationFrame !== 'undefined' ? (fn) => requestAnimationFrame(fn) : null);
    this.runs = [];
    this.state = 'idle';
    this.speed = 10; // loops per frame, or 'max'
    this.rafId = 0;
    this.dirty = true;
    this.wantFrame = false;
    this.inflight = false;
    this.resets = 0;
    this.ready = Promise.resolve(false);
    this.meter = { frames: [], loops: [], steps: [], fps: 0, loopsPerS: 0, stepsPerS: 0 };
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

  fail(err) {
    this.runs = [];
    if (this.state !== 'error') this.setState('error');
    this.session.request('pause').catch(() => {});
    this.onError(err);
    this.requestDraw();
  }

  /** Sends a request to the worker; a failure puts the page in `error` and resolves to null. */
  async send(type, payload = {}) {
    const runs = this.runs;
    try {
      return await this.session.request(type, payload);
    } catch (err) {
      // A stale request's failure does not concern the current runs, unless
      // the engine trapped; after a failure, later ones only echo it.
      if (this.state !== 'error' && (runs === this.runs || err.trap)) this.fail(err);
      return null;
    }
  }

  /**
   * (Re)builds the runs from the config; autoplay starts them. Resolves to
   * true once the fresh runs have their first frame (false if it failed or a
   * newer reset overtook it).
   */
  reset(opts) {
    this.ready = this.resetNow(opts);
    return this.ready;
  }

  /** Resolves once the newest reset has finished (tests and tools wait on it). */
  async whenReady() {
    let p;
    do {
      p = this.ready;
      await p;
    } while (p !== this.ready);
    return this.runs.length > 0;
  }

  async resetNow({ autoplay = false } = {}) {
    const ticket = ++this.resets;
    this.runs = [];
    if (this.state !== 'idle') this.setState('idle');
    let runs;
    try {
      runs = await this.session.reset(this.spec());
    } catch (err) {
      if (ticket === this.resets) this.fail(err);
      return false;
    }
    if (ticket !== this.resets) return false;
    this.runs = runs;
    this.meter.frames = [];
    this.meter.loops = [];
    this.meter.steps = [];
    this.onRuns(runs);
    if (!(await this.refresh())) return false;
    this.settle();
    if (autoplay && this.isLive()) this.play();
    return ticket === this.resets;
  }

  isLive() {
    return ['idle', 'running', 'paused'].includes(this.state);
  }

  play() {
    if (!this.isLive() || !this.runs.length) return;
    this.setState('running');
    this.send('play', { speed: this.speed });
    this.requestDraw();
  }

  pause() {
    if (this.state === 'running' || this.state === 'idle') {
      this.setState('paused');
      this.send('pause');
      // The worker may have searched on since the last frame: show where it stopped.
      this.requestDraw();
    }
  }

  toggle() {
    if (this.state === 'running') this.pause();
    else if (this.state === 'found' || this.state === 'capped') {
      this.reset({ autoplay: true });
    } else this.play();
  }

  /** One MCTS loop (selection, rollout, backpropagation) on each unfinished run. */
  stepLoop() {
    return this.step('stepLoop');
  }

  /** Finishes the current decision and makes the real move, on each unfinished run. */
  stepMove() {
    return this.step('stepMove');
  }

  async step(type) {
    if (!this.isLive() || !this.runs.length) return;
    this.pause();
    const runs = this.runs;
    const answer = await this.send(type, { views: this.views(runs) });
    this.take(answer, runs);
  }

  setSpeed(speed) {
    this.speed = speed;
    this.send('speed', { speed });
  }

  /** Applies a frame answer if it is for the current runs; true if applied. */
  take(answer, runs) {
    if (!answer || runs !== this.runs || !this.session.current(answer)) return false;
    answer.frames.forEach((f, i) => runs[i].apply(f));
    this.settle();
    this.dirty = true;
    this.schedule();
    return true;
  }

  /** Asks for a fresh frame now (no search at a set speed beyond the usual). */
  async refresh() {
    const runs = this.runs;
    if (!runs.length) return false;
    const answer = await this.send('frame', { views: this.views(runs) });
    return this.take(answer, runs);
  }

  /** Moves to found/capped once every run is done. */
  settle() {
    if (!this.isLive() || !this.runs.length) return;
    const st = this.runs.map((r) => r.status());
    if (st.every((s) => s !== 'running')) {
      // The first run is the main one; in a race the state follows it.
      this.setState(st[0] === 'capped' ? 'capped' : 'found');
    }
  }

  /** Redraws, with a fresh frame from the worker (layer choices may have changed). */
  requestDraw() {
    this.dirty = true;
    this.wantFrame = true;
    this.schedule();
  }

  schedule() {
    if (!this.rafId && this.raf) this.rafId = this.raf(this.frame);
  }

  /** One animation frame: ask for the next frame of the search, and draw what has arrived. */
  frame(ts) {
    this.rafId = 0;
    const running = this.state === 'running';
    if ((running || this.wantFrame) && !this.inflight && this.runs.length) {
      this.wantFrame = false;
      this.inflight = true;
      this.refresh().finally(() => {
        this.inflight = false;
        if (this.wantFrame) this.schedule();
      });
    }
    if (this.dirty) {
      this.dirty = false;
      this.measure(ts);
      try {
        this.drawFn({ state: this.state, meter: this.meter });
      } catch (err) {
        this.fail(err);
      }
    }
    if (this.state === 'running') this.schedule();
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
