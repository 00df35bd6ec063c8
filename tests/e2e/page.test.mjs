// End-to-end tests of the web page (index.html + www/ + the wasm engine) in
// Debian's Chromium through playwright-core, using the shared harness.
// Needs `make build` first (www/pkg, www/vendor).
//
// Every test fails on console errors, failed requests and requests leaving
// the origin, except where a test provokes an error on purpose.
//
// Tests read and drive the page only through its documented test interface,
// `window.torusTest` (www/shared/test-hook.js), and through the page's own controls.
import assert from 'node:assert/strict';
import { mkdir, readFile } from 'node:fs/promises';
import path from 'node:path';
import { test } from 'node:test';
import { SHOT_DIR, canvasIsBlank, screenshot } from './harness.mjs';
import { appServer, canvasHash, expectText, mainPath, runToEnd, state, text, useApp, viewShot, waitState, withApp } from './page-helpers.mjs';

useApp();

test('the default demo autoplays, draws and reaches found with no console errors', { timeout: 180_000 }, async () => {
  await withApp('', async (page) => {
    await page.waitForFunction(() => Number(document.getElementById('steps').textContent) >= 3, null, { timeout: 60_000 });
    assert.equal(await state(page), 'running');
    assert.equal(await canvasIsBlank(page, '#view-0'), false);
    const cfg = await page.evaluate(() => window.torusTest.runs()[0].config);
    assert.equal(cfg.n, 40);
    assert.equal(cfg.prior, 'gaussian');
    assert.equal(cfg.sigma, 5);
    assert.equal(cfg.searcher, 'mcts');
    assert.equal(cfg.variant, 'cells');
    assert.equal(cfg.rollout, 'rw');
    assert.equal(cfg.loops, 100);
    assert.equal(cfg.belief, 'posterior', 'the page plans with the posterior by default');
    await page.waitForFunction(() => Number(document.getElementById('steps').textContent) >= 20, null, { timeout: 60_000 });
    await viewShot(page, 'default-demo');
    assert.equal(await runToEnd(page), 'found');
    const steps = Number((await text(page, '#steps')).replace(/,/g, ''));
    const optimal = Number(await text(page, '#optimal'));
    assert.ok(steps >= optimal && optimal > 0);
    assert.equal(await text(page, '#ratio'), (steps / optimal).toFixed(2));
    // The numbers in plain words, the bound as the engine computed it for this prior.
    const bound = await text(page, '#lower-bound');
    assert.equal(bound, '78.2');
    assert.equal(
      await text(page, '#board-0 .banner'),
      `Found in ${steps} steps. The shortest path was ${optimal} steps. Over many targets from this prior, no searcher can average fewer than ${bound} steps.`,
    );
    for (const id of ['#loops-per-s', '#fps']) assert.match(await text(page, id), /\d/);
    await screenshot(page, 'default-demo-found');
  });
});

test('a URL round-trip reproduces the same path', { timeout: 180_000 }, async () => {
  const query = '?n=24&sigma=3&loops=30&seed=4242&rv=1&start=3,20&belief=posterior&autoplay=1';
  let first;
  let search;
  await withApp(query, async (page) => {
    await runToEnd(page);
    first = await mainPath(page);
    search = await page.evaluate(() => location.search);
  });
  assert.ok(first.length > 1);
  await withApp(search, async (page) => {
    await runToEnd(page);
    assert.deepEqual(await mainPath(page), first);
  });
});

test('the decision panel survives switching between a walker and MCTS', { timeout: 120_000 }, async () => {
  await withApp('?searcher=rw&autoplay=0&n=15&seed=2', async (page) => {
    await page.click('#step-move');
    await expectText(page, '#steps', '1');
    assert.match(await text(page, '#decision-note'), /does not deliberate/);
    await page.selectOption('#searcher', 'mcts');
    await page.locator('#searcher').dispatchEvent('change');
    // Paused after a move, the change is offered as a branch: MCTS from the walker's cell.
    await waitState(page, 'choosing');
    await page.click('#branch-go');
    await waitState(page, 'paused');
    await page.evaluate(() => window.torusTest.ready());
    await expectText(page, '#steps', '1');
    await page.click('#step-loop');
    // The branch's MCTS decided move 1 too (its 100 loops, the walker's move made), then this loop.
    await expectText(page, '#rollouts', '1 / 101');
    assert.notEqual(await state(page), 'error', await text(page, '#message'));
    // Visits, picks and a bar in each row again.
    assert.equal(await page.locator('#decision tbody tr td:nth-child(2) span.bar').count(), 4);
  });
});

