// Input that never destroys a run, motion, accessibility and the legend
// (issue 43): a click or a tap on the board only inspects it, a swipe
// scrolls; the start moves only in an explicit mode; an edit while paused
// stays paused; reduced motion means no autoplay and nothing drawn while
// idle; every mark drawn has a legend entry; a long rollout on a torus
// draws no line across the board.
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { runToEnd, setParam, state, useServer, withDevice } from './screen-helpers.mjs';

useServer();

/** What a click must not change: the runs (reset count), the start, the URL, the state. */
const snapshot = (page) =>
  page.evaluate(() => ({ resets: window.torusTest.resets(), start: window.torusTest.runs()[0].start, search: location.search, state: window.torusTest.state() }));

async function boardCentre(page) {
  const b = await page.locator('#view-0').boundingBox();
  return [b.x + b.width * 0.33, b.y + b.height * 0.43];
}

test('a click on the board neither starts the run nor moves its start: it inspects the cell; the start moves only in an explicit mode', { timeout: 120_000 }, async () => {
  await withDevice('1366x768', '?seed=3&autoplay=0&n=20', async (page) => {
    const before = await snapshot(page);
    assert.equal(before.state, 'idle');
    await page.mouse.click(...(await boardCentre(page)));
    await page.waitForTimeout(300);
    assert.deepEqual(await snapshot(page), before, 'the click changed nothing of the run');
    assert.match(await page.locator('#inspect').textContent(), /^\(7, 9\): not walked yet$/);
    assert.ok((await page.evaluate(() => window.torusTest.drawn().marks)).includes('selected'));
    // While it runs, a click does not restart it either.
    await page.click('#play');
    await page.waitForFunction(() => window.torusTest.runs()[0].steps >= 2, null, { timeout: 60_000 });
    const running = await snapshot(page);
    await page.mouse.click(...(await boardCentre(page)));
    await page.waitForTimeout(300);
    assert.deepEqual(await snapshot(page), running);
    // Explicit: Shift+click sets the start there; "Pick on grid" sets it once, then the mode ends.
    await page.keyboard.down('Shift');
    await page.mouse.click(...(await boardCentre(page)));
    await page.keyboard.up('Shift');
    await page.waitForFunction(() => window.torusTest.runs()[0]?.config.start.join(',') === '7,9', null, { timeout: 30_000 }).catch(async (e) => {
      throw new Error(`${e.message}: ${JSON.stringify(await page.evaluate(() => [location.search, window.torusTest.state(), window.torusTest.runs()[0]?.config.start, document.getElementById('inspect').textContent]))}`);
    });
    await page.click('#start-pick');
    const b = await page.locator('#view-0').boundingBox();
    await page.mouse.click(b.x + b.width * 0.02, b.y + b.height * 0.02);
    await page.waitForFunction(() => window.torusTest.runs()[0]?.config.start.join(',') === '1,1', null, { timeout: 30_000 });
    assert.equal(await page.getAttribute('#start-pick', 'aria-pressed'), 'false', 'the pick mode ends after one cell');
    const after = await snapshot(page);
    await page.mouse.click(...(await boardCentre(page)));
    await page.waitForTimeout(300);
    assert.equal((await snapshot(page)).resets, after.resets, 'the next click inspects again');
  });
});

