// The live view's state: the engine config (edited only through the
// engine) and the view parameters (speed, autoplay, race), and the ONE path
// by which they change: change() loads a painting, shows the config in the
// form, writes the URL and restarts the runs. Every edit, preset, opened
// experiment point, replay, race and speed goes through it. An edit made
// while the run is paused after move 0 waits for a choice (the controller's
// `choosing` state): a branch from that move, keeping the path so far, or a
// restart; a change of the world (n, prior, target, …) cannot branch, and restarts.

import { writeUrl, opponentConfig, pointToAt, atToPoint, parseBranch, formatBranch } from '../shared/url-state.js';
import { showMessage } from '../shared/ui.js';
import { reducedMotion } from './motion.js';

export class LiveState {
  /**
   * @param {object} o
   * @param {object} o.engine, o.schema, o.races   the wasm module, its schema, the race options
   * @param {object} o.controller, o.painter, o.form, o.controls, o.viewState   the live view's parts
   * @param {object} o.config, o.view              the starting config and view parameters
   * @param {() => void} o.onUrl                   writes the page's URL (it reads query())
   */
  constructor({ engine, schema, races, controller, painter, form, controls, viewState, config, view, onUrl }) {
    Object.assign(this, { engine, races, controller, painter, form, controls, viewState, config, view, onUrl });
    this.paintKeys = schema.params.filter((p) => p.kind === 'paint').map((p) => p.key);
    this.kept = null; // keep_traces of the runs under way
    this.trapped = false;
    this.restarted = [];
    this.last = { autoplay: false, paused: false }; // the newest restart's
    controller.on('error', (err) => {
      this.trapped = err instanceof WebAssembly.RuntimeError;
    });
    // An offer left (chosen, cancelled or overtaken): the form shows the config of the runs.
    controller.on('state', (s, prev) => {
      if (prev === 'choosing') this.showForm(this.config);
    });
    // Fresh or branched runs: the URL names their branch points.
    controller.on('runs', () => this.onUrl());
    // A run stopped at a point: the URL says where (a link reopens it there, paused).
    let at = '';
    controller.on('frame', () => {
      const now = this.at();
      if (now !== at) {
        at = now;
        this.onUrl();
      }
    });
  }

  /**
   * The one path for a change: takes `config` and the `view` parameters
   * given, shows them, writes the URL and (unless `restart` is false)
   * restarts the runs, with `note` shown once they start. Resolves as
   * restart() does.
   */
  change({ config = this.config, view = {}, autoplay, note = '', restart = true } = {}) {
    this.config = config;
    // A link's layers and point are applied once, here; the page then keeps them.
    const { show, at, branch, ...rest } = view;
    this.view = { ...this.view, ...rest };
    if (show) {
      const unknown = this.viewState.applyShown(show);
      if (unknown.length) note = [note, `Unknown layers in show=: ${unknown.join(', ').slice(0, 80)} (ignored).`].filter(Boolean).join('\n');
      this.controller.dispatch({ type: 'view', view: this.viewState.frameView() });
    }
    if (branch && restart) return this.openBranch(branch, at, note);
    if (at && restart) return this.openAt(atToPoint(at), note);
    if (view.speed !== undefined) this.controller.dispatch({ type: 'speed', speed: this.view.speed });
    this.showForm(config);
    this.controls.sync(this.view);
    this.onUrl();
    if (!restart) return Promise.resolve(true);
    const ready = this.restart(autoplay);
    if (note) showMessage(note);
    return ready;
  }

  /**
   * Fresh runs, paused at timeline point `point` (a link's `at`): they are
   * stepped there through the engine's timeline; a point past the run's
   * end leaves them at its start, with the engine's message.
   */
  async openAt(point, note) {
    this.onUrl();
    this.last = { autoplay: false, paused: true };
    if (this.controller.state !== 'idle') this.controller.setState('idle');
    const ready = await this.restartPaused();
    if (!ready) return false;
    // The run is made up to the point first: seek only reaches points reached.
    const answer = await this.controller.dispatch({ type: 'advanceTo', point });
    if (note || !answer.ok) showMessage([note, answer.ok ? '' : `Could not open the run at at=${pointToAt(point)}: ${answer.error}`].filter(Boolean).join('\n'));
    return answer.ok;
  }

  restartPaused(config = this.config) {
    for (const fn of this.restarted) fn();
    showMessage('');
    return this.controller.dispatch({ type: 'reset', configs: this.runConfigs(config), autoplay: false, paused: true });
  }