test('step loop and step move, by button and keyboard', { timeout: 120_000 }, async () => {
  await withApp('?autoplay=0&n=15&loops=20&seed=5', async (page) => {
    assert.equal(await state(page), 'idle');
    await page.click('#step-loop');
    assert.equal(await state(page), 'paused');
    await expectText(page, '#decision-loops', '1 / 20');
    await expectText(page, '#rollouts', '1 / 1');
    await page.locator('body').press('ArrowUp');
    await expectText(page, '#decision-loops', '2 / 20');
    await expectText(page, '#steps', '0');
    await page.click('#step-move');
    await expectText(page, '#steps', '1');
    await expectText(page, '#rollouts', '20 / 20');
    await page.locator('body').press('ArrowRight');
    await expectText(page, '#steps', '2');
    assert.equal((await mainPath(page)).length, 3);
    await page.locator('body').press(' ');
    assert.equal(await state(page), 'running');
    await page.locator('body').press(' ');
    assert.equal(await state(page), 'paused');
    await page.locator('body').press('r');
    await expectText(page, '#steps', '0');
  });
});

test('every control changes the run', { timeout: 300_000 }, async () => {
  await withApp('?autoplay=0&n=15&loops=20&seed=5&sigma=3', async (page) => {
    const fingerprint = async () => {
      // A control change restarts the run: wait for the fresh one.
      await page.evaluate(async () => {
        const t = window.torusTest;
        await t.ready();
        const live = () => ['idle', 'running', 'paused'].includes(t.state());
        for (let i = 0; i < 6 && live(); i++) await t.dispatch({ type: 'stepMove' });
      });
      return page.evaluate(() => {
        const t = window.torusTest;
        const runs = t.runs();
        if (!runs.length) throw new Error(`no runs: state ${t.state()}, message ${document.getElementById('message').textContent}`);
        return {
          // The engine configs of the runs (the seed is part of each).
          core: runs.map((r) => r.config),
          path: t.path(0),
          search: location.search,
          speed: t.speed(),
        };
      });
    };
    const base = await fingerprint();
    // The page's Restart button: fresh runs from the page's current config.
    const restartBase = async () => {
      await page.click('#reset');
      await page.evaluate(() => window.torusTest.ready());
    };
    // [control, how to set it, URL param, does the path have to change?]
    const cases = [
      ['#n', (p) => p.fill('#n', '17'), 'n=17', true],
      ['#prior', (p) => p.selectOption('#prior', 'uniform'), 'prior=uniform', true],
      ['#sigma', (p) => p.locator('#sigma').fill('6'), 'sigma=6', true],
      ['#rv', (p) => p.fill('#rv', '0'), 'rv=0', false],
      ['#start', (p) => p.fill('#start', '8,8'), 'start=8%2C8', true],
      ['#searcher', (p) => p.selectOption('#searcher', 'nsarw'), 'searcher=nsarw', true],
      ['#variant', (p) => p.selectOption('#variant', 'tree'), 'variant=tree', false],
      ['#rollout', (p) => p.selectOption('#rollout', 'greedy'), 'rollout=greedy', false],
      ['#belief', (p) => p.selectOption('#belief', 'prior'), 'belief=prior', false],
      ['#loops', (p) => p.fill('#loops', '7'), 'loops=7', false],
      ['#ms', async (p) => {
        await p.locator('#more-settings').evaluate((d) => { d.open = true; });
        await p.fill('#ms', '20');
      }, 'ms=20', false],
      ['#c', (p) => p.fill('#c', '0.5'), 'c=0.5', false],
      ['#mu', async (p) => {
        await p.selectOption('#rollout', 'levy');
        await p.locator('#rollout').dispatchEvent('change');
        await p.fill('#mu', '2.5');
      }, 'mu=2.5', false],
      ['#final', (p) => p.selectOption('#final', 'uct'), 'final=uct', false],
      ['#seed', (p) => p.fill('#seed', '6'), 'seed=6', false],
      ['#race', (p) => p.selectOption('#race', 'rw'), 'race=rw', false],
    ];
    const changedPaths = [];
    for (const [sel, set, param, mustChangePath] of cases) {
      await set(page);
      await page.locator(sel).dispatchEvent('change');
      const fp = await fingerprint();
      assert.ok(fp.search.includes(param), `${sel}: URL ${fp.search} lacks ${param}`);
      assert.notDeepEqual(fp.core, base.core, `${sel}: the engine config did not change`);
      if (mustChangePath) assert.notDeepEqual(fp.path, base.path, `${sel}: the path did not change`);
      if (JSON.stringify(fp.path) !== JSON.stringify(base.path)) changedPaths.push(sel);
      // Back to the base URL for the next control.
      await page.goto(`${appServer().url}?autoplay=0&n=15&loops=20&seed=5&sigma=3`);
      await page.waitForFunction(() => window.torusTest);
      await restartBase();
    }
    // Most controls change the first moves; all change the engine config.
    assert.ok(changedPaths.length >= 8, `only ${changedPaths.join(' ')} changed the path`);
    // New seed changes the seed and the run.
    await page.click('#new-seed');
    const fp = await fingerprint();
    assert.doesNotMatch(fp.search, /seed=5(&|$)/);
    // Speed changes the controller's work per frame and the URL.
    await page.locator('#speed').fill('16');
    await page.locator('#speed').dispatchEvent('input');
    assert.equal(await page.evaluate(() => window.torusTest.speed()), 'max');
    assert.match(await page.evaluate(() => location.search), /speed=max/);
  });
});

