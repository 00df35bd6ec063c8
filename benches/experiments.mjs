#!/usr/bin/env node
// Benchmark of experiments (no timed assertions; `make bench` runs it, not
// `make test`): one experiment (default `sigma-sweep`) at T trials per
// point, run
//   - by the CLI (`target/release/torus-search experiment NAME --trials T
//     --threads K`), wall time of the process;
//   - by the page's Experiments view with a pool of K Web Workers, and with
//     one worker (the view's own run timer: from the first chunk handed out
//     to the result assembled, as the page shows it);
// and prints a table: seconds, trials/s, the page's rate over the CLI's
// (goal ≥ 0.7) and K workers over 1 (goal ≥ 1.7 for K = 2). Each run's
// JSON is compared with the CLI's, byte for byte.
// Usage: node benches/experiments.mjs [--exp NAME] [--trials T] [--threads K] [--seed S] [--one-worker-trials T1]
// Needs `make build` (www/pkg) and builds the release CLI if stale.
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { ROOT, cliBinary, launchBrowser, openPage, startServer } from '../tests/e2e/harness.mjs';

const args = process.argv.slice(2);
const arg = (name, def) => (args.includes(name) ? args[args.indexOf(name) + 1] : def);
const name = arg('--exp', 'sigma-sweep');
const trials = Number(arg('--trials', '10'));
const threads = Number(arg('--threads', '2'));
const seed = arg('--seed', '1');
// One worker takes K times as long: a smaller T keeps it in minutes (rates are per trial).
const oneTrials = Number(arg('--one-worker-trials', String(trials)));

const BIN = cliBinary({ release: true });

function cli(t) {
  const dir = mkdtempSync(path.join(tmpdir(), 'torus-bench-exp-'));
  try {
    const t0 = process.hrtime.bigint();
    execFileSync(BIN, ['experiment', name, '--trials', String(t), '--seed', seed, '--threads', String(threads), '--out', dir], { stdio: ['ignore', 'ignore', 'inherit'], timeout: 3_600_000 });
    const seconds = Number(process.hrtime.bigint() - t0) / 1e9;
    return { seconds, text: readFileSync(path.join(dir, `${name}.json`), 'utf8') };
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
}

/** Runs the experiment in the page with k workers; resolves to { seconds, units, text }. */
async function page(context, url, k, t) {
  const { page: p } = await openPage(context, `${url}?view=experiments&exp=${encodeURIComponent(name)}&trials=${t}&seed=${seed}`);
  try {
    await p.waitForFunction(() => window.torusTest?.experiments, null, { timeout: 60_000 });
    return await p.evaluate(async (workers) => {
      const x = window.torusTest.experiments;
      x.usePool(workers);
      const text = await x.run();
      if (!text) throw new Error(`the run failed: ${document.getElementById('exp-status').textContent} ${document.getElementById('message').textContent}`);
      return { ...x.lastRun(), text };
    }, k);
  } finally {
    await p.close();
  }
}

const rows = [];
const row = (what, workers, t, seconds, units, same) => rows.push({ what, workers, trials: t, seconds: +seconds.toFixed(2), units, trials_per_s: +(units / seconds).toFixed(2), same_json_as_cli: same });

const native = cli(trials);
const units = JSON.parse(native.text).units.total;
row(`CLI --threads ${threads}`, threads, trials, native.seconds, units, true);
const nativeOne = oneTrials === trials ? native : cli(oneTrials);

const server = await startServer(ROOT);
const browser = await launchBrowser();
let pageK;
let pageOne;
try {
  pageK = await page(browser.context, server.url, threads, trials);
  row(`page, ${threads} workers`, threads, trials, pageK.seconds, pageK.units, pageK.text === native.text);
  pageOne = await page(browser.context, server.url, 1, oneTrials);
  row('page, 1 worker', 1, oneTrials, pageOne.seconds, pageOne.units, pageOne.text === nativeOne.text);
} finally {
  await browser.close();
  await server.close();
}

const rate = (r) => r.units / r.seconds;
console.log(`\nexperiment ${name}, seed ${seed}, ${units} trials at T = ${trials} (${BIN})\n`);
console.table(rows);
const summary = {
  page_over_cli: +(rate(pageK) / (units / native.seconds)).toFixed(3),
  workers_speedup: +(rate(pageK) / rate(pageOne)).toFixed(3),
};
console.log(`page trials/s over CLI trials/s (${threads} workers vs ${threads} threads): ${summary.page_over_cli} (goal ≥ 0.7)`);
console.log(`${threads} workers over 1 worker (trials/s): ${summary.workers_speedup} (goal ≥ 1.7 for 2)`);
console.log(JSON.stringify({ name, seed, trials, one_worker_trials: oneTrials, threads, rows, ...summary }));
if (rows.some((r) => !r.same_json_as_cli)) {
  console.error('error: a page run differs from the CLI run (see same_json_as_cli)');
  process.exitCode = 1;
}
