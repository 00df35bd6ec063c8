// Unit tests of the page's pure modules, run in Node (no browser; the
// engine runs in Node too): URL state, race options, wrap-aware path
// segments and the controller's state machine.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import path from 'node:path';
import { test } from 'node:test';
import { fileURLToPath } from 'node:url';
import { readUrl, writeUrl, raceOptions, readTreeView, treeViewText, pointToAt, atToPoint } from '../../www/shared/url-state.js';
import { wrapSegments } from '../../www/live/renderer.js';
import { Controller } from '../../www/live/controller.js';

const PKG = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../../www/pkg');
const engine = await import(path.join(PKG, 'torus_search.js'));
engine.initSync({ module: readFileSync(path.join(PKG, 'torus_search_bg.wasm')) });
const schema = engine.schema();
const races = raceOptions(engine, schema);
const read = (q) => readUrl(engine, schema, q, races);
const write = (config, view, opts = {}) => writeUrl(engine, config, view, { races, ...opts });

test('no parameters give the default demo', () => {
  const { config, view, messages } = read('');
  assert.deepEqual(messages, []);
  assert.equal(config.n, 40);
  assert.equal(config.prior, 'gaussian');
  assert.equal(config.sigma, 5);
  assert.equal(config.searcher, 'mcts');
  assert.equal(config.variant, 'cells');
  assert.equal(config.rollout, 'rw');
  assert.equal(config.belief, 'posterior');
  assert.equal(config.loops, 100);
  assert.equal(config.c, Math.SQRT2);
  assert.equal(config.seed, '1');
  assert.deepEqual(view, { speed: 10, autoplay: true, vs: '', show: '', at: '', branch: '', tree: '', lesson: '', race: '' });
});

test('every parameter round-trips through the URL', () => {
  const pairs = [
    ['n', '77'], ['prior', 'uniform'], ['rv', '0'], ['start', '3,70'], ['searcher', 'levy'], ['mu', '1.5'],
    ['step_cap', '5000'], ['seed', '18446744073709551615'], ['target', '5,6'],
  ];
  const { config, errors } = engine.parseParams(pairs);
  assert.deepEqual(errors, []);
  const view = { speed: 'max', autoplay: false, vs: 'rollout=levy c=0.5', show: 'visits,path', at: '12.3.rollout', branch: '4:c=0.5 loops=30/9', tree: 'b.best', lesson: 'theorem2', race: 'nsarw' };
  const back = read(write(config, view));
  assert.deepEqual(back.messages, []);
  assert.deepEqual(back.config, config);
  assert.deepEqual(back.view, view);
  // MCTS parameters survive too.
  const mcts = engine.parseParams([['variant', 'tree'], ['rollout', 'greedy'], ['epsilon', '0.3'], ['loops', '250'], ['ms', '12.5'], ['c', '2'], ['final', 'uct'], ['belief', 'prior'], ['tree_nodes', '4096']]).config;
  assert.deepEqual(read(write(mcts, { speed: 10, autoplay: true, race: '' })).config, mcts);
  // Defaults are left out, except the seed; the full form names every parameter.
  assert.equal(write(read('').config, read('').view), 'seed=1');
  const full = new URLSearchParams(write(config, view, { full: true }));
  for (const p of [...schema.params.map((q) => q.key), 'speed', 'autoplay', 'vs', 'show', 'at', 'branch', 'tree', 'lesson', 'race']) assert.ok(full.has(p), p);
  assert.deepEqual(read(full.toString()).config, config);
});

test('the tree view\'s link text: board B by a b prefix, round trip, and nothing else', () => {
  const cases = [
    ['', { board: 0, focus: 'all' }], ['best', { board: 0, focus: 'best' }], ['12', { board: 0, focus: 12 }],
    ['b', { board: 1, focus: 'all' }], ['b.best', { board: 1, focus: 'best' }], ['b.7', { board: 1, focus: 7 }],
  ];
  for (const [text, want] of cases) {
    assert.deepEqual(readTreeView(text), want, text);
    assert.equal(treeViewText(want), text);
    assert.deepEqual(read(`tree=${text}`).messages, [], text);
  }
  for (const bad of ['b.', 'bb', 'a', 'a.best', 'best.b', 'b.best.1', 'B', '-1', '1234567890']) {
    assert.equal(readTreeView(bad), undefined, bad);
    assert.match(read(`tree=${bad}`).messages[0] ?? '', /^Invalid tree=.*allowed .*b\.best or b\.ID for board B/, bad);
  }
});