test('layer toggles change the drawing', { timeout: 120_000 }, async () => {
  await withApp('?autoplay=0&n=20&loops=30&seed=3', async (page) => {
    await page.click('#step-move');
    await page.click('#step-move');
    for (const id of ['layer-prior', 'layer-plan', 'layer-visits', 'layer-path', 'layer-grid', 'reveal', 'tiling', 'layer-searched', 'layer-posterior', 'layer-arrows']) {
      const before = await canvasHash(page);
      await page.click(`#${id}`);
      await page.waitForTimeout(100);
      assert.notEqual(await canvasHash(page), before, `#${id} did not change the canvas`);
    }
  });
});

test('the path is drawn incrementally, a bounded number of points per frame, and starts over for a new run', { timeout: 120_000 }, async () => {
  await withApp('?autoplay=0', async (page) => {
    const r = await page.evaluate(async () => {
      const { Renderer, PATH_POINTS_PER_FRAME } = await import('./www/live/renderer.js');
      const canvas = document.createElement('canvas');
      canvas.width = canvas.height = 400;
      document.body.append(canvas);
      const view = new Renderer(canvas);
      const n = 50; // 8 px per cell
      // Laps along one row, crossing the wrap boundary on every lap.
      const row = (y, len) => Uint32Array.from({ length: len }, (_, i) => y * n + (i % n));
      const scene = (path, len, key) => ({
        n, layers: [], path, pathLen: len, pathKey: key, start: -1, position: -1, target: -1,
        showTarget: false, rv: 0, rollouts: [], practice: -1, decision: null, grid: false, tiling: false,
      });
      const ctx = canvas.getContext('2d');
      // Brightest channel at a cell's centre: the path's line is near white, the background dark.
      const lit = (y) => Array.from({ length: n }, (_, x) => Math.max(...ctx.getImageData(x * 8 + 4, y * 8 + 4, 1, 1).data.slice(0, 3)));
      const out = {};
      // A path 2.5 frames' budget long, drawn at once: three frames.
      const long = row(10, Math.floor(2.5 * PATH_POINTS_PER_FRAME));
      out.pending = [0, 1, 2, 3].map(() => view.draw(scene(long, long.length, 'a')));
      out.row10 = lit(10);
      out.row30 = lit(30);
      // A new run, even with a longer path than the last one drawn, replaces it.
      const short = row(30, n + 10);
      view.draw(scene(short, short.length, 'b'));
      const other = row(40, 2 * n);
      out.newRunPending = view.draw(scene(other, other.length, 'c'));
      out.row10After = lit(10);
      out.row30After = lit(30);
      out.row40After = lit(40);
      // Growing a few points per frame, as the search runs, draws the same cells.
      const grow = row(20, 3 * n);
      for (let len = 2; len <= grow.length; len += 7) view.draw(scene(grow, Math.min(len, grow.length), 'd'));
      view.draw(scene(grow, grow.length, 'd'));
      out.row20 = lit(20);
      out.row40Gone = lit(40);
      canvas.remove();
      return out;
    });
    assert.deepEqual(r.pending, [true, true, false, false], 'a long path fills in over frames, then stays drawn');
    const on = (v) => v.every((c) => c > 200);
    const off = (v) => v.every((c) => c < 120);
    assert.ok(on(r.row10) && off(r.row30), `row 10 drawn, row 30 empty: ${r.row10} / ${r.row30}`);
    assert.equal(r.newRunPending, false);
    assert.ok(off(r.row10After) && off(r.row30After) && on(r.row40After), 'a new run clears the old path');
    assert.ok(on(r.row20) && off(r.row40Gone), 'a path grown frame by frame is drawn whole');
  });
});

