// The search worker: a dedicated Web Worker with its own wasm instance that
// holds the page's episodes and runs the search, so the page's thread only
// draws. At full speed it searches without pause, in slices of a few
// milliseconds so that requests from the page are answered promptly; at a
// set speed it runs that many loops per frame request.
//
// Messages in (each with an `id`, answered once by { id, ok: true, ... } or
// { id, ok: false, error, trap }):
//   init   { module }                  instantiate the engine (a compiled WebAssembly.Module)
//   reset  { gen, runs: [{ core, label }], seed }
//                                      build fresh runs; answers { runs: [describe()] }
//   play   { speed } / pause / speed { speed }
//   frame  { views: [req per run] }    (at a set speed: that many loops first) answers { frames }
//   stepLoop / stepMove { views }      one loop / one move on each unfinished run; answers { frames }
//   export                             answers { runs: [exportData()] }
//   benchLoops { config, seed, loops } answers { loops, ms }: one timed wasm call
//   usage                              answers { usage: { wallMs, workMs, frameMs, frames } } since the last call
//   panicForTest { message }           a deliberate wasm panic (the page's error path is tested with it)
// Every answer to a reset or later carries the run generation `gen`, so the
// page drops answers meant for runs it has already replaced.

import { loadEngine, Run, describeError } from './engine.js';

/** Longest stretch of search between looks at the message queue (ms). */
const SLICE_MS = 6;
/** Work allowed per frame request at a set speed (ms): a frame's worth. */
const FRAME_WORK_MS = 12;

const st = {
  wasm: null,
  runs: [],
  gen: 0,
  playing: false,
  speed: 10,
  loopMs: 0.05, // measured ms per loop per run: sizes the chunks
  pumping: false,
  trapped: false,
  // Where the worker's time goes (read by the browser benchmark).
  usage: { since: performance.now(), workMs: 0, frameMs: 0, frames: 0 },
};

// A zero-delay yield to the event loop (setTimeout is clamped to 4 ms once nested).
const yieldChannel = new MessageChannel();
yieldChannel.port1.onmessage = () => pump();

function active() {
  return st.runs.filter((r) => r.status() === 'running');
}

/**
 * Runs loops on every unfinished run for about `budgetMs`, at most
 * `maxLoops` each. Loops go in chunks sized from the measured cost of a loop
 * (rollout lengths vary a lot; the rollout cap bounds one).
 */
function work(budgetMs, maxLoops) {
  const t0 = performance.now();
  try {
    return workLoops(t0, budgetMs, maxLoops);
  } finally {
    st.usage.workMs += performance.now() - t0;
  }
}

function workLoops(t0, budgetMs, maxLoops) {
  const deadline = t0 + budgetMs;
  let remaining = maxLoops;
  let loops = 0;
  while (remaining > 0) {
    const runs = active();
    if (!runs.length) break;
    const left = deadline - performance.now();
    if (left <= 0) break;
    const perLoop = st.loopMs * runs.length;
    const fit = Math.floor(Math.min(2, left) / Math.max(perLoop, 1e-4));
    const k = Math.max(1, Math.min(remaining, fit, 1 << 14));
    const c0 = performance.now();
    for (const r of runs) r.stepLoops(k);
    const dt = performance.now() - c0;
    // Exponential average (chunks of one loop are noisy).
    st.loopMs = 0.7 * st.loopMs + 0.3 * (dt / k / runs.length);
    loops += k;
    remaining -= k;
  }
  return loops;
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
  if (active().length) schedule();
  else st.playing = false;
}

function schedule() {
  if (st.pumping || !st.playing || st.speed !== 'max') return;
  st.pumping = true;
  yieldChannel.port2.postMessage(null);
}

function frames(views) {
  const t0 = performance.now();
  const transfer = [];
  const out = st.runs.map((r, i) => r.frame(views?.[i] ?? { layers: [], pathHave: 0 }, transfer, st.playing && r.status() === 'running'));
  st.usage.frameMs += performance.now() - t0;
  st.usage.frames++;
  return { frames: out, transfer };
}

function fail(id, err) {
  const trap = err instanceof WebAssembly.RuntimeError;
  if (trap) {
    // The instance cannot be trusted after a trap: stop everything.
    st.trapped = true;
    st.playing = false;
    st.runs = [];
  }
  self.postMessage({ id, gen: st.gen, ok: false, error: describeError(err), trap });
}

function freeRuns() {
  for (const r of st.runs) r.free();
  st.runs = [];
}

function reset(msg) {
  freeRuns();
  st.gen = msg.gen;
  st.playing = false;
  const seed = BigInt(msg.seed);
  st.runs = msg.runs.map((r) => new Run(r.core, seed, r.label));
  if (st.runs.length === 2) {
    // A walker racing MCTS moves in step with it (one real move each), so the
    // boards compare paths rather than compute; once MCTS is done it runs free.
    const [a, b] = st.runs;
    const pace = (walker, mcts) => {
      walker.pacer = () => (mcts.status() === 'running' ? mcts.h.steps() : Infinity);
    };
    if (a.isMcts && !b.isMcts) pace(b, a);
    else if (!a.isMcts && b.isMcts) pace(a, b);
  }
  return { runs: st.runs.map((r) => r.describe()) };
}

const HANDLERS = {
  async init(msg) {
    st.wasm = await loadEngine(msg.module);
    return { version: st.wasm.version() };
  },
  reset,
  play(msg) {
    st.speed = msg.speed;
    st.playing = true;
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
    if (st.playing && st.speed !== 'max') {
      work(FRAME_WORK_MS, st.speed);
      if (!active().length) st.playing = false;
    }
    return frames(msg.views);
  },
  stepLoop(msg) {
    st.playing = false;
    for (const r of active()) r.stepLoops(1);
    return frames(msg.views);
  },
  stepMove(msg) {
    st.playing = false;
    for (const r of active()) r.stepMove();
    return frames(msg.views);
  },
  /** Time spent searching and building frames since the last call, and the wall time. */
  usage() {
    const now = performance.now();
    const u = { ...st.usage, wallMs: now - st.usage.since };
    st.usage = { since: now, workMs: 0, frameMs: 0, frames: 0 };
    return { usage: u };
  },
  /** Times `benchMctsLoops(config, seed, loops)` in one call here (the browser benchmark). */
  benchLoops(msg) {
    const t0 = performance.now();
    const [loops] = st.wasm.benchMctsLoops(msg.config, BigInt(msg.seed), msg.loops);
    return { loops, ms: performance.now() - t0 };
  },
  export() {
    return { runs: st.runs.map((r) => r.exportData()) };
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
  try {
    const { transfer = [], ...reply } = (await handler(msg)) ?? {};
    self.postMessage({ id: msg.id, gen: st.gen, ok: true, ...reply }, transfer);
  } catch (err) {
    fail(msg.id, err);
  }
};