test('on a phone a tap on the board inspects it, and a swipe on the board scrolls the page', { timeout: 120_000 }, async () => {
  await withDevice('iphone13', '?seed=3&autoplay=0', async (page) => {
    const before = await snapshot(page);
    await page.touchscreen.tap(...(await boardCentre(page)));
    await page.waitForTimeout(300);
    assert.deepEqual(await snapshot(page), before, 'the tap changed nothing of the run');
    assert.match(await page.locator('#inspect').textContent(), /^\(\d+, \d+\): /);
    const cdp = await page.context().newCDPSession(page);
    // A finger put down on the board and moved up 300 px (touch events, as a phone sends them).
    const swipe = async () => {
      const [x, y0] = (await boardCentre(page)).map(Math.round);
      await cdp.send('Input.dispatchTouchEvent', { type: 'touchStart', touchPoints: [{ x, y: y0 }] });
      for (let k = 1; k <= 10; k++) {
        await cdp.send('Input.dispatchTouchEvent', { type: 'touchMove', touchPoints: [{ x, y: y0 - 30 * k }] });
        await page.waitForTimeout(16);
      }
      await cdp.send('Input.dispatchTouchEvent', { type: 'touchEnd', touchPoints: [] });
      await page.waitForTimeout(400);
      return page.evaluate(() => scrollY);
    };
    assert.ok((await swipe()) > 100, 'the swipe scrolled the page');
    assert.deepEqual(await snapshot(page), before, 'the swipe changed nothing of the run');
    // In the explicit pick mode the board takes the finger: the same swipe does not scroll.
    await page.click('#start-pick');
    await page.evaluate(() => scrollTo(0, 0));
    assert.equal(await swipe(), 0, 'picking a cell, the board keeps the swipe');
    assert.deepEqual(await snapshot(page), before, 'a swipe is not a pick');
  });
});

test('an edit while paused leaves the run paused (Restart: at move 0, with the same seed)', { timeout: 120_000 }, async () => {
  await withDevice('1366x768', '?seed=77&speed=10', async (page) => {
    await page.waitForFunction(() => window.torusTest.runs()[0].steps >= 3, null, { timeout: 60_000 });
    await page.click('#play');
    assert.equal(await state(page), 'paused');
    const resets = await page.evaluate(() => window.torusTest.resets());
    await setParam(page, 'loops', '30');
    // Paused after move 0, the edit waits for a choice (tests/e2e/branch.test.mjs has the branch).
    await page.waitForFunction(() => window.torusTest.state() === 'choosing', null, { timeout: 10_000 });
    assert.equal(await page.evaluate(() => window.torusTest.resets()), resets);
    await page.click('#branch-restart');
    await page.waitForFunction((r) => window.torusTest.resets() > r, resets);
    await page.evaluate(() => window.torusTest.ready());
    await page.waitForTimeout(500);
    const r = (await page.evaluate(() => window.torusTest.runs()))[0];
    assert.equal(await state(page), 'paused');
    assert.equal(await page.locator('#play').textContent(), 'Play');
    assert.deepEqual([r.config.loops, r.config.seed, r.steps, r.pathLen], [30, '77', 0, 1]);
    // Restart while paused also waits.
    await page.evaluate(() => window.torusTest.dispatch({ type: 'stepMove' }));
    await page.click('#reset');
    await page.evaluate(() => window.torusTest.ready());
    assert.equal(await state(page), 'paused');
  });
});