test('export JSON then import replays the episode exactly', { timeout: 180_000 }, async () => {
  let file;
  let exported;
  await withApp('?n=20&sigma=4&loops=25&seed=77&start=2,18&belief=posterior', async (page) => {
    await runToEnd(page);
    const [download] = await Promise.all([page.waitForEvent('download'), page.click('#export-json')]);
    await mkdir(SHOT_DIR, { recursive: true });
    file = path.join(SHOT_DIR, 'exported-episode.json');
    await download.saveAs(file);
    exported = JSON.parse(await readFile(file, 'utf8'));
    assert.equal(exported.format, 'torus-search-episode');
    assert.equal(exported.version, 2);
    assert.equal(exported.episode.config.seed, '77', 'each run carries its engine config, seed included');
    assert.deepEqual(exported.episode.path, await mainPath(page));
    const [png] = await Promise.all([page.waitForEvent('download'), page.click('#export-png')]);
    assert.match(png.suggestedFilename(), /\.png$/);
  });
  // Imported while a race runs: the file's single run replaces the race.
  await withApp('?race=rw&n=33&seed=1&speed=max', async (page) => {
    await page.waitForFunction(() => window.torusTest.runs().length === 2 && window.torusTest.state() === 'running', null, { timeout: 60_000 });
    await page.setInputFiles('#import-json', file);
    await page.waitForFunction(() => document.body.dataset.replay, null, { timeout: 90_000 });
    assert.equal(await page.evaluate(() => document.body.dataset.replay), 'match');
    assert.match(await text(page, '#message'), /Replayed exactly/);
    assert.deepEqual(await mainPath(page), exported.episode.path);
    assert.match(await page.evaluate(() => location.search), /seed=77/);
    assert.equal((await page.evaluate(() => window.torusTest.runs())).length, 1, 'the race is gone');
    assert.equal(await page.locator('#board-1').isVisible(), false);
    assert.doesNotMatch(await page.evaluate(() => location.search), /race=/);
  });
});

test('a hidden (minimised) window for 30 s: no burst of frames, no long task, the episode goes on where it was', { timeout: 180_000 }, async () => {
  await withApp('?speed=10', async (page) => {
    await page.waitForFunction(() => Number(document.getElementById('steps').textContent) >= 3, null, { timeout: 60_000 });
    await page.evaluate(() => {
      window.__long = [];
      new PerformanceObserver((l) => window.__long.push(...l.getEntries().map((e) => [Math.round(e.startTime), Math.round(e.duration)]))).observe({ type: 'longtask' });
    });
    // Headless Chromium keeps a minimised window (and a background tab)
    // `visible` with animation frames running, so the test also does what a
    // browser does to a hidden tab: no animation frame while it is hidden,
    // `document.visibilityState` 'hidden' with a visibilitychange event,
    // then the held callbacks run once, 30 s later, when it is shown.
    await page.evaluate(() => {
      const raf = window.requestAnimationFrame.bind(window);
      const held = [];
      let hidden = false;
      const flip = (h) => {
        hidden = h;
        document.dispatchEvent(new Event('visibilitychange'));
        if (!h) for (const fn of held.splice(0)) raf(fn);
      };
      window.requestAnimationFrame = (fn) => (hidden ? (held.push(fn), 0) : raf(fn));
      Object.defineProperty(document, 'visibilityState', { configurable: true, get: () => (hidden ? 'hidden' : 'visible') });
      Object.defineProperty(document, 'hidden', { configurable: true, get: () => hidden });
      window.__setHidden = flip;
    });
    const cdp = await page.context().newCDPSession(page);
    const { windowId } = await cdp.send('Browser.getWindowForTarget');
    await cdp.send('Browser.setWindowBounds', { windowId, bounds: { windowState: 'minimized' } });
    await page.evaluate(() => window.__setHidden(true));
    await page.waitForTimeout(500);
    const before = await page.evaluate(() => window.torusTest.path());
    await page.evaluate(() => window.torusTest.watchFrames());
    await page.waitForTimeout(30_000);
    assert.deepEqual(await page.evaluate(() => window.torusTest.frameLog()), [], 'nothing is drawn while hidden');
    assert.deepEqual(await page.evaluate(() => window.torusTest.path()), before, 'the path shown does not move while hidden');
    await page.evaluate(() => window.torusTest.watchFrames());
    const shown = await page.evaluate(() => performance.now());
    await cdp.send('Browser.setWindowBounds', { windowId, bounds: { windowState: 'normal' } });
    await page.evaluate(() => window.__setHidden(false));
    const t0 = Date.now();
    await page.waitForTimeout(1000);
    const log = await page.evaluate(() => window.torusTest.frameLog());
    const secs = (Date.now() - t0) / 1000;
    // At most one frame per animation frame: no queue of 30 s of frames.
    assert.ok(log.length <= 75 * secs, `${log.length} frames in ${secs.toFixed(1)} s after showing the window`);
    await page.waitForFunction((n) => window.torusTest.path().length > n + 1 || window.torusTest.state() !== 'running', before.length, { timeout: 60_000 });
    const after = await page.evaluate(() => window.torusTest.path());
    assert.deepEqual(after.slice(0, before.length), before, 'the same episode goes on');
    // Tasks over 50 ms happen on these 2 shared cores (software compositing
    // competes with the search worker); what must not happen is the page
    // catching up on 30 s of work in one go when it is shown again.
    const long = (await page.evaluate(() => window.__long)).filter(([t]) => t >= shown - 50);
    console.log(`# long tasks after showing: ${JSON.stringify(long)}`);
    assert.deepEqual(long.filter(([, d]) => d > 250), [], `long tasks [start, ms] after showing: ${JSON.stringify(long)}`);
  });
});

