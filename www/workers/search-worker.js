// The search worker: a dedicated Web Worker with its own wasm instance that
// holds the page's runs (one engine `Race`) and searches, so the page's
// thread only draws. It keeps no game state of its own: the runs live in
// the engine, and whether it searches is whatever the controller last said.
// At full speed it searches without pause, in slices of a few milliseconds
// so requests are answered promptly; at a set speed it runs that many loops
// per frame request.
//
// Messages in (each with an `id`, answered once by { id, gen, ok: true, ... }
// or { id, gen, ok: false, error, trap }):
//   init   { module }                   instantiate the engine (a compiled WebAssembly.Module)
//   reset  { gen, configs }             build the runs; answers { runs } (Race.describe())
//   play   { speed } / pause / speed { speed }
//   frame  { requests }                 (at a set speed: that many loops first) answers { frames }
//   stepLoop / stepMove { requests }    one loop / one move on each unfinished run; answers { frames }
//   stepPhase { requests }              one phase of the loop in flight on each run; answers { frames, steps }
//   seek { point, requests }            every run to a timeline point { move, loop, phase } (or run i
//                                       to the i-th of an array of them); answers { frames }
//   back { unit, requests }             one phase | loop | move back; answers { frames }
//   advanceTo { point, requests }       steps the runs forward as far as `point` (moves, loops,
//                                       phases; an array: each run to its own), then seeks it
//                                       exactly; answers { frames }
//   branch { gen, configs, move }       branches the runs at `move` (made first if not reached yet)
//                                       with new configs (Race.branch); answers { runs }. Refused:
//                                       the runs stay where they stood, under their generation
//   tree { run, query }                 the decision's tree (Race.tree); treeColumns { run, query } as columns
//                                       (a move a planner has yet to plan is made in calls of bounded
//                                       length, answering other requests between them)
//   export                              answers { runs } (Race.export())
//   benchLoops { config, loops }        answers { loops, ms }: one timed wasm call
//   usage                               answers { usage: { wallMs, workMs, frameMs, frames, memoryBytes } } since the last call
//   panicForTest { message }            a deliberate wasm panic (the page's error path is tested with it)
//   oomForTest                          allocates until wasm memory runs out (a real out-of-memory abort)
// Every answer carries the run generation `gen`, so the page drops answers
// meant for runs it has already replaced; every frames answer carries the
// timeline (Race.timeline(): the point shown and the furthest reached).
// A phase speed ('2s', '1s', '0.5s': one phase every so long) steps one
// phase per frame request once that long has passed.

import { loadEngine, describeError } from '../shared/engine.js';

/** Longest stretch of search between looks at the message queue (ms). */
const SLICE_MS = 6;
/** Work allowed per frame request at a set speed (ms): a frame's worth. */
const FRAME_WORK_MS = 12;

const st = {
  wasm: null,
  race: null,
  gen: 0,
  playing: false,
  speed: 10,
  loopMs: 0.05, // measured ms per loop per run: sizes the chunks
  pumping: false,
  lastPhase: 0, // when the last phase was stepped at a phase speed
  trapped: false,
  // Where the worker's time goes (read by the browser benchmark).
  usage: { since: performance.now(), workMs: 0, frameMs: 0, frames: 0 },
};

// A zero-delay yield to the event loop (setTimeout is clamped to 4 ms once nested).
const yieldChannel = new MessageChannel();
yieldChannel.port1.onmessage = () => pump();

/** Resolves on the event loop's next turn, after the messages already queued. */
function nextTurn() {
  return new Promise((resolve) => {
    const { port1, port2 } = new MessageChannel();
    port1.onmessage = () => {
      port1.close();
      resolve();
    };
    port2.postMessage(null);
  });
}

const running = () => (st.race ? st.race.running() : 0);

/** The ms between phases at a phase speed ('2s': one phase every 2 s), else 0. */
const phaseSpeedMs = (speed) => (typeof speed === 'string' && speed.endsWith('s') ? 1000 * Number(speed.slice(0, -1)) : 0);

