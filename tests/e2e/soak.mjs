#!/usr/bin/env node
// Soak test: plays the page for --minutes through episodes of varied
// configurations drawn from a seeded generator (N from 3 to 1024, every
// searcher and MCTS variant, race mode, batches in the worker pool), the way
// a user changes the controls: in one page, never reloading. Every
// --sample seconds it records the page's JS heap after a forced GC (CDP
// Runtime.getHeapUsage), the wasm memory of the page and of the search
// worker, the fps and the long tasks.
//
// Pass: no error (console, page state, batch), and memory flat after
// warm-up: the mean footprint (JS heap + page wasm + worker wasm), each
// wasm memory, the DOM node count and the event listener count over the
// last window grow less than 5% over the first window after warm-up
// (windows of 10 minutes for a 60-minute run, a third of the run after
// warm-up for short ones). The first scenarios are the largest (N = 1024
// alone, in a race and in a batch), so the warm-up reaches the high-water
// mark of wasm memory, which cannot shrink; after it the page must reuse,
// not grow.
//
// A sample comes every 60 s from 20 minutes up, every 10 s from 2 minutes
// up, else every 2 s: `make test` runs 20 s (the warm-up and about eight
// samples: an error or a gross leak), `make soak` 10 minutes or more.
//
// Usage: node tests/e2e/soak.mjs [--minutes M] [--seed S] [--sample SECONDS] [--json FILE]
import assert from 'node:assert/strict';
import { writeFile } from 'node:fs/promises';
import { describeProblems, launchBrowser, openPage, startServer } from './harness.mjs';

function arg(name, def, ok, allowed) {
  const i = process.argv.indexOf(`--${name}`);
  if (i < 0) return def;
  const v = process.argv[i + 1];
  if (!ok(v)) {
    console.error(`error: --${name} must be ${allowed}, got ${JSON.stringify(v)}`);
    process.exit(2);
  }
  return v;
}
const minutes = Number(arg('minutes', '2', (v) => Number(v) > 0 && Number(v) <= 24 * 60, 'a number of minutes in (0, 1440]'));
const seed = Number(arg('seed', '1', (v) => /^\d{1,9}$/.test(v ?? ''), 'an integer in 0..=999999999'));
const sample = Number(arg('sample', String(minutes >= 20 ? 60 : minutes >= 2 ? 10 : 2), (v) => Number(v) >= 1 && Number(v) <= 600, 'seconds in [1, 600]'));
const jsonOut = arg('json', null, (v) => typeof v === 'string' && v.length > 0, 'a file name');