test('100 configuration changes in 5 s while a search runs: no stale frame, no error, the last one wins', { timeout: 180_000 }, async () => {
  await withApp('?n=24&sigma=3&speed=max', async (page) => {
    await page.waitForFunction(() => window.torusTest.state() === 'running', null, { timeout: 60_000 });
    await page.evaluate(() => window.torusTest.watchFrames());
    // A new start cell each time: a frame of an older run would begin its
    // path at an older start than its run view says.
    for (let i = 0; i < 100; i++) {
      await page.evaluate((v) => {
        const el = document.getElementById('start');
        el.value = v;
        el.dispatchEvent(new Event('change'));
      }, `${(i % 24) + 1},${((7 * i) % 24) + 1}`);
      await page.waitForTimeout(50);
    }
    const last = `${(99 % 24) + 1},${((7 * 99) % 24) + 1}`;
    await page.waitForFunction((want) => {
      const r = window.torusTest.runs()[0];
      return r && r.config.start.join(',') === want && r.steps > 0;
    }, last, { timeout: 60_000 });
    const log = await page.evaluate(() => window.torusTest.frameLog());
    assert.ok(log.length > 10, `frames were drawn during the storm (${log.length})`);
    for (const f of log) {
      for (const r of f.runs) {
        assert.equal(r.path0 === -1 || r.path0 === r.start, true, `a frame's path starts at its run's start (${JSON.stringify(f)})`);
      }
    }
    assert.match(await page.evaluate(() => location.search), new RegExp(`start=${last.replace(',', '%2C')}(&|$)`));
    assert.notEqual(await state(page), 'error');
  });
});

test('preset= in the URL and the preset control set every value of a reading of the paper', { timeout: 120_000 }, async () => {
  await withApp('?preset=paper-code&autoplay=0', async (page) => {
    const cfg = await page.evaluate(() => window.torusTest.runs()[0].config);
    assert.deepEqual([cfg.variant, cfg.c, cfg.final, cfg.belief, cfg.step_cap], ['code', 2, 'uct', 'prior', 10000]);
    assert.equal(await page.locator('#preset').inputValue(), 'paper-code');
    // The bound on any searcher's mean steps for σ = 5 at N = 40 (the core's bound module).
    await expectText(page, '#lower-bound', '78.2');
    // Any other change leaves the preset; choosing one sets it again.
    await page.selectOption('#final', 'visits');
    await page.waitForFunction(() => document.getElementById('preset').value === 'custom');
    await page.selectOption('#preset', 'paper-text');
    await page.waitForFunction(() => window.torusTest.runs()[0]?.config.variant === 'cells' && window.torusTest.runs()[0].config.c === Math.SQRT2);
    assert.equal(await page.locator('#preset').inputValue(), 'paper-text');
  });
  await withApp('?preset=paper&c=3', async (page) => {
    assert.match(await text(page, '#message'), /Invalid preset="paper": allowed one of paper-text, paper-code\./);
    assert.equal(await page.evaluate(() => window.torusTest.runs()[0].config.c), 3);
  });
});

