// End-to-end tests of provenance and exports in Debian's Chromium: the
// footer names the engine's build; every committed result
// (docs/figures/*.json, or $FIGURES_DIR/*.json) loads in the Experiments
// view; chart exports hold the whole legend (every series, inside the
// image) and a caption with the build, date, page URL and spec; episode
// files and board PNGs carry their provenance.
// Needs `make build` first (www/pkg, www/vendor).
import assert from 'node:assert/strict';
import { existsSync, readdirSync, readFileSync } from 'node:fs';
import path from 'node:path';
import { after, before, test } from 'node:test';
import { ROOT, describeProblems, launchBrowser, openPage, screenshot, startServer } from './harness.mjs';

let server;
let browser;

before(async () => {
  assert.ok(existsSync(path.join(ROOT, 'www', 'pkg', 'torus_search.js')), 'www/pkg is missing: run `make build` first');
  server = await startServer(ROOT);
  browser = await launchBrowser({ viewport: { width: 1280, height: 900 } });
});

after(async () => {
  await browser?.close();
  await server?.close();
});

const DATE = /^\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ$/;

async function withPage(query, fn) {
  const { page, report } = await openPage(browser.context, `${server.url}${query}`);
  try {
    await page.waitForFunction(() => window.torusTest && window.torusTest.runs().length, null, { timeout: 30_000 });
    await fn(page);
    assert.equal(describeProblems(report), '', 'the page reported problems');
  } finally {
    await page.close();
  }
}

/** The provenance of the page's engine, as its footer and exports name it. */
const build = (page) => page.evaluate(async () => (await import('./www/shared/provenance.js')).currentBuild());

test('the footer names the build; every committed result loads', { timeout: 600_000 }, async () => {
  const dir = process.env.FIGURES_DIR || path.join(ROOT, 'docs', 'figures');
  const files = readdirSync(dir).filter((f) => f.endsWith('.json')).sort();
  assert.ok(files.length > 0, `no results in ${dir}`);
  await withPage('?view=experiments', async (page) => {
    const b = await build(page);
    assert.match(b.commit, /^([0-9a-f]{40}|unknown)$/);
    const footer = await page.locator('#build-info').textContent();
    assert.equal(footer, `Engine: ${b.label}.`);
    assert.ok(footer.includes(b.commit === 'unknown' ? 'commit unknown' : b.commit.slice(0, 12)), footer);
    const refused = [];
    for (const f of files) {
      const text = readFileSync(path.join(dir, f), 'utf8');
      const loaded = await page.evaluate(([t, n]) => window.torusTest.experiments.load(t, n), [text, f]);
      if (!loaded) refused.push(`${f}: ${await page.locator('#message').textContent()}`);
      else assert.equal(await page.evaluate(() => document.body.dataset.experiment), 'loaded', f);
      await page.evaluate(() => {
        document.getElementById('message').hidden = true;
      });
    }
    assert.deepEqual(refused, [], `committed results the page cannot load (regenerate with \`make figures\`):\n${refused.join('\n')}`);
  });
});

/** Ten searchers with long names, one trial each on a small torus: a legend of ten. */
const TEN = [
  'MCTS, RW rollouts:searcher=mcts', 'MCTS, Lévy rollouts:searcher=mcts rollout=levy', 'Random walk:searcher=rw', 'Lévy flight:searcher=levy',
  'NSARW:searcher=nsarw', 'Sweep:searcher=sweep', 'Receding horizon:searcher=horizon', 'Rollout improvement:searcher=improve',
  'Beam planner:searcher=beam', 'Spiral planner:searcher=spiral',
];

function tenQuery() {
  const q = new URLSearchParams([['view', 'experiments'], ['exp', 'custom'], ['trials', '2'], ['seed', '3'], ['preset', 'none'], ['n', '10'], ['loops', '10'], ['step_cap', '200']]);
  q.set('sweep', 'sigma:1 3');
  for (const s of TEN) q.append('series', s);
  return `?${q}`;
}

/**
 * Renders SVG text alone in a blank page (no CSP), screenshots it as
 * `shotName`, and returns its width, each top-level text with its right
 * edge, and its <metadata>.
 */