/**
 * Runs loops on every unfinished run for about `budgetMs`, at most
 * `maxLoops` each, in chunks sized from the measured cost of a loop
 * (rollout lengths vary a lot; the rollout cap bounds one).
 */
function work(budgetMs, maxLoops) {
  const t0 = performance.now();
  const deadline = t0 + budgetMs;
  let remaining = maxLoops;
  try {
    while (remaining > 0) {
      const runs = running();
      const left = deadline - performance.now();
      if (!runs || left <= 0) break;
      const fit = Math.floor(Math.min(2, left) / Math.max(st.loopMs * runs, 1e-4));
      const k = Math.max(1, Math.min(remaining, fit, 1 << 14));
      const c0 = performance.now();
      st.race.advance(k);
      // Exponential average (chunks of one loop are noisy).
      st.loopMs = 0.7 * st.loopMs + 0.3 * ((performance.now() - c0) / k / runs);
      remaining -= k;
    }
  } finally {
    st.usage.workMs += performance.now() - t0;
  }
}

function pump() {
  st.pumping = false;
  if (!st.playing || st.speed !== 'max' || st.trapped) return;
  try {
    work(SLICE_MS, Infinity);
  } catch (err) {
    fail(null, err);
    return;
  }
  schedule();
}

function schedule() {
  if (st.pumping || !st.playing || st.speed !== 'max' || !running()) return;
  st.pumping = true;
  yieldChannel.port2.postMessage(null);
}

/** One frame per run; buffers are transferred, not copied again. */
function frames(requests = []) {
  const t0 = performance.now();
  const live = st.playing && running() > 0;
  const out = st.race.frames(requests.map((r) => ({ ...r, live })));
  const transfer = [];
  for (const f of out) {
    transfer.push(f.path.buffer);
    for (const l of f.layers) if (l.rgba) transfer.push(l.rgba.buffer);
    for (const t of f.traces ?? []) transfer.push(t.buffer);
    if (f.intent) transfer.push(f.intent.buffer);
  }
  st.usage.frameMs += performance.now() - t0;
  st.usage.frames++;
  return { frames: out, transfer, timeline: st.race.timeline() };
}

function fail(id, err) {
  const trap = err instanceof WebAssembly.RuntimeError;
  if (trap) {
    // The instance cannot be trusted after a trap: drop everything.
    st.trapped = true;
    st.playing = false;
    st.race = null;
  }
  self.postMessage({ id, gen: st.gen, ok: false, error: describeError(err), trap });
}