test('invalid values name the parameter and the allowed range, and the default is used', () => {
  const bad = {
    n: '2', prior: 'cauchy', sigma: '-1', rv: 'NaN', start: '0,5', searcher: 'astar', variant: 'forest',
    rollout: 'bfs', belief: 'maybe', loops: '0', ms: '-5', c: 'inf', mu: '1', final: 'best',
    seed: '-1', speed: 'warp', autoplay: 'perhaps', race: 'me', step_cap: '0', paint: '*', at: '1.x', branch: '3:c', show: 'Visits<b>', tree: 'worst', lesson: 'none',
  };
  const { config, view, messages } = read(new URLSearchParams(bad).toString());
  const d = read('');
  for (const key of Object.keys(bad)) {
    const msg = messages.find((m) => m.startsWith(`Invalid ${key}=`));
    assert.ok(msg, `no message for ${key}: ${messages.join(' | ')}`);
    assert.match(msg, /allowed .*Using the default/);
    if (key in d.view) assert.deepEqual(view[key], d.view[key], key);
    else assert.deepEqual(config[key], d.config[key], key);
  }
  assert.match(messages.find((m) => m.startsWith('Invalid n=')), /an integer in 3\.\.=1024/);
  assert.match(messages.find((m) => m.startsWith('Invalid mu=')), /\(1, 3\]/);
  // start is checked against n, and a seed beyond 2^64 − 1 is refused, never wrapped.
  assert.equal(read('n=10&start=11,1').messages.length, 1);
  assert.deepEqual(read('n=10&start=10,10').config.start, [10, 10]);
  assert.match(read('seed=18446744073709551616').messages[0], /Invalid seed=.*0\.\.=18446744073709551615/);
  assert.match(read('bogus=1').messages[0], /Unknown URL parameter "bogus"/);
  // A repeated key: the last one counts.
  assert.equal(read('n=12&n=13').config.n, 13);
});

test('a link\'s point: one for every board, or one per board when a race\'s boards stand apart', () => {
  const at = (runs) => pointToAt({ ...runs[0], runs });
  assert.equal(at([{ move: 2, loop: 2, phase: null }, { move: 0, loop: 12, phase: null }]), '2.2/0.12');
  assert.equal(at([{ move: 2, loop: 2, phase: 'rollout' }, { move: 2, loop: 2, phase: 'rollout' }]), '2.2.rollout');
  assert.equal(at([{ move: 0, loop: 0, phase: null }]), '');
  assert.deepEqual(atToPoint('2.2/0.12'), [{ move: 2, loop: 2, phase: null }, { move: 0, loop: 12, phase: null }]);
  assert.deepEqual(atToPoint('3'), { move: 3, loop: 0, phase: null });
  assert.equal(read('at=2.2/0.12.select').view.at, '2.2/0.12.select');
  for (const bad of ['1/2/3', '1/', '/1', '1.2/x']) assert.match(read(`at=${encodeURIComponent(bad)}`).messages[0] ?? '', /^Invalid at=/, bad);
});

test('a painted prior survives the URL', () => {
  const n = 37;
  const levels = new Uint8Array(n * n);
  for (let i = 0; i < levels.length; i++) levels[i] = (i * 7919) % 97 < 20 ? (i % 15) + 1 : 0;
  const s = engine.encodePaint(levels);
  assert.match(s, /^[A-Za-z0-9_-]+$/);
  assert.deepEqual(engine.decodePaint(s, n), levels);
  const { config, messages } = read(`prior=paint&n=${n}&paint=${s}`);
  assert.deepEqual(messages, []);
  assert.equal(config.prior, 'paint');
  assert.equal(config.paint, s);
  assert.deepEqual(read(write(config, read('').view)).config, config);
  // prior=paint without a painting falls back to the default prior, with a message.
  const bare = read('prior=paint');
  assert.equal(bare.config.prior, 'gaussian');
  assert.match(bare.messages.join(' '), /Invalid prior=/);
});

