// Unit tests of the page's pure modules, run in Node (no browser):
// URL state parsing/serialisation, painted-prior encoding, wrap-aware path
// segments and the controller's state machine.
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { parseParams, serializeConfig, defaults, encodePaint, decodePaint, SPECS } from '../../www/url-state.js';
import { wrapSegments } from '../../www/renderer.js';
import { Controller } from '../../www/controller.js';

test('no parameters give the default demo', () => {
  const { config, messages } = parseParams('');
  assert.deepEqual(messages, []);
  assert.equal(config.n, 40);
  assert.equal(config.prior, 'gaussian');
  assert.equal(config.sigma, 5);
  assert.equal(config.searcher, 'mcts');
  assert.equal(config.variant, 'cells');
  assert.equal(config.rollout, 'rw');
  assert.equal(config.loops, 100);
  assert.equal(config.autoplay, true);
  assert.equal(config.c, Math.SQRT2);
});

test('every parameter round-trips through the URL', () => {
  const cfg = {
    ...defaults(),
    n: 77, prior: 'uniform', sigma: 2.5, rv: 0, start: [3, 70], searcher: 'levy', variant: 'tree',
    rollout: 'greedy', belief: 'posterior', loops: 250, ms: 12.5, c: 2, mu: 1.5, final: 'uct',
    seed: 18446744073709551615n, speed: 'max', autoplay: false, race: 'nsarw',
  };
  const q = serializeConfig(cfg);
  const { config, messages } = parseParams(q);
  assert.deepEqual(messages, []);
  assert.deepEqual(config, { ...cfg, paint: '' });
  // Defaults are left out, except the seed.
  assert.equal(serializeConfig(defaults()), 'seed=1');
  // The full form names every required parameter.
  const full = new URLSearchParams(serializeConfig(defaults(), { full: true }));
  for (const key of ['n', 'prior', 'sigma', 'rv', 'start', 'searcher', 'variant', 'rollout', 'belief', 'loops', 'ms', 'c', 'mu', 'final', 'seed', 'speed', 'autoplay']) {
    assert.ok(full.has(key), key);
  }
});

test('invalid values name the parameter and the allowed range, and the default is used', () => {
  const bad = {
    n: '2', prior: 'cauchy', sigma: '-1', rv: 'NaN', start: '0,5', searcher: 'astar', variant: 'forest',
    rollout: 'bfs', belief: 'maybe', loops: '0', ms: '-5', c: 'inf', mu: '1', final: 'best',
    seed: '-1', speed: 'warp', autoplay: 'perhaps', race: 'me',
  };
  const { config, messages } = parseParams(new URLSearchParams(bad).toString());
  const d = defaults();
  for (const key of Object.keys(bad)) {
    const msg = messages.find((m) => m.startsWith(`Invalid ${key}=`));
    assert.ok(msg, `no message for ${key}: ${messages.join(' | ')}`);
    assert.match(msg, /allowed/);
    assert.deepEqual(config[key], d[key], key);
  }
  assert.match(messages.find((m) => m.startsWith('Invalid n=')), /3–1024/);
  assert.match(messages.find((m) => m.startsWith('Invalid mu=')), /\(1, 3\]/);
  // start is checked against n.
  assert.equal(parseParams('n=10&start=11,1').messages.length, 1);
  assert.deepEqual(parseParams('n=10&start=10,10').config.start, [10, 10]);
  assert.match(parseParams('bogus=1').messages[0], /Unknown URL parameter "bogus"/);
});

test('a painted prior survives the URL', () => {
  const n = 37;
  const levels = new Uint8Array(n * n);
  for (let i = 0; i < levels.length; i++) levels[i] = (i * 7919) % 97 < 20 ? (i % 15) + 1 : 0;
  const s = encodePaint(levels);
  assert.match(s, /^[A-Za-z0-9_-]+$/);
  assert.deepEqual(decodePaint(s, n), levels);
  assert.equal(decodePaint(s, n + 1), null);
  assert.equal(decodePaint(`${s}A`, n), null);
  const big = new Uint8Array(1024 * 1024);
  assert.deepEqual(decodePaint(encodePaint(big), 1024), big);
  const { config } = parseParams(`prior=paint&n=${n}&paint=${s}`);
  assert.equal(config.prior, 'paint');
  assert.equal(config.paint, s);
});

test('wrap-aware segments never cross the grid', () => {
  const n = 5;
  const idx = (x, y) => y * n + x;
  // Right from x=4 wraps to x=0: drawn to the right edge, then from the left edge.
  const segs = wrapSegments([idx(4, 2), idx(0, 2)], n);
  assert.deepEqual(segs, [[4.5, 2.5, 5, 2.5], [0, 2.5, 0.5, 2.5]]);
  // Up from y=0 wraps to y=4.
  assert.deepEqual(wrapSegments([idx(1, 0), idx(1, 4)], n), [[1.5, 0.5, 1.5, 0], [1.5, 5, 1.5, 4.5]]);
  // An ordinary move is one segment.
  assert.deepEqual(wrapSegments([idx(1, 1), idx(2, 1)], n), [[1.5, 1.5, 2.5, 1.5]]);
  // A random walk: no segment is longer than one cell.
  let c = idx(2, 2);
  const path = [c];
  let s = 12345;
  for (let i = 0; i < 500; i++) {
    s = (s * 1103515245 + 12345) % 2 ** 31;
    const m = s % 4;
    const x = c % n;
    const y = Math.floor(c / n);
    const d = [[0, -1], [1, 0], [0, 1], [-1, 0]][m];
    c = ((y + d[1] + n) % n) * n + ((x + d[0] + n) % n);
    path.push(c);
  }
  for (const [x0, y0, x1, y1] of wrapSegments(path, n)) {
    assert.ok(Math.abs(x1 - x0) + Math.abs(y1 - y0) <= 1 + 1e-9);
    for (const v of [x0, y0, x1, y1]) assert.ok(v >= 0 && v <= n);
  }
});