  /**
   * Fresh runs rebuilt as a link's `branch` says: the first parent's run,
   * made up to the first branch move and branched there, and so on, the
   * last branch with this config; then paused at `at`. A bad value leaves
   * this config's own run at its start, with the engine's message.
   */
  async openBranch(text, at, note) {
    const levels = parseBranch(text);
    const fail = async (why) => {
      await this.restartPaused();
      showMessage([note, `Could not open the branch branch=${text.slice(0, 60)}: ${why}. Showing this configuration's own run from move 0.`].filter(Boolean).join('\n'));
      return false;
    };
    let parents;
    try {
      parents = levels.map((l) => l.pairs.reduce((c, [k, v]) => this.engine.setParam(c, k, v), this.config));
    } catch (err) {
      return fail(err.message);
    }
    this.showForm(this.config);
    this.last = { autoplay: false, paused: true };
    if (this.controller.state !== 'idle') this.controller.setState('idle');
    if (!(await this.restartPaused(parents[0]))) return false;
    for (const [k, { move }] of levels.entries()) {
      const answer = await this.controller.dispatch({ type: 'branch', configs: this.runConfigs(parents[k + 1] ?? this.config), move });
      if (!answer.ok) return fail(answer.error);
    }
    const answer = at ? await this.controller.dispatch({ type: 'advanceTo', point: atToPoint(at) }) : { ok: true };
    if (note || !answer.ok) showMessage([note, answer.ok ? '' : `Could not open the run at at=${at}: ${answer.error}`].filter(Boolean).join('\n'));
    this.onUrl();
    return answer.ok;
  }

  /** The runs' branch points as a link's `branch` ('' for runs of their own). */
  branchText() {
    const run = this.controller.runs[0];
    if (!run?.lineage?.length) return '';
    const changes = (parent) => this.engine.configDifferences(run.config, parent).filter((d) => d.key !== 'keep_traces').map((d) => [d.key, d.b]);
    return formatBranch(run.lineage.map((p) => ({ move: p.move, pairs: changes(p.config) })));
  }

  /** Shows `config` in the form (and its painting). */
  showForm(config) {
    const applicable = new Set(this.engine.applicable(config));
    if (this.paintKeys.some((k) => applicable.has(k))) this.painter.load(config);
    this.form.sync({ text: new Map(this.engine.configParams(config, true)), applicable, preset: this.engine.presetOf(config) ?? null });
  }

  /** Where a stopped run stands, as a link's `at` ('' when running, or at the start). */
  at() {
    const s = this.controller.state;
    if (!['paused', 'found', 'capped'].includes(s)) return '';
    return pointToAt(this.controller.timeline);
  }

  /** Sets one parameter from text through the engine; a bad value keeps the old one, with a message. */
  edit(key, raw) {
    let config;
    try {
      config = this.engine.setParam(this.config, key, raw);
    } catch (err) {
      config = this.withPainting(key, raw);
      if (!config) {
        const was = this.engine.configParams(this.config, true).find(([k]) => k === key)?.[1];
        showMessage(`Invalid ${key} ${JSON.stringify(String(raw).slice(0, 40))}: ${err.message}.${was === undefined ? '' : ` Keeping ${key}=${was}.`}`);
        this.change({ restart: false });
        return Promise.resolve(false);
      }
    }
    return this.propose(config);
  }

  /**
   * An edited config. Paused after move 0, it waits for a choice (an offer:
   * branch from the move shown, or restart) when only the searcher's
   * parameters changed, and restarts with a note when the world changed
   * (the engine's branchCheck says why); otherwise it restarts as any change.
   */
  propose(config) {
    const c = this.controller;
    const move = c.timeline?.move ?? 0;
    if (!['paused', 'choosing'].includes(c.state) || move === 0) return this.change({ config });
    const from = c.offer?.from ?? this.config;
    const same = (a, b) => JSON.stringify(this.engine.configParams(a, true)) === JSON.stringify(this.engine.configParams(b, true));
    if (same(from, config)) {
      c.dispatch({ type: 'cancel' });
      return Promise.resolve(true);
    }
    const why = this.engine.branchCheck(from, config);
    if (why) return this.change({ config, note: `Restarted from move 0: ${why}.` });
    c.dispatch({ type: 'offer', offer: { from, config, move } });
    this.showForm(config);
    return Promise.resolve(true);
  }

  /** The offered edit as a branch from its move: the path so far kept, the new setting from there. */
  async chooseBranch() {
    const offer = this.controller.offer;
    if (!offer) return false;
    this.config = offer.config;
    const answer = await this.controller.dispatch({ type: 'branch', configs: this.runConfigs(), move: offer.move });
    if (!answer.ok) this.config = offer.from;
    this.showForm(this.config);
    this.onUrl();
    return answer.ok;
  }

  /** The offered edit as a restart from move 0 (paused, as the run was). */
  chooseRestart() {
    const offer = this.controller.offer;
    return offer ? this.change({ config: offer.config }) : Promise.resolve(false);
  }