test('race opponents come from the searcher registry', () => {
  assert.deepEqual(races.map((r) => r.id), ['', 'mcts-cells', 'mcts-tree', 'mcts-code', 'mcts-pomcp', 'rw', 'levy', 'nsarw', 'sweep', 'horizon', 'improve', 'beam', 'spiral']);
  const tree = races.find((r) => r.id === 'mcts-tree');
  assert.deepEqual(tree.pairs, [['searcher', 'mcts'], ['variant', 'tree']]);
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
    const d = [[0, -1], [1, 0], [0, 1], [-1, 0]][s % 4];
    const x = c % n;
    const y = Math.floor(c / n);
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
  const s = { loops: 0, gen: 0, playing: false, speed: 10, log: [], resets: [] };
  const frame = () => ({ status: s.loops >= goal ? 'found' : 'running', work: s.loops, rollout_steps: 3 * s.loops, steps: Math.floor(s.loops / 5) });
  const view = (config) => {
    const v = { frame: frame(), config, status: () => v.frame.status, work: () => v.frame.work, rolloutSteps: () => v.frame.rollout_steps, request: (vw) => ({ vw }) };
    v.apply = (f) => {
      v.frame = f;
    };
    return v;
  };
  const work = (k) => {
    s.loops = Math.min(goal, s.loops + k);
  };
  s.reset = async (configs) => {
    await null;
    if (failReset) throw new Error('boom');
    s.resets.push(configs);
    s.gen++;
    s.loops = 0;
    return configs.map(view);
  };
  s.branch = async (configs, move) => {
    await null;
    if (move > s.loops) throw new Error(`branch at move ${move} is past the run's moves`);
    s.gen++;
    return configs.map(view);
  };
  s.current = (answer) => answer.gen === s.gen;
  s.request = async (type, payload = {}) => {
    await null;
    s.log.push([type, payload]);
    if (type === 'play') s.playing = true;
    if (type === 'pause') s.playing = false;
    if (type === 'speed') s.speed = payload.speed;
    if (type === 'stepLoop') work(1);
    if (type === 'stepMove') work(5);
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

test('the controller state machine takes commands one way and reports by events', async () => {
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
  const c = new Controller({ session, raf });
  c.on('state', (st) => states.push(st));
  c.on('frame', () => drawn++);
  const cfg = { n: 12, seed: '3' };
  assert.equal(await c.dispatch({ type: 'reset', configs: [cfg], autoplay: false }), true);
  assert.deepEqual(session.resets, [[cfg]], 'the reset carries the configs');
  assert.equal(c.state, 'idle');
  assert.equal(document.body.dataset.state, 'idle');
  // The view travels with every frame request.
  c.dispatch({ type: 'view', view: { layers: ['x'], traces: true } });
  await c.dispatch({ type: 'stepLoop' });
  assert.equal(c.state, 'paused');
  assert.deepEqual(session.log.at(-1), ['stepLoop', { requests: [{ vw: { layers: ['x'], traces: true } }] }]);
  assert.equal(c.runs[0].work(), 1);
  await c.dispatch({ type: 'stepMove' });
  assert.equal(c.runs[0].work(), 6);
  c.dispatch({ type: 'speed', speed: 2 });
  c.dispatch({ type: 'play' });
  assert.equal(c.state, 'running');
  await runFrames(20);
  // Two loops per frame until the goal: the run is found and the loop stops.
  assert.equal(c.runs[0].work(), 10);
  assert.equal(c.state, 'found');
  assert.ok(drawn > 0);
  assert.deepEqual(states.slice(-3), ['paused', 'running', 'found']);
  // An offer waits in `choosing`: playback and steps do nothing; cancel keeps the runs.
  c.dispatch({ type: 'seek', point: { move: 0 } });
  c.setState('paused');
  const kept = c.runs;
  assert.equal(c.dispatch({ type: 'offer', offer: { move: 1 } }), true);
  assert.equal(c.state, 'choosing');
  assert.deepEqual(c.offer, { move: 1 });
  c.dispatch({ type: 'play' });
  await c.dispatch({ type: 'stepMove' });
  assert.equal(c.state, 'choosing');
  assert.equal(c.dispatch({ type: 'cancel' }), true);
  assert.deepEqual([c.state, c.offer, c.runs], ['paused', null, kept]);
  // A branch refused: a message, the runs as they were; a branch made: fresh runs, paused.
  const said = [];
  c.on('message', (m) => said.push(m));
  c.dispatch({ type: 'offer', offer: { move: 99 } });
  assert.deepEqual(await c.dispatch({ type: 'branch', configs: [{ n: 7 }], move: 99 }), { ok: false, error: "branch at move 99 is past the run's moves" });
  assert.deepEqual([c.state, c.runs, said], ['paused', kept, ["branch at move 99 is past the run's moves"]]);
  assert.deepEqual(await c.dispatch({ type: 'branch', configs: [{ n: 7 }], move: 2 }), { ok: true });
  assert.deepEqual(c.runs.map((r) => r.config), [{ n: 7 }]);
  c.settle();
  c.setState('found');
  assert.throws(() => c.setState('running'), /invalid state transition/);
  assert.throws(() => c.dispatch({ type: 'warp' }), /unknown command/);
  // Stepping a finished run does nothing.
  await c.dispatch({ type: 'stepMove' });
  assert.equal(c.state, 'found');
  // Toggling a finished run replays the same configs (the branch's).
  c.dispatch({ type: 'toggle' });
  await c.whenReady();
  assert.deepEqual(session.resets.at(-1), [{ n: 7 }]);
  // A reset overtaken by a newer one leaves only the newer runs.
  const older = c.dispatch({ type: 'reset', configs: [cfg] });
  const newer = c.dispatch({ type: 'reset', configs: [{ n: 5 }] });
  assert.deepEqual([await older, await newer], [false, true]);
  assert.equal(c.state, 'idle');
  assert.deepEqual(c.runs.map((r) => r.config), [{ n: 5 }]);
  // A wasm trap in the worker puts the page in `error` with the message.
  const errs = [];
  c.on('error', (e) => errs.push(e.message));
  await c.dispatch({ type: 'request', request: 'panicForTest', payload: { message: 'x' } });
  assert.equal(c.state, 'error');
  assert.match(errs[0], /wasm panic/);
  assert.deepEqual(c.runs, []);
  // A failing reset (an invalid config) too.
  const bad = new Controller({ session: fakeSession({ failReset: true }), raf });
  bad.on('error', (e) => errs.push(e.message));
  assert.equal(await bad.dispatch({ type: 'reset', configs: [{}] }), false);
  assert.equal(bad.state, 'error');
  assert.equal(errs.at(-1), 'boom');
  delete globalThis.document;
});
