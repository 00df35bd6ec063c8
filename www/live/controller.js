// The playback state machine. It owns the requestAnimationFrame loop and
// takes commands one way, through dispatch(); what happens comes back as
// events. The search runs in a worker (www/workers/search-worker.js, reached
// through www/live/search-session.js): each animation frame the controller asks
// for the next frame of the search and hands the latest one to its 'frame'
// listeners, so the page's thread only draws. It holds no game logic.
//
// States: idle | running | paused | choosing | found | capped | error,
// mirrored to document.body.dataset.state for tests. `choosing`: paused, with
// an edit offered as a branch or a restart (`offer` holds it) until one is chosen.
//
// Commands (dispatch({ type, ... })):
//   reset { configs, autoplay, paused }  fresh runs from engine configs; resolves once they
//                                have a frame (paused: they wait in `paused` rather than `idle`)
//   play | pause | toggle        playback
//   stepLoop | stepMove          one MCTS loop / one real move on each unfinished run (pauses first)
//   stepPhase                    one phase of the loop in flight (select, expand, roll out, back up)
//   seek { point }               every run to a timeline point { move, loop, phase } it has reached
//   advanceTo { point }          steps forward to a point not reached yet, then seeks it (a link's `at`)
//   back { unit }                one phase | loop | move back (seek and back pause first, and bring
//                                a found or capped run back to paused; a bad point leaves the runs
//                                as they were and resolves to { ok: false, error })
//   offer { offer }              paused → choosing: an edit waits for a choice (`offer`: the
//                                caller's { config, move, ... }, held until then)
//   cancel                       choosing → paused: the edit dropped, the runs as they were
//   branch { configs, move }     the runs branched at `move` (made first if not reached) with new
//                                configs, paused there; resolves to { ok } or { ok: false, error }
//                                (then a `message`, and the runs as they were)
//   speed { speed }              loops per frame, or 'max'
//   view { view }                what frames carry: { layers: [layer requests], traces: bool }
//   redraw                       draw again with a fresh frame (view options changed)
//   animate                      draw again at the next animation frame, with the frame held
//                                (motion on the board: a glide, a fade, a pulse)
//   export                       resolves to each run's export (config, path, result)
//   request { request, payload } a raw worker request (benchmarks, tests)
//   ask { request, payload }     a raw worker request whose failure is the caller's (rejects; the
//                                page stays as it was): the tree view's queries
// Events (on(name, fn)):
//   state (state, prev) · runs (runViews) · frame ({ state, meter, runs, timeline }) · error (err)
//   · message (text): a command refused (a seek past the end), the runs unchanged
// `timeline` is the engine's: { move, loop, phase, end: { move, loop, phase } } of the first run.

const TRANSITIONS = {
  idle: ['running', 'paused', 'found', 'capped', 'error', 'idle'],
  running: ['paused', 'found', 'capped', 'error', 'idle'],
  paused: ['running', 'paused', 'choosing', 'found', 'capped', 'error', 'idle'],
  choosing: ['paused', 'idle', 'error'],
  found: ['idle', 'paused', 'error'],
  capped: ['idle', 'paused', 'error'],
  error: ['idle', 'error'],
};

export class Controller {
  /**
   * @param {object} o
   * @param {object} o.session            a SearchSession (or a stand-in with reset/request/current)
   * @param {(fn) => number} [o.raf]       requestAnimationFrame
   */
  constructor({ session, raf = null }) {
    this.session = session;
    this.raf = raf ?? (typeof requestAnimationFrame !== 'undefined' ? (fn) => requestAnimationFrame(fn) : null);
    this.listeners = { state: [], runs: [], frame: [], error: [], message: [] };
    this.timeline = null;
    this.runs = [];
    this.offer = null; // the edit waiting for a choice (state choosing)
    this.view = { layers: [], traces: false };
    this.state = 'idle';
    this.speed = 10;
    this.scheduled = false; // an animation frame is asked for (a flag: a held or shimmed rAF may return no id)
    this.dirty = true;
    this.wantFrame = false;
    this.inflight = false;
    this.stepping = 0; // steps the worker has yet to answer
    this.resets = 0;
    this.ready = Promise.resolve(false);
    this.meter = { frames: [], loops: [], steps: [], fps: 0, loopsPerS: 0, stepsPerS: 0 };
    this.tick = this.tick.bind(this);
    this.setState('idle');
  }