/**
 * A stand-in for the search worker: one run that is found after `goal`
 * loops. It answers like SearchSession (reset -> run views; request ->
 * answers with frames), after a microtask, as the real worker would later.
 */
function fakeSession({ goal = 10, failReset = false } = {}) {
  const s = { loops: 0, gen: 0, playing: false, speed: 10, log: [] };
  const frame = () => ({
    status: s.loops >= goal ? 'found' : 'running',
    loopsTotal: s.loops,
    rolloutSteps: 3 * s.loops,
    steps: Math.floor(s.loops / 5),
  });
  const view = () => {
    const v = { snap: frame(), status: () => v.snap.status, loopsDone: () => v.snap.loopsTotal, rolloutSteps: () => v.snap.rolloutSteps };
    v.apply = (f) => { v.snap = f; };
    return v;
  };
  const work = (k) => { s.loops = Math.min(goal, s.loops + k); };
  s.reset = async () => {
    await null;
    if (failReset) throw new Error('boom');
    s.gen++;
    s.loops = 0;
    return [view()];
  };
  s.current = (answer) => answer.gen === s.gen;
  s.request = async (type, payload = {}) => {
    await null;
    s.log.push(type);
    if (type === 'play') s.playing = true;
    if (type === 'pause') s.playing = false;
    if (type === 'speed') s.speed = payload.speed;
    if (type === 'stepLoop') { s.playing = false; work(1); }
    if (type === 'stepMove') { s.playing = false; work(5); }
    if (type === 'frame' && s.playing) work(s.speed === 'max' ? goal : s.speed);
    if (type === 'panicForTest') {
      const err = new Error('The engine crashed (wasm panic): test');
      err.trap = true;
      throw err;
    }
    return { gen: s.gen, frames: [frame()] };
  };
  return s;
}

test('the controller state machine', async () => {
  globalThis.document = { body: { dataset: {} } };
  const session = fakeSession({ goal: 10 });
  const frames = [];
  const raf = (fn) => frames.push(fn);
  const runFrames = async (k) => {
    for (let i = 0; i < k && frames.length; i++) {
      frames.shift()(i * 16);
      await new Promise((r) => setTimeout(r, 0));
    }
  };
  const states = [];
  let drawn = 0;
  const c = new Controller({ session, spec: () => ({}), views: (runs) => runs.map(() => ({})), draw: () => drawn++, onState: (s) => states.push(s), raf });
  assert.equal(await c.reset({ autoplay: false }), true);
  assert.equal(c.state, 'idle');
  assert.equal(document.body.dataset.state, 'idle');
  await c.stepLoop();
  assert.equal(c.state, 'paused');
  assert.equal(c.runs[0].loopsDone(), 1);
  await c.stepMove();
  assert.equal(c.runs[0].loopsDone(), 6);
  c.setSpeed(2);
  c.play();
  assert.equal(c.state, 'running');
  await runFrames(20);
  // Two loops per frame until the goal: the run is found and the loop stops.
  assert.equal(c.runs[0].loopsDone(), 10);
  assert.equal(c.state, 'found');
  assert.ok(drawn > 0);
  assert.deepEqual(states.slice(-3), ['paused', 'running', 'found']);
  assert.throws(() => c.setState('running'), /invalid state transition/);
  // Stepping a finished run does nothing.
  await c.stepMove();
  assert.equal(c.state, 'found');
  // A reset overtaken by a newer one leaves only the newer runs.
  const older = c.reset();
  const newer = c.reset();
  assert.deepEqual([await older, await newer], [false, true]);
  assert.equal(c.state, 'idle');
  // A wasm trap in the worker puts the page in `error` with the message.
  const errs = [];
  c.onError = (e) => errs.push(e.message);
  await c.send('panicForTest', { message: 'x' });
  assert.equal(c.state, 'error');
  assert.match(errs[0], /wasm panic/);
  assert.deepEqual(c.runs, []);
  // A failing reset (an invalid config) too.
  const bad = new Controller({ session: fakeSession({ failReset: true }), spec: () => ({}), views: () => [], draw: () => {}, onError: (e) => errs.push(e.message), raf });
  assert.equal(await bad.reset(), false);
  assert.equal(bad.state, 'error');
  assert.equal(errs.at(-1), 'boom');
  delete globalThis.document;
});

test('all required parameter names are specified', () => {
  const keys = SPECS.map((s) => s.key);
  for (const k of ['n', 'prior', 'sigma', 'rv', 'start', 'searcher', 'variant', 'rollout', 'belief', 'loops', 'ms', 'c', 'mu', 'final', 'seed', 'speed', 'autoplay']) {
    assert.ok(keys.includes(k), k);
  }
});