/** mulberry32: a small seeded generator, so a soak is replayable. */
function rng(s) {
  let a = s >>> 0;
  return () => {
    a = (a + 0x6d2b79f5) >>> 0;
    let t = a;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}
const rand = rng(seed);
const pick = (xs) => xs[Math.floor(rand() * xs.length)];

const server = await startServer();
const browser = await launchBrowser();
const { page, report } = await openPage(browser.context, `${server.url}?autoplay=0&speed=max`);
await page.waitForFunction(() => window.torusTest?.runs().length > 0, null, { timeout: 60_000 });
const cdp = await page.context().newCDPSession(page);
await page.evaluate(() => {
  window.__long = [];
  new PerformanceObserver((l) => window.__long.push(...l.getEntries().map((e) => e.duration))).observe({ type: 'longtask' });
});
const schema = await page.evaluate(() => window.torusTest.engine.schema());
const searchers = schema.searchers.map((s) => s.name);
const variants = schema.params.find((p) => p.key === 'variant').choices;
const raceIds = await page.evaluate(() => [...document.getElementById('race').options].map((o) => o.value));

/** Sets a control as a user does: its value, then its change event. */
async function set(id, value) {
  await page.evaluate(([i, v]) => {
    const el = document.getElementById(i);
    el.value = v;
    el.dispatchEvent(new Event(el.type === 'range' ? 'input' : 'change'));
    if (el.type === 'range') el.dispatchEvent(new Event('change'));
  }, [id, String(value)]);
}

async function waitSettled(ms) {
  const t0 = Date.now();
  while (Date.now() - t0 < ms) {
    await page.waitForTimeout(250);
    const st = await page.evaluate(() => document.body.dataset.state);
    if (st === 'error') throw new Error(`page state error: ${await page.locator('#message').textContent()}`);
    if (st === 'found' || st === 'capped') break;
  }
}

/** One scenario: a live run (maybe a race) or a batch, for a few seconds. */
async function scenario(spec) {
  await set('race', '');
  await set('n', spec.n);
  await set('searcher', spec.searcher);
  if (spec.variant && (await page.locator('#variant').isEnabled())) await set('variant', spec.variant);
  if (spec.race) await set('race', spec.race);
  if (spec.batch) {
    await set('batch-trials', spec.batch);
    await page.evaluate(() => delete document.body.dataset.batch);
    await page.click('#batch-run');
    // A user stops a batch that takes too long; stopping is part of the soak.
    const over = () => ['done', 'error', 'stopped'].includes(document.body.dataset.batch);
    if (!(await page.waitForFunction(over, null, { timeout: spec.ms }).then(() => true, () => false))) {
      // The batch may end between the wait and the click (Stop is then
      // disabled): click only a live Stop, then the batch must be over.
      await page.evaluate(() => {
        const stop = document.getElementById('batch-stop');
        if (!stop.disabled) stop.click();
      });
      await page.waitForFunction(over, null, { timeout: 30_000 });
    }
    const b = await page.evaluate(() => document.body.dataset.batch);
    if (b === 'error') throw new Error(`batch ${b}: ${await page.locator('#batch-progress').textContent()}`);
  } else {
    if ((await page.evaluate(() => document.body.dataset.state)) !== 'running') await page.click('#play').catch(() => {});
    await waitSettled(spec.ms);
  }
}

function nextSpec(i) {
  // Warm-up: the largest footprints first (see the header).
  const warm = [
    { n: 1024, searcher: 'mcts', variant: 'tree', ms: 4000 },
    { n: 1024, searcher: 'mcts', variant: 'cells', race: 'rw', ms: 4000 },
    { n: 1024, searcher: 'rw', batch: 4, ms: 8000 },
  ];
  if (i < warm.length) return warm[i];
  const n = pick([3, 4, 5, 8, 12, 20, 40, 40, 64, 128, 256, 512, 1024]);
  const r = rand();
  return {
    n,
    searcher: pick(searchers),
    variant: pick(variants),
    race: r < 0.3 ? pick(raceIds.filter(Boolean)) : '',
    batch: r > 0.85 ? (n > 256 ? 4 : 20) : 0,
    ms: 1000 + Math.floor(rand() * 4000),
  };
}

async function measure(t0) {
  await cdp.send('HeapProfiler.collectGarbage');
  const heap = await cdp.send('Runtime.getHeapUsage');
  const dom = await cdp.send('Memory.getDOMCounters');
  const m = await page.evaluate(async () => {
    const t = window.torusTest;
    const usage = await t.request('usage').catch(() => null);
    const long = window.__long.splice(0);
    return {
      pageWasm: t.engine.memoryBytes(),
      workerWasm: usage?.usage?.memoryBytes ?? 0,
      fps: t.fps(),
      longTasks: long.length,
      longestMs: Math.round(Math.max(0, ...long)),
    };
  });
  return { minute: +((Date.now() - t0) / 60_000).toFixed(2), jsHeap: heap.usedSize, domNodes: dom.nodes, listeners: dom.jsEventListeners, ...m };
}

const t0 = Date.now();
const end = t0 + minutes * 60_000;
const samples = [];
let nextSample = t0;
let i = 0;
let failure = null;
try {
  while (Date.now() < end) {
    const spec = nextSpec(i++);
    spec.ms = Math.max(500, Math.min(spec.ms, end - Date.now()));
    await scenario(spec);
    if (describeProblems(report)) throw new Error(describeProblems(report));
    if (Date.now() >= nextSample) {
      const s = { ...(await measure(t0)), scenarios: i, warm: i <= 3 };
      samples.push(s);
      console.log(JSON.stringify(s));
      nextSample += sample * 1000;
    }
  }
  samples.push({ ...(await measure(t0)), scenarios: i, warm: false });
} catch (err) {
  failure = err;
} finally {
  await browser.close();
  await server.close();
}

const mib = (b) => b / 2 ** 20;
const foot = (s) => s.jsHeap + s.pageWasm + s.workerWasm;
const after = samples.filter((s) => !s.warm);
const window = Math.max(1, Math.floor(minutes >= 30 ? after.length * (10 / minutes) : after.length / 3));
const mean = (xs, f) => xs.reduce((a, s) => a + f(s), 0) / xs.length;
/** Growth of the mean of `f` from the first window after warm-up to the last. */
const growthOf = (f) => {
  if (!after.length) return 0;
  const a = mean(after.slice(0, window), f);
  return a > 0 ? mean(after.slice(-window), f) / a - 1 : 0;
};
const first = after.length ? mean(after.slice(0, window), foot) : 0;
const last = after.length ? mean(after.slice(-window), foot) : 0;
const growth = growthOf(foot);
// The worker's wasm is most of the footprint and would hide a leak in the
// page, so the page's DOM nodes and event listeners must stay flat too.
// The JS heap is reported, not judged: what it gains after warm-up is
// compiled code (a heap-snapshot diff over 300 resets finds only V8 code
// objects: InstructionStream, Code, TrustedByteArray), which the JIT adds
// as functions get hot and which levels off.
const parts = { pageWasm: growthOf((s) => s.pageWasm), workerWasm: growthOf((s) => s.workerWasm), domNodes: growthOf((s) => s.domNodes), listeners: growthOf((s) => s.listeners) };
const jsHeapGrowth = growthOf((s) => s.jsHeap);
const table = samples.map((s) => `| ${s.minute} | ${mib(s.jsHeap).toFixed(1)} | ${mib(s.pageWasm).toFixed(0)} | ${mib(s.workerWasm).toFixed(0)} | ${s.domNodes} | ${s.listeners} | ${s.fps.toFixed(0)} | ${s.longTasks} (${s.longestMs} ms) | ${s.scenarios} |`);
console.log(['| minute | JS heap MiB | page wasm MiB | worker wasm MiB | DOM nodes | listeners | fps | long tasks (longest) | scenarios |', '| --- | --- | --- | --- | --- | --- | --- | --- | --- |', ...table].join('\n'));
const pct = (g) => `${(100 * g).toFixed(2)}%`;
console.log(`footprint: first window ${mib(first).toFixed(1)} MiB, last window ${mib(last).toFixed(1)} MiB, growth ${pct(growth)} (page wasm ${pct(parts.pageWasm)}, worker wasm ${pct(parts.workerWasm)}, DOM nodes ${pct(parts.domNodes)}, listeners ${pct(parts.listeners)}; JS heap ${pct(jsHeapGrowth)}, not judged; ${window} samples each); ${i} scenarios, seed ${seed}`);
if (jsonOut) await writeFile(jsonOut, JSON.stringify({ minutes, seed, sample, samples, growth, parts, jsHeapGrowth }, null, 1));
if (failure) {
  console.error(`soak failed after ${i} scenarios: ${failure.message}`);
  process.exit(1);
}
assert.ok(after.length >= 2, 'the soak ran long enough to compare windows');
for (const [name, g] of Object.entries({ footprint: growth, ...parts })) {
  if (!(g < 0.05)) {
    console.error(`soak failed: ${name} grew ${pct(g)} from the first window after warm-up to the last (limit 5%)`);
    process.exit(1);
  }
}
console.log('soak passed');