test('reduced motion: no autoplay, no frame drawn while idle, no glide; the board is described and the end announced', { timeout: 180_000 }, async () => {
  // The searcher's drawn points over the second of two steps: between cells while it glides.
  const afterStep = async (page) => {
    await page.evaluate(() => window.torusTest.dispatch({ type: 'stepMove' }));
    await page.evaluate(() => window.torusTest.watchFrames());
    await page.evaluate(() => window.torusTest.dispatch({ type: 'stepMove' }));
    await page.waitForTimeout(1000);
    const log = await page.evaluate(() => window.torusTest.frameLog());
    const between = log.filter((f) => f.at && f.at.some((v) => Math.abs((v % 1) - 0.5) > 0.01)).length;
    return { frames: log.length, between };
  };
  let moving;
  await withDevice('1366x768', '?seed=3', async (page) => {
    await page.waitForFunction(() => window.torusTest.runs()[0].steps >= 1, null, { timeout: 60_000 });
    await page.click('#play');
    moving = await afterStep(page);
  });
  await withDevice('1366x768', '?seed=3', async (page) => {
    await page.evaluate(() => window.torusTest.ready());
    await page.waitForTimeout(1500);
    assert.equal(await state(page), 'idle', 'no autoplay');
    assert.equal(await page.locator('#play').textContent(), 'Play');
    await page.evaluate(() => window.torusTest.watchFrames());
    await page.waitForTimeout(2000);
    assert.deepEqual(await page.evaluate(() => window.torusTest.frameLog()), [], 'no animation frame drawn while idle');
    const still = await afterStep(page);
    assert.ok(moving.between >= 1, `the searcher glides between cells without reduced motion (${JSON.stringify(moving)})`);
    // Each step draws a frame, and a busy machine may add one or two while a layer
    // finishes in slices; a glide or a fading trail would draw one per display frame
    // for 60–400 ms.
    assert.ok(still.between === 0 && still.frames <= 6, `with reduced motion it jumps, in at most 6 frames (${JSON.stringify(still)})`);
    assert.equal(await page.getAttribute('#view-0', 'role'), 'img');
    const described = await page.getAttribute('#view-0', 'aria-describedby');
    assert.match(await page.locator(`#${described}`).textContent(), /^Searcher at \(\d+, \d+\) after 2 steps; \d+\.\d% of the prior searched\.$/);
    await runToEnd(page);
    await page.waitForFunction(() => /^Found in/.test(document.getElementById('announce').textContent), null, { timeout: 10_000 });
    assert.equal(await page.getAttribute('#announce', 'role'), 'status');
  }, { reducedMotion: 'reduce' });
});

/** Plays `query` for a while, then pauses: every mark drawn meanwhile, and what the legend names. */
async function marksAndLegend(page, act) {
  await page.evaluate(() => window.torusTest.watchFrames());
  await act();
  const drawn = new Set((await page.evaluate(() => window.torusTest.frameLog())).flatMap((f) => f.marks));
  await page.evaluate(() => window.torusTest.dispatch({ type: 'pause' }));
  await page.waitForTimeout(300);
  for (const m of await page.evaluate(() => window.torusTest.drawn().marks)) drawn.add(m);
  return { drawn, legend: await page.evaluate(() => window.torusTest.legend()), layers: await page.evaluate(() => window.torusTest.drawn().layers) };
}

test('every mark drawn has a legend entry, and every heat layer drawn its scale', { timeout: 240_000 }, async () => {
  const seen = new Set();
  const check = ({ drawn, legend, layers }, where) => {
    for (const m of drawn) {
      assert.ok(legend.marks.includes(m), `${where}: ${m} is drawn but the legend lacks it (${legend.marks})`);
      seen.add(m);
    }
    for (const l of layers.filter((x) => x !== 'searched')) assert.ok(legend.layers.includes(l), `${where}: layer ${l} drawn, not in the legend`);
  };
  await withDevice('1366x768', '?n=11&sigma=2&loops=40&seed=3&start=2,2&keep_traces=3&speed=1&rv=2', async (page) => {
    await page.check('#layer-searched');
    check(await marksAndLegend(page, () => page.waitForTimeout(2500)), 'teaching-like run');
    await page.mouse.click(...(await boardCentre(page)));
    await page.check('#reveal');
    check(await marksAndLegend(page, () => page.waitForTimeout(300)), 'a selected cell, the target revealed');
  });
  await withDevice('1366x768', '?searcher=horizon&n=20&sigma=3&speed=1', async (page) => {
    check(await marksAndLegend(page, () => page.waitForFunction(() => window.torusTest.runs()[0].steps >= 3, null, { timeout: 60_000 })), 'a planner');
  });
  await withDevice('1366x768', '?seed=3&n=16&sigma=2', async (page) => {
    check(await marksAndLegend(page, () => runToEnd(page)), 'found');
  });
  const all = ['searcher', 'path', 'start', 'target', 'practice', 'rollout', 'planned', 'arrows', 'vision', 'searched', 'selected'];
  assert.deepEqual(all.filter((m) => !seen.has(m)), [], 'the scenes drew every kind of mark');
});