const HANDLERS = {
  async init(msg) {
    st.wasm = await loadEngine(msg.module);
    return { version: st.wasm.version() };
  },
  reset(msg) {
    st.race?.free();
    st.race = null;
    st.gen = msg.gen;
    st.playing = false;
    st.race = new st.wasm.Race(msg.configs);
    return { runs: st.race.describe() };
  },
  play(msg) {
    st.speed = msg.speed;
    st.playing = true;
    st.lastPhase = 0;
    schedule();
    return {};
  },
  pause() {
    st.playing = false;
    return {};
  },
  speed(msg) {
    st.speed = msg.speed;
    schedule();
    return {};
  },
  frame(msg) {
    const phaseMs = phaseSpeedMs(st.speed);
    if (st.playing && phaseMs) {
      const now = performance.now();
      if (now - st.lastPhase >= phaseMs && running()) {
        st.lastPhase = now;
        st.race.stepPhase();
      }
    } else if (st.playing && st.speed !== 'max') work(FRAME_WORK_MS, st.speed);
    return frames(msg.requests);
  },
  stepPhase(msg) {
    const steps = st.race.stepPhase();
    return { ...frames(msg.requests), steps };
  },
  seek(msg) {
    st.race.seek(msg.point);
    return frames(msg.requests);
  },
  back(msg) {
    st.race.back(msg.unit);
    return frames(msg.requests);
  },
  advanceTo(msg) {
    const { race } = st;
    // One point (the first run's) or one per run; each run's own end is stepped to its point.
    const each = Array.isArray(msg.point);
    const want = (each ? msg.point : [msg.point]).map((p) => ({ loop: 0, phase: null, ...p }));
    const ends = () => race.timeline().runs.map((r) => r.end);
    const short = (pred) => ends().some((t, i) => want[i] && pred(t, want[i]));
    const before = (t, p) => t.move < p.move || (t.move === p.move && t.loop < p.loop);
    while (short((t, p) => t.move < p.move) && race.running()) race.stepMove();
    while (short(before) && race.running()) race.stepLoop();
    const inLoop = (t, p) => p.phase && t.move === p.move && t.loop === p.loop && t.phase !== p.phase;
    for (let k = 0; k < 4 && short(inLoop) && race.running(); k++) race.stepPhase();
    race.seek(each ? want : want[0]);
    return frames(msg.requests);
  },
  branch(msg) {
    const { race } = st;
    const was = race.timeline();
    st.playing = false;
    let advanced = false;
    while (race.timeline().end.move < msg.move && race.running()) {
      race.stepMove();
      advanced = true;
    }
    let runs;
    try {
      runs = race.branch(msg.configs, msg.move);
    } catch (err) {
      // Refused after making moves to reach it: back where the runs stood.
      if (advanced && !(err instanceof WebAssembly.RuntimeError)) race.seek({ move: was.move, loop: was.loop, phase: was.phase });
      throw err;
    }
    st.gen = msg.gen;
    return { runs };
  },
  tree(msg) {
    return { tree: st.race.tree(msg.run ?? 0, msg.query) };
  },
  treeColumns(msg) {
    return { tree: st.race.treeColumns(msg.run ?? 0, msg.query) };
  },
  stepLoop(msg) {
    st.race.stepLoop();
    return frames(msg.requests);
  },
  async stepMove(msg) {
    // A planner may take thousands of slices to make its first move: make
    // it in calls of bounded length and answer frames, pause and reset
    // between them.
    const race = st.race;
    race.askMove();
    while (!race.makeAskedMoves()) {
      await nextTurn();
      if (st.race !== race) throw new Error('stepMove: the runs were replaced before the move was made');
    }
    return frames(msg.requests);
  },
  export() {
    return { runs: st.race.export() };
  },
  /** Time spent searching and building frames since the last call, and the wall time. */
  usage() {
    const now = performance.now();
    const u = { ...st.usage, wallMs: now - st.usage.since, memoryBytes: st.wasm?.memoryBytes() ?? 0 };
    st.usage = { since: now, workMs: 0, frameMs: 0, frames: 0 };
    return { usage: u };
  },
  /** Times `benchMctsLoops(config, loops)` in one call here (the browser benchmark). */
  benchLoops(msg) {
    const t0 = performance.now();
    const [loops] = st.wasm.benchMctsLoops(msg.config, msg.loops);
    return { loops, ms: performance.now() - t0 };
  },
  oomForTest() {
    st.wasm.oomForTest();
    return {};
  },
  panicForTest(msg) {
    st.wasm.panicForTest(msg.message);
    return {};
  },
};

self.onmessage = async (e) => {
  const msg = e.data;
  const handler = HANDLERS[msg.type];
  if (!handler) {
    self.postMessage({ id: msg.id, gen: st.gen, ok: false, error: `unknown request ${JSON.stringify(msg.type)}` });
    return;
  }
  if (st.trapped && msg.type !== 'init') {
    self.postMessage({ id: msg.id, gen: st.gen, ok: false, error: 'the engine crashed earlier: restart the page', trap: true });
    return;
  }
  if (!st.race && !['init', 'reset', 'benchLoops', 'usage', 'panicForTest', 'oomForTest', 'play', 'pause', 'speed'].includes(msg.type)) {
    self.postMessage({ id: msg.id, gen: st.gen, ok: false, error: `${msg.type}: no runs yet` });
    return;
  }
  try {
    const { transfer = [], ...reply } = (await handler(msg)) ?? {};
    self.postMessage({ id: msg.id, gen: st.gen, ok: true, ...reply }, transfer);
  } catch (err) {
    fail(msg.id, err);
  }
};
