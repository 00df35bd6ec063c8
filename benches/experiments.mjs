#!/usr/bin/env node
// Benchmark of experiments, CLI against the page (no timed assertions;
// `make bench` runs it, not `make test`). Prints a table and one JSON line.
//
//  A. The figure: `sigma-sweep` (--exp) at T trials per point (--trials),
//     run by the CLI with --threads K and by the page's Experiments view
//     with a pool of K Web Workers (K = --threads, default 2).
//  B. Rates and scaling on an experiment of many similar trials (--rate-exp,
//     default `delta`, at --rate-trials, default 100): the CLI with K threads
//     and with 1, the page with K workers and with 1. Ratios of trials/s:
//     page K / CLI K (goal ≥ 0.7) and page K / page 1 (goal ≥ 1.7 for K = 2);
//     CLI K / CLI 1 shows what the machine gave at the time (the cores may
//     be shared). sigma-sweep is a poor workload for scaling: at small T one
//     trapped MCTS episode (thousands of moves at the step cap) takes most of
//     the time on one core whatever the pool size.
//
// The CLI time is the process's wall time; the page time is the view's own
// run timer (first chunk handed out to the result assembled), as the page
// shows it. Every page result is compared with the CLI's, byte for byte.
// Usage: node benches/experiments.mjs [--exp NAME] [--trials T] [--rate-exp NAME]
//        [--rate-trials T] [--threads K] [--seed S] [--skip-figure]
// Needs `make build` (www/pkg); builds the release CLI if stale.
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { ROOT, cliBinary, launchBrowser, openPage, startServer } from '../tests/e2e/harness.mjs';

const args = process.argv.slice(2);
const arg = (name, def) => (args.includes(name) ? args[args.indexOf(name) + 1] : def);
const figure = { exp: arg('--exp', 'sigma-sweep'), trials: Number(arg('--trials', '10')) };
const rates = { exp: arg('--rate-exp', 'delta'), trials: Number(arg('--rate-trials', '100')) };
const threads = Number(arg('--threads', '2'));
const seed = arg('--seed', '1');
const skipFigure = args.includes('--skip-figure');

const BIN = cliBinary({ release: true });

/** Runs the CLI; resolves to { seconds, units, text }. */
function cli(exp, trials, k) {
  const dir = mkdtempSync(path.join(tmpdir(), 'torus-bench-exp-'));
  try {
    const t0 = process.hrtime.bigint();
    execFileSync(BIN, ['experiment', exp, '--trials', String(trials), '--seed', seed, '--threads', String(k), '--out', dir], { stdio: ['ignore', 'ignore', 'inherit'], timeout: 6 * 3_600_000 });
    const seconds = Number(process.hrtime.bigint() - t0) / 1e9;
    const text = readFileSync(path.join(dir, `${exp}.json`), 'utf8');
    return { seconds, units: JSON.parse(text).units.total, text };
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
}

/** Runs the experiment in a fresh page with k workers; resolves to { seconds, units, text }. */
async function page(context, url, exp, trials, k) {
  const { page: p } = await openPage(context, `${url}?view=experiments&exp=${encodeURIComponent(exp)}&trials=${trials}&seed=${seed}`);
  try {
    await p.waitForFunction(() => window.torusTest?.experiments, null, { timeout: 60_000 });
    return await p.evaluate(async (workers) => {
      const x = window.torusTest.experiments;
      x.usePool(workers);
      const text = await x.run();
      if (!text) throw new Error(`the run failed: ${document.getElementById('exp-status').textContent} ${document.getElementById('message').textContent}`);
      const r = x.lastRun();
      return { seconds: r.seconds, units: r.units, text };
    }, k);
  } finally {
    await p.close();
  }
}

const rows = [];
const rate = (r) => r.units / r.seconds;
function row(part, what, exp, trials, r, cliText) {
  rows.push({ part, what, experiment: exp, trials, units: r.units, seconds: +r.seconds.toFixed(2), trials_per_s: +rate(r).toFixed(2), same_json_as_cli: r.text === cliText });
}

const server = await startServer(ROOT);
const browser = await launchBrowser();
const out = {};
try {
  if (!skipFigure) {
    const c = cli(figure.exp, figure.trials, threads);
    row('A', `CLI, ${threads} threads`, figure.exp, figure.trials, c, c.text);
    const p = await page(browser.context, server.url, figure.exp, figure.trials, threads);
    row('A', `page, ${threads} workers`, figure.exp, figure.trials, p, c.text);
    out.figure = { experiment: figure.exp, trials: figure.trials, cli_seconds: +c.seconds.toFixed(2), page_seconds: +p.seconds.toFixed(2), page_over_cli: +(rate(p) / rate(c)).toFixed(3) };
  }
  const cK = cli(rates.exp, rates.trials, threads);
  row('B', `CLI, ${threads} threads`, rates.exp, rates.trials, cK, cK.text);
  const c1 = cli(rates.exp, rates.trials, 1);
  row('B', 'CLI, 1 thread', rates.exp, rates.trials, c1, cK.text);
  const pK = await page(browser.context, server.url, rates.exp, rates.trials, threads);
  row('B', `page, ${threads} workers`, rates.exp, rates.trials, pK, cK.text);
  const p1 = await page(browser.context, server.url, rates.exp, rates.trials, 1);
  row('B', 'page, 1 worker', rates.exp, rates.trials, p1, cK.text);
  out.rates = {
    experiment: rates.exp,
    trials: rates.trials,
    page_over_cli: +(rate(pK) / rate(cK)).toFixed(3),
    page_workers_speedup: +(rate(pK) / rate(p1)).toFixed(3),
    cli_threads_speedup: +(rate(cK) / rate(c1)).toFixed(3),
    page1_over_cli1: +(rate(p1) / rate(c1)).toFixed(3),
  };
} finally {
  await browser.close();
  await server.close();
}

console.log(`\nexperiments: CLI (${BIN}) against the page's worker pool, seed ${seed}\n`);
console.table(rows);
if (out.figure) console.log(`A. ${out.figure.experiment} at T = ${out.figure.trials}: CLI ${out.figure.cli_seconds} s, page ${out.figure.page_seconds} s (${threads} cores); page/CLI trials/s ${out.figure.page_over_cli}`);
const r = out.rates;
console.log(`B. ${r.experiment} at T = ${r.trials}: page/CLI trials/s with ${threads} ${r.page_over_cli} (goal ≥ 0.7); page ${threads} workers / 1 worker ${r.page_workers_speedup} (goal ≥ 1.7 for 2); CLI ${threads} threads / 1 thread ${r.cli_threads_speedup}; page 1 / CLI 1 ${r.page1_over_cli1}`);
console.log(JSON.stringify({ seed, threads, rows: rows.map(({ part, what, experiment, trials, units, seconds, trials_per_s, same_json_as_cli }) => ({ part, what, experiment, trials, units, seconds, trials_per_s, same_json_as_cli })), ...out }));
if (rows.some((x) => !x.same_json_as_cli)) {
  console.error('error: a run differs from the CLI run (see same_json_as_cli)');
  process.exitCode = 1;
}
