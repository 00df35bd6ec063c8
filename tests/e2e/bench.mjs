#!/usr/bin/env node
// Browser benchmark (no timed assertions): prints one JSON object with
//   fps_n256              frames/s at N=256 with one heat layer (the prior),
//                         the path and the gliding searcher drawn while MCTS runs
//   draw_ms_per_frame_*   main-thread time per drawn frame: `boards` (the whole
//                         board: scene, trails kept, rendering) and its parts
//                         (Renderer methods: heat layer, trails, path, marks,
//                         searcher, grid); n256_visits_trails draws the MCTS
//                         visits (recoloured as the search runs) and the rollouts
//   put_image_data_*      putImageData calls on the page's thread per drawn frame,
//                         and the layers whose pixels changed (one call each)
//   longest_task_ms_n256  the longest main-thread task meanwhile (PerformanceObserver 'longtask')
//   page_loops_per_s_*    MCTS loops/s in the page (search worker, drawing on)
//   page_loop_window_*    which loops of the episode the page ran meanwhile
//   wasm_window_loops_per_s_*  the same loops in one wasm call in the search
//                         worker (no frame loop, no drawing)
//   wasm_loops_per_s_*    MCTS loops in one wasm call on the page's thread (loops 0..L)
//   wasm_rw_steps_per_s   RW rollout lattice steps/s in wasm (N=40, r_v=1)
//   fps_n100_long_path    frames/s and the longest task over 3 s of a long
//                         N=100 episode once its path has 9000 moves
//   native_*              with --native: `target/release/torus-search bench --json`
//                         (the suite), and the very loops the page ran, timed
//                         natively (`bench --episode CONFIG --loops FROM..TO`,
//                         CONFIG the run's engine config, seed included);
//                         page_over_native_* divides the two
// Each page figure is the median of --repeat measurements (default 3), and
// every ratio is taken within one measurement (its own loop window) first.
// Usage: node tests/e2e/bench.mjs [--native] [--seconds S] [--repeat R]
// Needs `make build` (www/pkg) first. It reads and drives the page through
// its test interface, `window.torusTest` (www/shared/test-hook.js).
import { execFileSync } from 'node:child_process';
import { existsSync, mkdtempSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { ROOT, launchBrowser, openPage, startServer } from './harness.mjs';

const args = process.argv.slice(2);
const seconds = Number(args[args.indexOf('--seconds') + 1]) || 5;
const wantNative = args.includes('--native');
const repeat = Math.max(1, Math.min(20, Number(args[args.indexOf('--repeat') + 1]) || 3));

// Counts animation frames and long tasks from before the page's own scripts run.
const PROBE = () => {
  window.__bench = { frames: 0, longest: 0, longTasks: 0 };
  const tick = () => {
    window.__bench.frames++;
    requestAnimationFrame(tick);
  };
  requestAnimationFrame(tick);
  try {
    new PerformanceObserver((list) => {
      for (const e of list.getEntries()) {
        window.__bench.longest = Math.max(window.__bench.longest, e.duration);
        window.__bench.longTasks++;
      }
    }).observe({ type: 'longtask', buffered: true });
  } catch {
    window.__bench.longest = -1; // not supported
  }
};

/**
 * Times the drawing on the page's thread: wraps Boards.prototype.draw and
 * the Renderer's drawing methods (the same module instances the page uses)
 * and counts putImageData calls. Sums go to window.__draw.
 */
async function instrumentDrawing(page) {
  await page.evaluate(async () => {
    const { Renderer } = await import('./www/live/renderer.js');
    const { Boards } = await import('./www/live/boards.js');
    const d = { frames: 0, puts: 0, uploads: 0, ms: {} };
    window.__draw = d;
    const wrap = (proto, name, key) => {
      const f = proto[name];
      d.ms[key] = 0;
      proto[name] = function wrapped(...a) {
        const t = performance.now();
        try {
          return f.apply(this, a);
        } finally {
          d.ms[key] += performance.now() - t;
        }
      };
    };
    wrap(Boards.prototype, 'draw', 'boards');
    for (const m of ['draw', 'drawTrails', 'drawPath', 'drawIntent', 'drawMarks', 'drawSearcher', 'drawFrame', 'hatched']) wrap(Renderer.prototype, m, m === 'draw' ? 'renderer' : m);
    const boardsDraw = Boards.prototype.draw;
    Boards.prototype.draw = function counted(...a) {
      d.frames++;
      return boardsDraw.apply(this, a);
    };
    const upload = Renderer.prototype.upload;
    Renderer.prototype.upload = function counted(...a) {
      const before = this.uploads;
      const r = upload.apply(this, a);
      d.uploads += this.uploads - before;
      return r;
    };
    const put = CanvasRenderingContext2D.prototype.putImageData;
    CanvasRenderingContext2D.prototype.putImageData = function counted(...a) {
      d.puts++;
      return put.apply(this, a);
    };
  });
}

/** Per drawn frame between two snapshots of window.__draw. */
function perFrame(a, b) {
  const frames = Math.max(1, b.frames - a.frames);
  const ms = Object.fromEntries(Object.keys(b.ms).map((k) => [k, +((b.ms[k] - a.ms[k]) / frames).toFixed(3)]));
  return { frames: b.frames - a.frames, ms, puts: +((b.puts - a.puts) / frames).toFixed(3), changed_layers: +((b.uploads - a.uploads) / frames).toFixed(3) };
}

/** Waits for the page's runs, unticks the layers `untick`, ticks `tick` (a heat chip), and plays at full speed. */
async function playAtFullSpeed(page, untick, tick = []) {
  await page.waitForFunction(() => window.torusTest?.runs().length, null, { timeout: 60_000 });
  await page.evaluate(async ([ids, on]) => {
    for (const id of ids) {
      const el = document.getElementById(id);
      if (el.checked) el.click();
    }
    for (const id of on) {
      const el = document.getElementById(id);
      if (!el.checked) el.click();
    }
    const t = window.torusTest;
    // Unticking a trace layer restarts the run (traces are kept from the start).
    await t.ready();
    t.dispatch({ type: 'speed', speed: 'max' });
    t.dispatch({ type: 'play' });
  }, [untick, tick]);
}

async function measurePage(context, url, { untick = [], tick = [] } = {}) {
  const { page } = await openPage(context, url);
  try {
    await page.waitForFunction(() => window.torusTest?.runs().length, null, { timeout: 60_000 });
    await instrumentDrawing(page);
    await playAtFullSpeed(page, untick, tick);
    await page.waitForTimeout(1000); // warm up
    const sample = () => page.evaluate(() => {
      const t = window.torusTest;
      const runs = t.runs();
      return {
        t: performance.now(),
        frames: window.__bench.frames,
        loops: runs.reduce((a, r) => a + r.work, 0),
        config: runs[0].config,
        steps: runs.reduce((a, r) => a + r.rolloutSteps, 0),
        state: t.state(),
        longest: window.__bench.longest,
        longTasks: window.__bench.longTasks,
        draw: structuredClone(window.__draw),
      };
    });
    await page.evaluate(() => {
      window.__bench.longest = 0;
      window.__bench.longTasks = 0;
    });
    const a = await sample();
    // Sample until the window ends or the episode does (rates cover running time only).
    let b = a;
    while (b.t - a.t < seconds * 1000) {
      await page.waitForTimeout(250);
      const s = await sample();
      if (s.state !== 'running') {
        b.state = s.state;
        break;
      }
      b = s;
    }
    if (b === a) throw new Error(`the run ended during warm-up (${url})`);
    const dt = (b.t - a.t) / 1000;
    return {
      fps: +((b.frames - a.frames) / dt).toFixed(1),
      loops_per_s: Math.round((b.loops - a.loops) / dt),
      rollout_steps_per_s: Math.round((b.steps - a.steps) / dt),
      longest_task_ms: b.longest,
      long_tasks: b.longTasks,
      state_at_end: b.state,
      draw: perFrame(a.draw, b.draw),
      window: [a.loops, b.loops],
      config: a.config,
    };
  } finally {
    await page.close();
  }
}

/**
 * Frames/s late in a long episode (N=100, σ=15, full speed), once its path
 * has `moves` moves: the path must not cost more to draw as it grows.
 */
async function measureLongPath(context, url, moves) {
  const { page } = await openPage(context, url);
  try {
    await playAtFullSpeed(page, ['layer-rollouts', 'layer-practice']);
    await page.waitForFunction(
      (m) => window.torusTest.runs()[0].pathLen >= m || window.torusTest.state() !== 'running',
      moves,
      { timeout: 180_000, polling: 250 },
    );
    const probe = () => page.evaluate(() => ({
      t: performance.now(),
      frames: window.__bench.frames,
      moves: window.torusTest.runs()[0].pathLen - 1,
      state: window.torusTest.state(),
      longest: window.__bench.longest,
    }));
    await page.evaluate(() => {
      window.__bench.longest = 0;
    });
    const a = await probe();
    await page.waitForTimeout(3000);
    const b = await probe();
    if (a.state !== 'running' || b.state !== 'running') return { error: `the episode ended before ${moves} moves + 3 s` };
    return {
      moves: [a.moves, b.moves],
      fps: +((b.frames - a.frames) / ((b.t - a.t) / 1000)).toFixed(1),
      longest_task_ms: b.longest,
    };
  } finally {
    await page.close();
  }
}

/** Times, in one wasm call in the search worker, the loops a page measurement ran. */
async function measureWindow(context, url, m) {
  const { page } = await openPage(context, url);
  try {
    await page.waitForFunction(() => window.torusTest?.runs().length, null, { timeout: 60_000 });
    return await page.evaluate(async ({ config, window: [a, b] }) => {
      const t = window.torusTest;
      const run = async (loops) => {
        const answer = await t.request('benchLoops', { config, loops });
        if (!answer) throw new Error(`benchLoops failed: ${document.getElementById('message').textContent}`);
        return answer;
      };
      await run(Math.min(a, 5000)); // warm up
      const ta = (await run(a)).ms;
      const tb = (await run(b)).ms;
      return Math.round((b - a) / ((tb - ta) / 1000));
    }, m);
  } finally {
    await page.close();
  }
}

async function measureWasm(context, url) {
  const { page } = await openPage(context, url);
  try {
    await page.waitForFunction(() => window.torusTest?.engine, null, { timeout: 60_000 });
    return await page.evaluate(() => {
      const w = window.torusTest.engine;
      window.torusTest.dispatch({ type: 'pause' });
      const time = (fn) => {
        fn(); // warm up
        const t0 = performance.now();
        const r = fn();
        return [r, (performance.now() - t0) / 1000];
      };
      // The seed as decimal text, as in a config (the binding turns it into a u64).
      const [steps, ts] = time(() => w.benchRolloutSteps('rw', 40, 1, 2, '1', 2e8));
      // Flat engine configs (fields left out take their defaults); the seed is part of each.
      const cfg = { n: 40, prior: 'gaussian', sigma: 5, loops: 100, seed: '1' };
      const [loops, tl] = time(() => w.benchMctsLoops(cfg, 20000)[0]);
      const cfg0 = { n: 40, prior: 'delta', loops: 100, seed: '1' };
      const [loops0, tl0] = time(() => w.benchMctsLoops(cfg0, 20000)[0]);
      const cfg100 = { n: 100, prior: 'gaussian', sigma: 15, loops: 100, seed: '1' };
      const [loops100, tl100] = time(() => w.benchMctsLoops(cfg100, 5000)[0]);
      return {
        wasm_rw_steps_per_s: Math.round(steps / ts),
        wasm_loops_per_s_n40_sigma5: Math.round(loops / tl),
        wasm_loops_per_s_n40_sigma0: Math.round(loops0 / tl0),
        wasm_loops_per_s_n100_sigma15: Math.round(loops100 / tl100),
      };
    });
  } finally {
    await page.close();
  }
}

const BIN = path.join(ROOT, 'target', 'release', 'torus-search');

function native() {
  if (!existsSync(BIN)) return { native_error: 'build it first: cargo build --release' };
  try {
    const out = JSON.parse(execFileSync(BIN, ['bench', '--json'], { encoding: 'utf8', timeout: 600_000 }));
    return { native: out };
  } catch (err) {
    return { native_error: String(err.message).split('\n')[0] };
  }
}

/** Times natively the loops the page ran (same config, seed and loop numbers). */
function nativeWindow(m) {
  if (!existsSync(BIN)) return null;
  const dir = mkdtempSync(path.join(tmpdir(), 'torus-bench-'));
  const file = path.join(dir, 'config.json');
  // The run's engine config, its seed included.
  writeFileSync(file, JSON.stringify(m.config));
  const args = ['bench', '--json', '--episode', file, '--loops', `${m.window[0]}..${m.window[1]}`];
  return JSON.parse(execFileSync(BIN, args, { encoding: 'utf8', timeout: 600_000 })).loops_per_s;
}

const median = (xs) => {
  const v = xs.filter((x) => Number.isFinite(x)).sort((p, q) => p - q);
  if (!v.length) return null;
  const m = v.length >> 1;
  return v.length % 2 ? v[m] : (v[m - 1] + v[m]) / 2;
};
const r3 = (x) => (x === null ? null : +x.toFixed(3));

const server = await startServer(ROOT);
const browser = await launchBrowser({ viewport: { width: 1280, height: 900 } });
const result = { seconds, repeat, chromium: null, url_n256: null };
try {
  await browser.context.addInitScript(PROBE);
  result.chromium = browser.context.browser()?.version() ?? null;
  // N=256: the prior heat layer, the path and the gliding searcher (the
  // default picture), then the visits (a layer that changes) with the
  // rollout trails; N=100: a long episode at full speed. Each is measured `repeat`
  // times on fresh pages, and each measurement's loop window is also timed
  // in one wasm call in the search worker and (--native) natively, right
  // after it: this machine's speed drifts by ±10% over a minute, so ratios
  // are taken per measurement and the medians reported.
  const q256 = '?n=256&sigma=40&loops=100&seed=1&belief=posterior';
  result.url_n256 = q256;
  const noTraces = ['layer-rollouts', 'layer-practice'];
  const configs = [
    ['n256', q256, noTraces, []],
    ['n256_visits_trails', q256, [], ['layer-visits']],
    ['n100_sigma15', '?n=100&sigma=15&seed=1', noTraces, []],
  ];
  for (const [tag, query, untick, tick] of configs) {
    const runs = [];
    for (let k = 0; k < repeat; k++) {
      const m = await measurePage(browser.context, `${server.url}${query}`, { untick, tick });
      m.wasm = await measureWindow(browser.context, `${server.url}?autoplay=0`, m);
      m.native = wantNative ? nativeWindow(m) : null;
      runs.push(m);
    }
    const pick = (f) => median(runs.map(f));
    result[`fps_${tag}`] = r3(pick((m) => m.fps));
    result[`longest_task_ms_${tag}`] = Math.max(...runs.map((m) => m.longest_task_ms));
    result[`draw_ms_per_frame_${tag}`] = Object.fromEntries(Object.keys(runs[0].draw.ms).map((k) => [k, r3(pick((m) => m.draw.ms[k]))]));
    result[`put_image_data_per_frame_${tag}`] = r3(pick((m) => m.draw.puts));
    result[`changed_layers_per_frame_${tag}`] = r3(pick((m) => m.draw.changed_layers));
    result[`long_tasks_${tag}`] = runs.reduce((a, m) => a + m.long_tasks, 0);
    result[`page_loops_per_s_${tag}`] = Math.round(pick((m) => m.loops_per_s));
    result[`wasm_window_loops_per_s_${tag}`] = Math.round(pick((m) => m.wasm));
    result[`page_over_wasm_window_${tag}`] = r3(pick((m) => m.loops_per_s / m.wasm));
    if (wantNative && runs.every((m) => m.native)) {
      result[`native_window_loops_per_s_${tag}`] = Math.round(pick((m) => m.native));
      result[`page_over_native_${tag}`] = r3(pick((m) => m.loops_per_s / m.native));
      result[`wasm_window_over_native_${tag}`] = r3(pick((m) => m.wasm / m.native));
    }
    result[`runs_${tag}`] = runs.map((m) => ({
      window: m.window,
      fps: m.fps,
      page: m.loops_per_s,
      wasm: m.wasm,
      native: m.native === null ? null : Math.round(m.native),
    }));
  }
  result.fps_n100_long_path = await measureLongPath(browser.context, `${server.url}?n=100&sigma=15&seed=1`, 9000);
  Object.assign(result, await measureWasm(browser.context, `${server.url}?autoplay=0`));
} finally {
  await browser.close();
  await server.close();
}
if (wantNative) Object.assign(result, native());
console.log(JSON.stringify(result, null, 2));