  /** Drops the offered edit: the run and the form as they were. */
  cancelOffer() {
    this.controller.dispatch({ type: 'cancel' });
  }

  /** An edit that puts an empty painting to use (prior=paint) starts from a blob in the middle; null if that does not help. */
  withPainting(key, raw) {
    for (const p of this.paintKeys) {
      if (this.config[p] || p === key) continue;
      try {
        const config = this.engine.setParam(this.engine.setParam(this.config, p, this.painter.blob(this.config.n)), key, raw);
        if (this.engine.applicable(config).includes(p)) return config;
      } catch {
        /* not this painting's doing */
      }
    }
    return null;
  }

  /** Opens an engine config (a point of an experiment), with no race; `show()` first shows the live view. */
  open(config, note, show) {
    let checked;
    try {
      checked = this.engine.checkConfig(config);
    } catch (err) {
      showMessage(`Could not open that configuration: ${err.message}`);
      return Promise.resolve(false);
    }
    show();
    return this.change({ config: checked, view: { race: '' }, autoplay: true, note });
  }

  /** The live view's query: only what differs from the defaults (and the seed), or with `full` everything. */
  query({ full = false } = {}) {
    const view = { ...this.view, show: this.viewState.shown(), at: this.at(), branch: this.branchText() };
    return writeUrl(this.engine, this.config, view, { full, races: this.races });
  }

  /**
   * The engine configs of the runs: the config, and the race opponent's
   * (the race option's searcher, then the `vs` changes: any parameters),
   * keeping the traces the view draws.
   */
  runConfigs(config = this.config) {
    this.kept = this.viewState.traceCount(config.keep_traces);
    const main = this.engine.setParam(config, 'keep_traces', String(this.kept));
    const opponent = this.opponent(main);
    return opponent ? [main, opponent] : [main];
  }

  /** The race opponent of `main` (the config by default), or null when not racing; a bad change shows a message and is left out. */
  opponent(main = this.config) {
    const race = this.races.find((r) => r.id === this.view.race);
    if (!race?.pairs.length && !this.view.vs) return null;
    try {
      return opponentConfig(this.engine, main, race?.pairs ?? [], this.view.vs);
    } catch (err) {
      showMessage(`Race: the opponent's change "${this.view.vs}" is not valid: ${err.message}.`);
      return race?.pairs.length ? opponentConfig(this.engine, main, race.pairs, '') : null;
    }
  }

  /**
   * Fresh runs from the current config (same seed); resolves once they have
   * a frame. By default they play on if the runs played, wait paused if they
   * were paused (an edit never starts a run), and after a finished run play
   * as the view says (not under reduced motion).
   */
  restart(autoplay = this.playsOn()) {
    if (this.trapped) {
      // A trap in the page's own wasm instance (not the search worker's,
      // which is replaced at the next reset) leaves it untrustworthy.
      location.reload();
      return Promise.resolve(false);
    }
    for (const fn of this.restarted) fn();
    if (this.controller.state !== 'error') showMessage('');
    // A reset under way (state idle) counts as what it will become.
    const s = this.controller.state;
    const paused = s === 'paused' || s === 'choosing' || (s === 'idle' && this.last.paused);
    this.last = { autoplay, paused };
    return this.controller.dispatch({ type: 'reset', configs: this.runConfigs(), autoplay, paused });
  }

  playsOn() {
    const s = this.controller.state;
    if (s === 'idle') return this.last.autoplay;
    return s === 'running' || ((s === 'found' || s === 'capped') && this.view.autoplay && !reducedMotion());
  }

  /** Calls `fn` at every restart. */
  onRestart(fn) {
    this.restarted.push(fn);
  }

  /** A trace layer ticked or unticked: fresh runs if they must keep another number of traces. */
  tracesChanged() {
    if (this.viewState.traceCount(this.config.keep_traces) !== this.kept) this.restart();
    else this.controller.dispatch({ type: 'redraw' });
  }

  /** A playback button or key, or a move on the timeline (`arg`: { move } for 'seek'). */
  playback(action, arg) {
    const back = { backMove: 'move', backLoop: 'loop', backPhase: 'phase' }[action];
    if (back) this.controller.dispatch({ type: 'back', unit: back });
    else if (action === 'start') this.controller.dispatch({ type: 'seek', point: { move: 0 } });
    else if (action === 'end') this.controller.dispatch({ type: 'seek', point: this.controller.timeline?.end ?? { move: 0 } });
    else if (action === 'seek') this.controller.dispatch({ type: 'seek', point: { move: arg.move } });
    else if (action === 'restart') this.restart();
    else if (action === 'newSeed') this.edit('seed', String(crypto.getRandomValues(new Uint32Array(1))[0]));
    else if (action === 'toggle' && this.controller.state === 'error') this.restart(true);
    else this.controller.dispatch({ type: action });
  }
}