  /** Subscribes to an event; returns the unsubscribe function. */
  on(name, fn) {
    this.listeners[name].push(fn);
    return () => {
      this.listeners[name] = this.listeners[name].filter((f) => f !== fn);
    };
  }

  emit(name, ...args) {
    for (const fn of this.listeners[name]) fn(...args);
  }

  /** The one way in: see the command list at the top of this file. */
  dispatch(cmd) {
    switch (cmd.type) {
      case 'reset':
        this.ready = this.reset(cmd.configs, cmd.autoplay, cmd.paused);
        return this.ready;
      case 'play':
        return this.play();
      case 'pause':
        return this.pause();
      case 'toggle':
        return this.toggle();
      case 'stepLoop':
      case 'stepMove':
      case 'stepPhase':
        return this.step(cmd.type);
      case 'seek':
        return this.travel('seek', { point: cmd.point });
      case 'back':
        return this.travel('back', { unit: cmd.unit });
      case 'advanceTo':
        return this.travel('advanceTo', { point: cmd.point });
      case 'offer':
        if (this.state !== 'paused' && this.state !== 'choosing') return false;
        this.offer = cmd.offer;
        this.setState('choosing');
        return true;
      case 'cancel':
        if (this.state !== 'choosing') return false;
        this.offer = null;
        this.setState('paused');
        this.redraw();
        return true;
      case 'branch':
        this.ready = this.branch(cmd.configs, cmd.move);
        return this.ready;
      case 'speed':
        this.speed = cmd.speed;
        this.send('speed', { speed: cmd.speed });
        return undefined;
      case 'view':
        this.view = cmd.view;
        return this.redraw();
      case 'redraw':
        return this.redraw();
      case 'animate':
        this.dirty = true;
        return this.schedule();
      case 'export':
        return this.send('export').then((a) => a?.runs ?? null);
      case 'request':
        return this.send(cmd.request, cmd.payload ?? {});
      case 'ask':
        return this.session.request(cmd.request, cmd.payload ?? {});
      default:
        throw new Error(`unknown command ${JSON.stringify(cmd.type)}`);
    }
  }

  setState(next) {
    const prev = this.state;
    if (prev !== next && !TRANSITIONS[prev].includes(next)) {
      throw new Error(`invalid state transition ${prev} → ${next}`);
    }
    this.state = next;
    if (typeof document !== 'undefined') document.body.dataset.state = next;
    this.emit('state', next, prev);
    this.dirty = true;
  }