async function inspectSvg(svgText, shotName) {
  const page = await browser.context.newPage();
  try {
    await page.setContent(`<body style="margin:0;background:#fff">${svgText}</body>`);
    await screenshot(page, shotName);
    return await page.evaluate(() => {
      const svg = document.querySelector('body > svg');
      const width = Number(svg.getAttribute('width'));
      const texts = [...svg.querySelectorAll(':scope > text')].map((el) => {
        const b = el.getBBox();
        return { text: el.textContent, right: b.x + b.width };
      });
      return { width, texts, metadata: svg.querySelector('metadata')?.textContent ?? null };
    });
  } finally {
    await page.close();
  }
}

test('chart exports hold every series of the legend and a caption with the provenance', { timeout: 600_000 }, async () => {
  await withPage(tenQuery(), async (page) => {
    assert.equal(await page.locator('#message').isHidden(), true, 'the URL is valid');
    await page.click('#exp-run');
    await page.waitForFunction(() => ['done', 'error'].includes(document.body.dataset.experiment), null, { timeout: 300_000, polling: 200 });
    assert.equal(await page.evaluate(() => document.body.dataset.experiment), 'done', await page.locator('#exp-status').textContent());
    const b = await build(page);
    for (const mode of ['box', 'mean']) {
      await page.selectOption('#exp-chart', mode);
      await page.waitForSelector(`#exp-figure[data-mode="${mode}"] svg`, { timeout: 10_000 });
      const svg = await page.evaluate(() => window.torusTest.experiments.exported('svg'));
      const { width, texts, metadata } = await inspectSvg(svg, `export-${mode}-ten-series`);
      const labels = texts.map((t) => t.text);
      for (const s of TEN) assert.ok(labels.includes(s.split(':')[0]), `${mode}: the legend names ${s.split(':')[0]}`);
      const outside = texts.filter((t) => t.right > width + 0.5);
      assert.deepEqual(outside, [], `${mode}: text beyond the right edge (${width})`);
      const caption = labels.join('\n');
      assert.match(caption, /custom · .* · 2 trials per point · seed 3 · preset none/);
      assert.ok(caption.includes(`exported: torus-search ${b.version}, commit`), caption);
      assert.match(caption, /page: http:\/\/127\.0\.0\.1:\d+\/\?view=experiments/);
      assert.ok(caption.includes('spec: {"name":"custom","trials":2,'), caption);
      const meta = JSON.parse(metadata);
      assert.equal(meta.export.commit, b.commit);
      assert.match(meta.export.date, DATE);
      assert.equal(meta.results.commit, b.commit, 'the results were made by this page');
      assert.equal(meta.spec.name, 'custom');
      assert.ok((await page.evaluate(() => window.torusTest.experiments.exported('png'))) > 5000, 'a PNG of the chart');
    }
  });
});

/** Width and height from a PNG's IHDR. */
function pngSize(bytes) {
  return { width: bytes.readUInt32BE(16), height: bytes.readUInt32BE(20) };
}

test('episode files and board PNGs carry their provenance', { timeout: 300_000 }, async () => {
  await withPage('?n=12&seed=5&speed=max', async (page) => {
    await page.evaluate(() => window.torusTest.dispatch({ type: 'play' }));
    await page.waitForFunction(() => ['found', 'capped'].includes(document.body.dataset.state), null, { timeout: 90_000 });
    const b = await build(page);
    const [json] = await Promise.all([page.waitForEvent('download'), page.click('#export-json')]);
    const file = JSON.parse(readFileSync(await json.path(), 'utf8'));
    assert.deepEqual(Object.keys(file.provenance), ['version', 'commit', 'dirty', 'date', 'command']);
    assert.equal(file.provenance.commit, b.commit);
    assert.equal(file.provenance.version, file.engine);
    assert.match(file.provenance.date, DATE);
    assert.ok(file.provenance.command.includes('seed=5'), file.provenance.command);
    const [png] = await Promise.all([page.waitForEvent('download'), page.click('#export-png')]);
    const size = pngSize(readFileSync(await png.path()));
    const board = await page.evaluate(() => document.getElementById('view-0').height);
    assert.ok(size.height >= board + 28, `a caption under the boards: ${size.height} vs ${board}`);
  });
});
