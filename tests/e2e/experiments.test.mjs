// End-to-end tests of the Experiments view (www/experiments/view.js) in Debian's
// Chromium, with the shared harness: the page and the CLI give the same
// result for the same experiment and seed (byte for byte), whatever the
// number of workers; a cancelled run leaves the page usable and the next
// run starts clean; bad results files and bad URL values get messages and
// change nothing; downloads; a point opens in the live view.
// Needs `make build` first (www/pkg, www/vendor); builds the debug CLI if stale.
//
// The tests read and drive the view through `window.torusTest` (www/shared/test-hook.js)
// and its own controls. Experiments are tiny (N = 12, a few trials).
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { after, before, test } from 'node:test';
import { ROOT, cliBinary, describeProblems, launchBrowser, openPage, screenshot, startServer } from './harness.mjs';
import { stripProvenance as strip } from './strip.mjs';

let server;
let browser;
let BIN;

before(async () => {
  assert.ok(existsSync(path.join(ROOT, 'www', 'pkg', 'torus_search.js')), 'www/pkg is missing: run `make build` first');
  assert.ok(existsSync(path.join(ROOT, 'www', 'vendor', 'plot.umd.min.js')), 'www/vendor is missing: run `make build` first');
  BIN = cliBinary();
  server = await startServer(ROOT);
  browser = await launchBrowser({ viewport: { width: 1280, height: 900 } });
});

after(async () => {
  await browser?.close();
  await server?.close();
});

/** A small custom sweep: σ ∈ {0, 3} on a 12-torus, MCTS (20 loops) and RW, 3 trials per point. */
const SMALL = {
  trials: '3',
  seed: '11',
  params: [['n', '12'], ['loops', '20'], ['step_cap', '400']],
  sweep: ['sigma', ['0', '3']],
  series: ['MCTS:searcher=mcts', 'RW:searcher=rw'],
};

function smallQuery({ trials = SMALL.trials, seed = SMALL.seed } = {}) {
  const q = new URLSearchParams([['view', 'experiments'], ['exp', 'custom'], ['trials', trials], ['seed', seed], ...SMALL.params]);
  q.set('sweep', `${SMALL.sweep[0]}:${SMALL.sweep[1].join(' ')}`);
  for (const s of SMALL.series) q.append('series', s);
  return `?${q}`;
}