test('bad URL values show a message naming the parameter, and the page still runs', { timeout: 120_000 }, async () => {
  await withApp('?n=abc&sigma=-1&rv=x&start=99,99&searcher=foo&loops=0&c=nan&mu=5&final=z&seed=-3&speed=fast&autoplay=maybe&bogus=1', async (page) => {
    const msg = await text(page, '#message');
    for (const key of ['n', 'sigma', 'rv', 'start', 'searcher', 'loops', 'c', 'mu', 'final', 'seed', 'speed', 'autoplay']) {
      assert.match(msg, new RegExp(`Invalid ${key}=`), `no message for ${key}`);
    }
    assert.match(msg, /Invalid n="abc": allowed an integer in 3\.\.=1024\. Using the default n=40\./);
    assert.match(msg, /Unknown URL parameter "bogus" ignored\./);
    assert.equal(await page.locator('#message').isVisible(), true);
    await page.waitForFunction(() => Number(document.getElementById('steps').textContent) >= 1, null, { timeout: 60_000 });
    assert.equal(await state(page), 'running');
    assert.equal(await page.evaluate(() => window.torusTest.runs()[0].config.n), 40);
  });
});

test('script and javascript: payloads in any parameter are not executed', { timeout: 180_000 }, async () => {
  const payloads = [
    '<script>window.__pwned=1</script>',
    'javascript:window.__pwned=1',
    '"><img src=x onerror="window.__pwned=1">',
  ];
  const keys = ['n', 'prior', 'sigma', 'rv', 'start', 'searcher', 'variant', 'rollout', 'belief', 'loops', 'ms', 'c', 'mu', 'final', 'seed', 'speed', 'autoplay', 'race', 'paint', '<b>x</b>'];
  for (const p of payloads) {
    const q = new URLSearchParams(keys.map((k) => [k, p])).toString();
    await withApp(`?${q}`, async (page, report) => {
      await page.waitForTimeout(500);
      assert.equal(await page.evaluate(() => window.__pwned), undefined);
      assert.equal(await page.locator('#message img, #message script, #message b').count(), 0);
      const msg = await text(page, '#message');
      assert.ok(msg.includes(p.slice(0, 20)), 'the payload is shown as text');
      assert.notEqual(await state(page), 'error');
      assert.deepEqual(report.offOrigin, []);
      assert.deepEqual(report.failedRequests, []);
    });
  }
});

test('no request leaves the origin, and the CSP is set', { timeout: 120_000 }, async () => {
  await withApp('?race=levy&speed=max', async (page, report) => {
    await page.waitForTimeout(2000);
    assert.deepEqual(report.offOrigin, []);
    const csp = await page.locator('meta[http-equiv="Content-Security-Policy"]').getAttribute('content');
    // img-src blob: and data: are for the Experiments view's PNG export and Plot's colour ramps (see index.html).
    assert.equal(
      csp,
      "default-src 'self'; script-src 'self' 'wasm-unsafe-eval'; img-src 'self' blob: data:; object-src 'none'; base-uri 'none'; require-trusted-types-for 'script'; trusted-types torus",
    );
    // Trusted Types are enforced, and a violation reaches the harness's
    // listener (so the zero-violation check of every test can fail).
    const refused = await page.evaluate(() => {
      try {
        document.createElement('div').innerHTML = '<b>x</b>';
        return false;
      } catch (e) {
        return e instanceof TypeError;
      }
    });
    assert.equal(refused, true, 'innerHTML with a string is refused');
    await page.waitForTimeout(100);
    const violations = report.consoleErrors.filter((e) => e.startsWith('CSP violation: require-trusted-types-for'));
    assert.equal(violations.length, 1, report.consoleErrors.join('\n'));
    report.consoleErrors.splice(0, report.consoleErrors.length, ...report.consoleErrors.filter((e) => !e.includes('TrustedHTML') && !e.startsWith('CSP violation')));
    assert.equal(await page.locator('script:not([src])').count(), 0, 'no inline scripts');
    assert.equal(await page.locator('[onclick], [onload], [onerror], [onchange], [oninput]').count(), 0, 'no inline handlers');
    const origins = await page.evaluate(() => performance.getEntriesByType('resource').map((e) => new URL(e.name).origin));
    for (const o of origins) assert.equal(o, appServer().origin);
  });
});

/**
 * After the engine trapped: the board still shows the last frame, and
 * Restart gets a fresh worker (the trapped instance is dropped) that
 * searches again.
 */