test('a long rollout and a long path on a torus draw no line across the board, and the searcher shows at both edges mid-wrap', { timeout: 60_000 }, async () => {
  await withDevice('1366x768', '?autoplay=0', async (page) => {
    const r = await page.evaluate(async () => {
      const { Renderer } = await import('./www/live/renderer.js');
      const { decimate, MAX_TRAIL_POINTS } = await import('./www/live/trails.js');
      const canvas = document.createElement('canvas');
      canvas.width = canvas.height = 400;
      document.body.append(canvas);
      const view = new Renderer(canvas);
      const n = 40; // 10 px a cell
      // A walk of 30 000 steps in a band of six columns round the wrap (x in 37..39, 0..2)
      // and rows 10..15: it crosses the wrap thousands of times, so it is decimated.
      let s = 7;
      let [x, y] = [0, 12];
      const cells = [];
      for (let i = 0; i < 30_000; i++) {
        s = (s * 1103515245 + 12345) % 2 ** 31;
        const [dx, dy] = [[0, -1], [1, 0], [0, 1], [-1, 0]][(s >> 8) % 4];
        const nx = (x + dx + n) % n;
        const ny = y + dy;
        if ((nx <= 2 || nx >= 37) && ny >= 10 && ny <= 15) [x, y] = [nx, ny];
        cells.push(y * n + x);
      }
      const walk = Uint32Array.from(cells);
      const trail = decimate(walk);
      const scene = (extra) => ({ n, layers: [], path: null, pathLen: 0, pathKey: 'w', start: -1, position: -1, target: -1, showTarget: false, rv: 0, trails: [], practice: -1, decision: null, selected: -1, grid: false, tiling: false, ...extra });
      const ctx = canvas.getContext('2d');
      // Lit pixels (brighter than the background) per column.
      const litColumns = () => {
        const d = ctx.getImageData(0, 0, 400, 400).data;
        const cols = new Array(400).fill(0);
        for (let i = 0; i < d.length; i += 4) if (Math.max(d[i], d[i + 1], d[i + 2]) > 60) cols[(i / 4) % 400]++;
        return cols;
      };
      view.draw(scene({ trails: [{ cells: trail, alpha: 1 }] }));
      const trailCols = litColumns();
      view.draw(scene({ path: walk, pathLen: walk.length }));
      view.draw(scene({ path: walk, pathLen: walk.length }));
      const pathCols = litColumns();
      // The searcher half way across the wrap between (39, 20) and (0, 20).
      view.draw(scene({ position: 20 * n, at: [40, 20.5] }));
      const d = ctx.getImageData(0, 200, 400, 10).data;
      const white = (px) => d[4 * (5 * 400 + px)] > 200;
      canvas.remove();
      return { decimated: trail.length, max: MAX_TRAIL_POINTS, trailCols, pathCols, leftEdge: white(1), rightEdge: white(398), middle: white(200) };
    });
    assert.ok(r.decimated <= r.max + 1 && r.decimated > r.max / 2, `the 30 000-step rollout was decimated to ${r.decimated} points`);
    for (const [name, cols] of [['rollout', r.trailCols], ['path', r.pathCols]]) {
      // Cells 3..36 (pixels 30..370) are never entered; lines may reach a few pixels past the band (line caps, end marks).
      const across = cols.slice(45, 355).reduce((a, b) => a + b, 0);
      assert.equal(across, 0, `the ${name} drew ${across} pixels across the board`);
      assert.ok(cols.slice(0, 30).reduce((a, b) => a + b, 0) > 100 && cols.slice(370).reduce((a, b) => a + b, 0) > 100, `the ${name} is drawn at both edges`);
    }
    assert.deepEqual([r.leftEdge, r.rightEdge, r.middle], [true, true, false], 'mid-wrap the searcher shows at both edges');
  });
});