  fail(err) {
    this.runs = [];
    if (this.state !== 'error') this.setState('error');
    this.session.request('pause').catch(() => {});
    this.emit('error', err);
    this.redraw();
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

  /** Resolves once the newest reset has finished (tests and tools wait on it). */
  async whenReady() {
    let p;
    do {
      p = this.ready;
      await p;
    } while (p !== this.ready);
    return this.runs.length > 0;
  }

  /**
   * (Re)builds the runs. Resolves to true once the fresh runs have their
   * first frame (false if it failed or a newer reset overtook it). With
   * `paused` they wait in `paused` (an edit made while paused), else in
   * `idle` unless `autoplay`.
   */
  async reset(configs, autoplay = false, paused = false) {
    const ticket = ++this.resets;
    this.runs = [];
    this.offer = null;
    if (this.state !== 'idle') this.setState('idle');
    let runs;
    try {
      runs = await this.session.reset(configs);
    } catch (err) {
      if (ticket === this.resets) this.fail(err);
      return false;
    }
    if (ticket !== this.resets) return false;
    this.runs = runs;
    this.timeline = null;
    this.meter.frames = [];
    this.meter.loops = [];
    this.meter.steps = [];
    this.emit('runs', runs);
    if (!(await this.refresh())) return false;
    this.settle();
    if (autoplay && this.isLive()) this.play();
    else if (paused && this.state === 'idle') this.setState('paused');
    return ticket === this.resets;
  }

  /**
   * Branches the paused runs at `move` with `configs` (an offer chosen, or
   * a link's branch). Nothing is sent for the old runs meanwhile; once the
   * worker has branched, the fresh runs wait in `paused` with their frame.
   * Refused, the runs stay as they were, with a `message`.
   */
  async branch(configs, move) {
    if (!['paused', 'choosing'].includes(this.state) || !this.runs.length || this.stepping) {
      return { ok: false, error: `branch: the run must be paused, not ${this.state}` };
    }
    const ticket = ++this.resets;
    const old = this.runs;
    this.offer = null;
    if (this.state === 'choosing') this.setState('paused');
    this.runs = [];
    let runs;
    try {
      runs = await this.session.branch(configs, move);
    } catch (err) {
      if (ticket !== this.resets) return { ok: false, error: err.message };
      if (err.trap) this.fail(err);
      else {
        this.runs = old;
        this.emit('message', err.message);
        this.redraw();
      }
      return { ok: false, error: err.message };
    }
    if (ticket !== this.resets) return { ok: false, error: 'branch: overtaken by a reset' };
    this.runs = runs;
    this.timeline = null;
    this.emit('runs', runs);
    if (!(await this.refresh())) return { ok: false, error: 'branch: overtaken by a reset' };
    this.settle();
    return { ok: true };
  }

  isLive() {
    return ['idle', 'running', 'paused'].includes(this.state);
  }

  play() {
    if (!this.isLive() || !this.runs.length) return;
    this.setState('running');
    this.send('play', { speed: this.speed });
    this.redraw();
  }

  pause() {
    if (this.state === 'running' || this.state === 'idle') {
      this.setState('paused');
      this.send('pause');
      // The worker may have searched on since the last frame: show where it stopped.
      this.redraw();
    }
  }

  toggle() {
    if (this.state === 'running') this.pause();
    else if (this.state === 'found' || this.state === 'capped') {
      // Replay the same runs from the start.
      const configs = this.runs.map((r) => r.config);
      this.dispatch({ type: 'reset', configs, autoplay: true });
    } else this.play();
  }

  async step(type) {
    if (!this.isLive() || !this.runs.length) return;
    this.pause();
    const runs = this.runs;
    // A move a planner has yet to plan can take seconds: ask for frames
    // meanwhile, so its progress shows.
    this.stepping++;
    this.redraw();
    try {
      const answer = await this.send(type, { requests: this.requests(runs) });
      this.take(answer, runs);
    } finally {
      this.stepping--;
    }
  }

  /**
   * A seek or a step back: pauses, and moves the runs on their timeline.
   * Resolves to { ok: true } once the page holds the frame there, or to
   * { ok: false, error } when the engine refused (the runs as they were).
   */
  async travel(type, payload) {
    const runs = this.runs;
    if (!runs.length || !['idle', 'running', 'paused', 'found', 'capped'].includes(this.state)) return { ok: false, error: `${type}: no runs to move` };
    this.pause();
    let answer;
    try {
      answer = await this.session.request(type, { ...payload, requests: this.requests(runs) });
    } catch (err) {
      if (err.trap) {
        this.fail(err);
        return { ok: false, error: err.message };
      }
      this.emit('message', err.message);
      return { ok: false, error: err.message };
    }
    if (!this.take(answer, runs)) return { ok: false, error: `${type}: the runs were replaced meanwhile` };
    // Back before the end of a finished run: it can be played on again.
    if ((this.state === 'found' || this.state === 'capped') && runs.some((r) => r.status() === 'running')) this.setState('paused');
    return { ok: true };
  }

  requests(runs) {
    return runs.map((r) => r.request(this.view));
  }

  /** Applies a frame answer if it is for the current runs; true if applied. */
  take(answer, runs) {
    if (!answer || runs !== this.runs || !this.session.current(answer)) return false;
    answer.frames.forEach((f, i) => runs[i].apply(f));
    if (answer.timeline) this.timeline = answer.timeline;
    this.settle();
    this.dirty = true;
    this.schedule();
    return true;
  }

  /** Asks for a fresh frame now (at a set speed the worker searches a frame's worth first). */
  async refresh() {
    const runs = this.runs;
    if (!runs.length) return false;
    const answer = await this.send('frame', { requests: this.requests(runs) });
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

  /** Draws again, with a fresh frame from the worker. */
  redraw() {
    this.dirty = true;
    this.wantFrame = true;
    this.schedule();
  }

  schedule() {
    if (this.scheduled || !this.raf) return;
    this.scheduled = true;
    this.raf(this.tick);
  }

  /** One animation frame: ask for the next frame of the search, and draw what has arrived. */
  tick(ts) {
    this.scheduled = false;
    const running = this.state === 'running' || this.stepping > 0;
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
        this.emit('frame', { state: this.state, meter: this.meter, runs: this.runs, timeline: this.timeline });
      } catch (err) {
        this.fail(err);
      }
    }
    if (running) this.schedule();
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
      loops += r.work();
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