/** The CLI's files for the same experiment: { json, csv, trials, paired } (text). */
function cliSmall({ trials = SMALL.trials, seed = SMALL.seed } = {}) {
  const dir = mkdtempSync(path.join(tmpdir(), 'torus-e2e-exp-'));
  try {
    const args = ['experiment', 'custom', '--trials', trials, '--seed', seed, '--out', dir, '--threads', '2'];
    for (const [k, v] of SMALL.params) args.push(`--${k.replaceAll('_', '-')}`, v);
    args.push('--sweep', `${SMALL.sweep[0]}=${SMALL.sweep[1].join(',')}`);
    for (const s of SMALL.series) args.push('--series', s);
    execFileSync(BIN, args, { stdio: ['ignore', 'ignore', 'pipe'], timeout: 300_000 });
    const file = (ext) => readFileSync(path.join(dir, `custom.${ext}`), 'utf8');
    return { json: file('json'), csv: file('csv'), trials: file('trials.csv'), paired: file('paired.csv') };
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
}

/** Opens the page at `query` and runs fn(page, report); fails on console errors unless allowed. */
async function withView(query, fn, { allowErrors = false } = {}) {
  const { page, report } = await openPage(browser.context, `${server.url}${query}`);
  try {
    await page.waitForFunction(() => window.torusTest?.experiments && window.torusTest.runs().length, null, { timeout: 30_000 });
    await fn(page, report);
    if (!allowErrors) assert.equal(describeProblems(report), '', 'the page reported problems');
  } finally {
    await page.close();
  }
}

const status = (page) => page.evaluate(() => window.torusTest.experiments.status());
const message = (page) => page.evaluate(() => (document.getElementById('message').hidden ? '' : document.getElementById('message').textContent));

/** Clicks Run and waits for the run to end; returns its status. */
async function runAndWait(page, timeout = 240_000) {
  await page.click('#exp-run');
  await page.waitForFunction(() => ['done', 'error', 'cancelled'].includes(document.body.dataset.experiment), null, { timeout, polling: 100 });
  return status(page);
}

test('the page and the CLI give the same result, byte for byte, for any number of workers', { timeout: 600_000 }, async () => {
  const cli = cliSmall();
  await withView(smallQuery(), async (page) => {
    assert.equal(await page.evaluate(() => window.torusTest.view()), 'experiments');
    assert.equal(await page.locator('#experiments').isVisible(), true);
    assert.equal(await message(page), '', 'the URL is valid');
    // The controls show the URL's experiment.
    assert.equal(await page.inputValue('#exp-name'), 'custom');
    assert.equal(await page.inputValue('#exp-trials'), SMALL.trials);
    assert.equal(await page.inputValue('#exp-seed'), SMALL.seed);
    assert.equal(await page.inputValue('#exp-sweep-key'), 'sigma');
    assert.equal(await page.inputValue('#exp-sweep-values'), '0 3');
    const controls = ['#exp-chart', '#exp-csv', '#exp-trials-csv', '#exp-paired-csv', '#exp-json', '#exp-svg', '#exp-png'];
    // Nothing to chart or download before a result.
    for (const id of controls) {
      assert.equal(await page.locator(id).isDisabled(), true, `${id} before a result`);
    }
    assert.equal(await runAndWait(page), 'done', await page.locator('#exp-status').textContent());
    for (const id of controls) {
      assert.equal(await page.locator(id).isDisabled(), false, `${id} with a result`);
    }
    const text = await page.evaluate(() => window.torusTest.experiments.result());
    // The same bytes but for the provenance (the page's: its build, the date, its URL).
    assert.equal(strip(text), strip(cli.json), 'the page JSON is the CLI JSON');
    assert.notEqual(text, cli.json, 'each carries its own provenance');
    const prov = JSON.parse(text).provenance;
    assert.deepEqual(Object.keys(prov), ['version', 'commit', 'dirty', 'date', 'command']);
    const build = await page.evaluate(async () => (await import('./www/shared/provenance.js')).currentBuild());
    assert.equal(prov.commit, build.commit, "the page's engine made it");
    assert.match(prov.commit, /^([0-9a-f]{40}|unknown)$/);
    assert.match(prov.date, /^\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ$/);
    assert.ok(prov.command.startsWith(server.url), prov.command);
    const csv = await page.evaluate(() => window.torusTest.experiments.exported('csv'));
    assert.equal(strip(csv), strip(cli.csv), 'the page CSV is the CLI CSV');
    assert.ok(csv.includes(`\n# date: ${prov.date}\n`), 'the CSV carries the provenance of its result');
    assert.equal(strip(await page.evaluate(() => window.torusTest.experiments.exported('trials-csv'))), strip(cli.trials), 'the per-trial CSV is the CLI\'s');
    assert.equal(strip(await page.evaluate(() => window.torusTest.experiments.exported('paired-csv'))), strip(cli.paired), 'the paired CSV is the CLI\'s');
    const result = JSON.parse(text);
    // One row per trial; the paired table: RW against MCTS at each σ, as the engine computed it.
    assert.equal(strip(cli.trials).trim().split('\n').length, 1 + 12);
    assert.equal(result.paired.length, 2);
    assert.equal(await page.locator('#exp-paired tbody tr').count(), 2);
    const first = await page.locator('#exp-paired tbody tr').first().locator('td').allTextContents();
    const c = result.paired[0];
    assert.deepEqual(first.slice(0, 4), ['RW', 'MCTS', '0', '3']);
    assert.equal(first[5], `${c.wins} / ${c.ties} / ${c.losses}`);
    assert.ok(first[4].startsWith(c.difference.estimate.toFixed(1)), first[4]);
    assert.equal(result.points.length, 4);
    assert.equal(result.units.total, 12);
    // The chart and the table show the result; the status reports the run.
    assert.ok(await page.locator('#exp-figure svg').count() > 0, 'a chart is drawn');
    assert.equal(await page.locator('#exp-table tbody tr').count(), 4);
    assert.match(await page.locator('#exp-status').textContent(), /^12 trials in .* on \d+ workers? \(/);
    const workers = await page.evaluate(() => window.torusTest.experiments.workers());
    assert.equal(workers, await page.evaluate(() => navigator.hardwareConcurrency));
    await screenshot(page, 'experiments-custom');
    // One worker, and three: the same bytes.
    for (const k of [1, 3]) {
      await page.evaluate((n) => window.torusTest.experiments.usePool(n), k);
      assert.equal(await runAndWait(page), 'done');
      assert.equal(strip(await page.evaluate(() => window.torusTest.experiments.result())), strip(cli.json), `${k} worker(s)`);
    }
    // Fault injection: a worker dies mid-run. The pool replaces it and the
    // fresh worker re-runs its chunk: the same bytes.
    await page.evaluate(() => window.torusTest.experiments.usePool(2));
    await page.click('#exp-run');
    assert.equal(await status(page), 'running');
    assert.equal(await page.evaluate(() => window.torusTest.experiments.killWorker(0)), true);
    await page.waitForFunction(() => ['done', 'error', 'cancelled'].includes(document.body.dataset.experiment), null, { timeout: 240_000, polling: 100 });
    assert.equal(await status(page), 'done', await page.locator('#exp-status').textContent());
    assert.equal(await page.evaluate(() => window.torusTest.experiments.replaced()), 1, 'one worker was replaced');
    assert.equal(strip(await page.evaluate(() => window.torusTest.experiments.result())), strip(cli.json), 'a lost worker changes no byte');
    // Downloads: SVG (the chart, with its title) and PNG.
    const svg = await page.evaluate(() => window.torusTest.experiments.exported('svg'));
    assert.match(svg, /^<svg xmlns="http:\/\/www.w3.org\/2000\/svg"/);
    assert.ok(svg.includes(result.experiment.title), 'the SVG has the title');
    assert.ok((await page.evaluate(() => window.torusTest.experiments.exported('png'))) > 2000, 'a PNG of the chart');
    for (const mode of ['mean', 'excess', 'box', 'paired']) {
      await page.selectOption('#exp-chart', mode);
      await page.waitForSelector(`#exp-figure[data-mode="${mode}"] svg`, { timeout: 10_000 });
    }
    // The paired chart draws the engine's comparisons: its legend names each pair.
    const pairedSvg = await page.evaluate(() => window.torusTest.experiments.exported('svg'));
    const pair = `${result.paired[0].series} − ${result.paired[0].reference}`;
    assert.ok(pairedSvg.includes(pair), `the paired chart's legend names ${pair}`);
    // The Download buttons save files named as the CLI names them.
    const [dl] = await Promise.all([page.waitForEvent('download'), page.click('#exp-json')]);
    assert.equal(dl.suggestedFilename(), 'custom.json');
    const [trials] = await Promise.all([page.waitForEvent('download'), page.click('#exp-trials-csv')]);
    assert.equal(trials.suggestedFilename(), 'custom.trials.csv');
  });
});

test('a point opens in the live view with its configuration and the seed of its trial 0', { timeout: 300_000 }, async () => {
  await withView(smallQuery(), async (page) => {
    assert.equal(await runAndWait(page), 'done');
    const text = await page.evaluate(() => window.torusTest.experiments.result());
    const result = JSON.parse(text);
    // The RW point at σ = 3 (the last one): open it from the table.
    const p = result.points.at(-1);
    await page.locator('#exp-table tbody tr').last().getByRole('button', { name: 'Open' }).click();
    await page.waitForFunction(() => window.torusTest.view() === 'live', null, { timeout: 10_000 });
    await page.evaluate(() => window.torusTest.ready());
    const run = (await page.evaluate(() => window.torusTest.runs()))[0];
    assert.deepEqual(run.config, { ...p.config, keep_traces: run.config.keep_traces });
    assert.equal(run.config.seed, result.spec.seed);
    assert.match(await message(page), /^Opened RW at sigma = 3 from “Custom experiment”: trial 0 of the point \(seed 11\)\.$/);
    assert.match(page.url(), /[?&]seed=11(&|$)/, 'the live URL carries the seed');
    // The live episode is the point's trial 0: the same steps and target as its row.
    const steps = result.row_fields.indexOf('steps');
    const target = result.row_fields.indexOf('target');
    const row = result.rows.find((r) => r[0] === p.index && r[1] === 0);
    await page.evaluate(() => {
      window.torusTest.dispatch({ type: 'speed', speed: 'max' });
      window.torusTest.dispatch({ type: 'play' });
    });
    await page.waitForFunction(() => ['found', 'capped'].includes(window.torusTest.state()), null, { timeout: 60_000 });
    const ended = (await page.evaluate(() => window.torusTest.runs()))[0];
    assert.equal(ended.steps, row[steps], 'steps of trial 0');
    assert.equal(ended.target, row[target], 'target cell of trial 0');
    assert.doesNotMatch(page.url(), /view=experiments/);
    // Back to the experiments: the result is still there.
    await page.click('#tab-experiments');
    assert.equal(await page.evaluate(() => window.torusTest.experiments.result()), text);
    assert.match(page.url(), /view=experiments&exp=custom/);
    // A click on the chart opens the point under the pointer (the means chart: a dot at σ = 0).
    await page.selectOption('#exp-chart', 'mean');
    await page.waitForSelector('#exp-figure[data-mode="mean"]', { timeout: 10_000 });
    // Each series' dots are its marker (a path; a circle for the first).
    const dot = await page.locator('#exp-figure g[aria-label="dot"] :is(circle, path)').first().boundingBox();
    await page.mouse.move(dot.x + dot.width / 2, dot.y + dot.height / 2);
    await page.mouse.click(dot.x + dot.width / 2, dot.y + dot.height / 2);
    await page.waitForFunction(() => window.torusTest.view() === 'live', null, { timeout: 10_000 });
    assert.match(await message(page), /^Opened (MCTS|RW) at sigma = 0 from “Custom experiment”/);
    await page.evaluate(() => window.torusTest.ready());
    assert.equal((await page.evaluate(() => window.torusTest.runs()))[0].config.sigma, 0);
  });
});

test('cancelling a run leaves the page usable, and a new run starts clean', { timeout: 600_000 }, async () => {
  const cli = cliSmall();
  // A run long enough to cancel: 20000 trials per point (80000 trials, a minute or more).
  await withView(smallQuery({ trials: '20000' }), async (page) => {
    await page.click('#exp-run');
    assert.equal(await status(page), 'running');
    // The chart fills in as trials finish: the engine's statistics of the rows so far.
    await page.waitForFunction(() => /\(running: \d+ of 80000 trials so far\)$/.test(document.getElementById('exp-title').textContent), null, { timeout: 120_000, polling: 50 });
    const partial = await page.evaluate(() => window.torusTest.experiments.shown());
    assert.equal(partial.points.length, 4);
    assert.ok(partial.units.total === 80000 && partial.rows.length < 80000, `${partial.rows.length} rows so far`);
    assert.ok(partial.points.every((p) => p.n > 0), 'round-robin chunks: every point has trials early');
    await page.waitForFunction(() => document.querySelector('#exp-figure svg'), null, { timeout: 10_000 });
    await page.click('#exp-cancel');
    await page.waitForFunction(() => document.body.dataset.experiment === 'cancelled', null, { timeout: 10_000 });
    assert.match(await page.locator('#exp-status').textContent(), /^Cancelled after .*; the chart shows the \d+ trials done by then\. Nothing to save\.$/);
    assert.equal(await page.isDisabled('#exp-run'), false);
    assert.equal(await page.isDisabled('#exp-cancel'), true);
    assert.equal(await page.isDisabled('#exp-json'), true, 'a cancelled run has nothing to save');
    assert.equal(await page.evaluate(() => window.torusTest.experiments.result()), null);
    // The live view still works.
    await page.click('#tab-live');
    await page.evaluate(async () => {
      const t = window.torusTest;
      t.dispatch({ type: 'speed', speed: 'max' });
      t.dispatch({ type: 'play' });
    });
    await page.waitForFunction(() => window.torusTest.runs()[0].steps >= 3, null, { timeout: 60_000 });
    await page.evaluate(() => window.torusTest.dispatch({ type: 'pause' }));
    // A new run of the small experiment gives exactly the CLI's result.
    await page.click('#tab-experiments');
    await page.fill('#exp-trials', SMALL.trials);
    await page.locator('#exp-trials').dispatchEvent('change');
    assert.equal(await page.evaluate(() => window.torusTest.experiments.state().trials), SMALL.trials);
    assert.equal(await runAndWait(page), 'done');
    assert.equal(strip(await page.evaluate(() => window.torusTest.experiments.result())), strip(cli.json));
    assert.equal(await page.evaluate(() => document.getElementById('exp-progress').value), 12);
  });
});

test('a malformed or foreign results file gets a message and changes nothing; a CLI file loads', { timeout: 300_000 }, async () => {
  const cli = cliSmall();
  await withView(smallQuery(), async (page) => {
    assert.equal(await runAndWait(page), 'done');
    const before = await page.evaluate(() => window.torusTest.experiments.result());
    const title = await page.locator('#exp-title').textContent();
    const load = async (name, text) => {
      await page.setInputFiles('#exp-load', { name, mimeType: 'application/json', buffer: Buffer.from(text) });
      await page.waitForFunction(() => !document.getElementById('message').hidden || document.body.dataset.experiment === 'loaded', null, { timeout: 10_000 });
    };
    const foreign = JSON.parse(cli.json);
    foreign.format = 'torus-search-episode';
    const broken = JSON.parse(cli.json);
    delete broken.points;
    for (const [name, text] of [['truncated.json', cli.json.slice(0, 200)], ['episode.json', JSON.stringify(foreign)], ['points-missing.json', JSON.stringify(broken)], ['array.json', '[1, 2, 3]']]) {
      await load(name, text);
      assert.match(await message(page), new RegExp(`^${name.replace('.', '\\.')} is not a results file this page can read: .+\\. Nothing changed\\.$`), name);
      assert.equal(await page.evaluate(() => window.torusTest.experiments.result()), before, `${name} changed the result`);
      assert.equal(await page.locator('#exp-title').textContent(), title);
      assert.equal(await status(page), 'done');
      await page.evaluate(() => {
        document.getElementById('message').hidden = true;
      });
    }
    // The CLI's file (another seed) loads and is drawn.
    const other = cliSmall({ seed: '12' });
    await load('custom.json', other.json);
    assert.equal(await status(page), 'loaded');
    assert.equal(await page.evaluate(() => window.torusTest.experiments.result()), other.json);
    assert.equal(await page.locator('#exp-table tbody tr').count(), 4);
    assert.ok(await page.locator('#exp-figure svg').count() > 0);
    assert.equal(await page.evaluate(() => window.torusTest.experiments.exported('csv')), other.csv);
    assert.equal(await page.evaluate(() => window.torusTest.experiments.exported('trials-csv')), other.trials);
  });
});

test('bad URL values of the Experiments view get messages naming them; the defaults are used', { timeout: 120_000 }, async () => {
  const q = '?view=experiments&exp=no-such&trials=0&seed=-1&preset=paper-poem&n=2&bogus=1';
  await withView(q, async (page) => {
    const msg = await message(page);
    for (const key of ['exp', 'trials', 'seed', 'preset', 'n']) assert.match(msg, new RegExp(`Invalid ${key}=`), key);
    assert.match(msg, /Unknown URL parameter "bogus" ignored\./);
    const state = await page.evaluate(() => window.torusTest.experiments.state());
    const list = await page.evaluate(() => window.torusTest.engine.experimentList());
    assert.equal(state.name, list[0].name);
    assert.equal(state.seed, '1');
    assert.deepEqual(state.params, []);
    // The page works: its URL is now the valid state.
    assert.match(page.url(), new RegExp(`[?&]exp=${list[0].name}(&|$)`));
    assert.doesNotMatch(page.url(), /bogus|no-such/);
  });
  // Values that conflict only together: the engine's reason, and Run refuses to start.
  await withView('?view=experiments&exp=sigma-sweep&trials=2&sigma=3', async (page) => {
    assert.match(await message(page), /The experiment cannot run as it is: sigma is the x axis of sigma-sweep/);
    await page.click('#exp-run');
    assert.equal(await status(page), 'error');
    assert.match(await page.locator('#exp-status').textContent(), /^Not started: sigma is the x axis/);
  });
  await withView('?view=sideways', async (page) => {
    assert.match(await message(page), /Invalid view="sideways": allowed one of live, experiments\./);
    assert.equal(await page.evaluate(() => window.torusTest.view()), 'live');
  });
  // A bad edit in the form keeps the experiment as it was.
  await withView(smallQuery(), async (page) => {
    await page.fill('#exp-seed', 'abc');
    await page.locator('#exp-seed').dispatchEvent('change');
    assert.match(await message(page), /Invalid seed="abc".*The experiment was not changed\./s);
    assert.equal(await page.inputValue('#exp-seed'), SMALL.seed);
    assert.equal(await page.evaluate(() => window.torusTest.experiments.state().seed), SMALL.seed);
  });
});
