// The first ten seconds (issue 43): at two laptops, a wide screen and two
// phones, the board, the playback bar and the legend are all in view at
// load, with a message, with a panel open and at the found moment; touch
// targets are big enough; the keys are on the page; the first-visit tour
// points at what it names and is remembered; one heat layer at a time, a
// uniform prior drawn dim, and the searcher visible at any N.
// Screenshots: target/e2e/screen-<device>[-message|-found].png.
import assert from 'node:assert/strict';
import { mkdir } from 'node:fs/promises';
import path from 'node:path';
import { test } from 'node:test';
import { SHOT_DIR } from './harness.mjs';
import { VIEWPORTS } from './www-shots.mjs';
import { assertInView, runToEnd, setParam, state, useServer, withDevice } from './screen-helpers.mjs';

useServer();

const ON_SCREEN = ['#view-0', '.playback', '#legend'];

async function shot(page, name) {
  await mkdir(SHOT_DIR, { recursive: true });
  await page.screenshot({ path: path.join(SHOT_DIR, `screen-${name}.png`) });
}

/** Interactive elements of the header and the board's column smaller than 44 × 44 CSS px. */
const smallTargets = (page) =>
  page.evaluate(() => {
    const out = [];
    for (const el of document.querySelectorAll('.top button, .stage button, .stage .chip, .stage input[type="range"]')) {
      const r = el.getBoundingClientRect();
      if (r.width === 0 || el.closest('[hidden]')) continue;
      if (r.height < 43.5 || r.width < 43.5) out.push(`${el.id || el.className || el.tagName} ${Math.round(r.width)}×${Math.round(r.height)}`);
    }
    return out;
  });

for (const device of Object.keys(VIEWPORTS)) {
  test(`${device}: the board, the playback bar and the legend are in view at load, with a message, with a panel open and at the end`, { timeout: 240_000 }, async () => {
    await withDevice(device, '?seed=3', async (page) => {
      await page.waitForFunction(() => window.torusTest.runs()[0].steps >= 2, null, { timeout: 60_000 });
      await assertInView(page, ON_SCREEN, `${device} at load`);
      await shot(page, device);
      // A bad value: the message shows (beside the board, or over the top of a phone's page).
      await setParam(page, 'n', '2');
      await page.waitForFunction(() => /Invalid n/.test(document.getElementById('message').textContent));
      assert.ok(await page.locator('#message').isVisible());
      await assertInView(page, ON_SCREEN, `${device} with a message`);
      await shot(page, `${device}-message`);
      // A panel opens: the configuration's "More settings".
      await page.locator('#more-settings').evaluate((d) => { d.open = true; });
      await assertInView(page, ON_SCREEN, `${device} with a panel open`);
      await page.click('#message-close');
      assert.equal(await page.locator('#message').isVisible(), false, 'the message can be closed');
      await runToEnd(page);
      await page.waitForFunction(() => !document.getElementById('next-steps').hidden);
      await assertInView(page, [...ON_SCREEN, '#next-steps'], `${device} at the end`);
      await shot(page, `${device}-found`);
      if (VIEWPORTS[device].hasTouch) assert.deepEqual(await smallTargets(page), [], 'touch targets of at least 44 px');
      assert.equal(await page.evaluate(() => scrollY), 0, 'nothing scrolled the page');
    });
  });
}

test('the keys are shown on the page, and the speed slider says its value in words', { timeout: 60_000 }, async () => {
  await withDevice('1366x768', '?seed=3&autoplay=0', async (page) => {
    const keys = await page.locator('.keys').innerText();
    for (const k of ['space', 'restart', 'new target', 'Shift', 'one phase', 'back a move', 'Home']) assert.ok(keys.includes(k), `keys name ${k}: ${keys}`);
    assert.ok(await page.locator('.keys').isVisible());
    assert.equal(await page.getAttribute('#speed', 'aria-valuetext'), '10 loops/frame');
    await page.locator('#speed').fill('3');
    await page.locator('#speed').dispatchEvent('input');
    assert.equal(await page.getAttribute('#speed', 'aria-valuetext'), '1 loop/frame');
    // Slower still: a phase at a time.
    await page.locator('#speed').fill('0');
    await page.locator('#speed').dispatchEvent('input');
    assert.equal(await page.getAttribute('#speed', 'aria-valuetext'), 'one phase every 2 s');
  });
});

test('the first-visit tour: five steps, each ringing what it names, then dismissed and remembered', { timeout: 180_000 }, async () => {
  await withDevice('1366x768', '?seed=3', async (page) => {
    await page.waitForSelector('#tour:not([hidden])', { timeout: 30_000 });
    assert.equal(await state(page), 'paused', 'the run waits while the tour is open');
    const anchors = [null, '#heat-switch', '#legend [data-mark="rollout"]', null, '.playback'];
    for (let i = 0; i < anchors.length; i++) {
      assert.equal(await page.locator('#tour-count').textContent(), `${i + 1} of 5`);
      const { spot, target, card } = await page.evaluate((sel) => {
        const rect = (el) => el.getBoundingClientRect().toJSON();
        let target;
        if (sel) target = rect(document.querySelector(sel));
        else {
          // The searcher: its drawn point on the board (the test hook's run and the board's geometry).
          const c = document.getElementById('view-0').getBoundingClientRect();
          const r = window.torusTest.runs()[0];
          const pos = window.torusTest.path().at(-1);
          const cell = c.width / r.n;
          const [x, y] = [c.left + ((pos % r.n) + 0.5) * cell, c.top + (Math.floor(pos / r.n) + 0.5) * cell];
          target = { left: x - 1, right: x + 1, top: y - 1, bottom: y + 1 };
        }
        return { spot: rect(document.getElementById('tour-spot')), target, card: rect(document.getElementById('tour')) };
      }, anchors[i]);
      const inside = (a, b) => a.left >= b.left - 1 && a.right <= b.right + 1 && a.top >= b.top - 1 && a.bottom <= b.bottom + 1;
      assert.ok(inside(target, spot), `step ${i + 1}: the ring ${JSON.stringify(spot)} goes round ${JSON.stringify(target)}`);
      const overlap = !(card.right <= spot.left || card.left >= spot.right || card.bottom <= spot.top || card.top >= spot.bottom);
      assert.ok(!overlap, `step ${i + 1}: the card does not hide what it names`);
      await page.click('#tour-next');
    }
    assert.ok(await page.locator('#tour').isHidden(), 'Done closes it');
    assert.equal(await state(page), 'running', 'the run goes on after the tour');
    await page.reload();
    // Six steps, or whatever stops them (the tour back, the run not playing), said on a failure.
    const seen = () => page.evaluate(() => ({ state: document.body.dataset.state, steps: window.torusTest?.runs()[0]?.steps, tour: !document.getElementById('tour')?.hidden }));
    await page
      .waitForFunction(() => window.torusTest?.runs()[0]?.steps >= 6 || !document.getElementById('tour')?.hidden, null, { timeout: 90_000 })
      .catch(async (e) => assert.fail(`after the reload ${JSON.stringify(await seen())}: ${e.message}`));
    assert.ok(await page.locator('#tour').isHidden(), `a second visit has no tour (${JSON.stringify(await seen())})`);
    await page.click('#tour-open');
    assert.ok(await page.locator('#tour').isVisible(), 'the Tour button opens it again');
    await page.keyboard.press('Escape');
    assert.ok(await page.locator('#tour').isHidden(), 'Esc closes it');
  }, { firstVisit: true });
});

test('one heat layer at a time: a chip switches it, the scale starts at 0, the hatch is not a second ramp', { timeout: 120_000 }, async () => {
  await withDevice('1366x768', '?seed=3&autoplay=0', async (page) => {
    await page.evaluate(() => window.torusTest.dispatch({ type: 'stepMove' }));
    const drawn = () => page.evaluate(() => window.torusTest.drawn().layers);
    await page.waitForFunction(() => window.torusTest.drawn().layers.length === 1);
    assert.deepEqual(await drawn(), ['prior'], 'the prior alone by default');
    await page.click('#layer-visits');
    await page.waitForFunction(() => window.torusTest.drawn().layers.join() === 'visits');
    assert.equal(await page.isChecked('#layer-prior'), false, 'one click switched it');
    assert.deepEqual(await page.evaluate(() => window.torusTest.legend().layers), ['visits']);
    assert.equal(await page.locator('#legend .heat .ticks span').first().textContent(), '0');
    await page.check('#layer-searched');
    await page.waitForFunction(() => window.torusTest.drawn().layers.join() === 'visits,searched');
    assert.ok((await page.evaluate(() => window.torusTest.drawn().marks)).includes('searched'), 'the searched cells are a hatch (a mark), not a ramp');
    await page.click('#layer-visits');
    await page.waitForFunction(() => window.torusTest.drawn().layers.join() === 'searched');
    assert.ok(await page.locator('#legend .heat').isHidden());
  });
});

/** The share of the board's pixels brighter than `level` (0–255, max channel), and the mean of that channel. */
const brightness = (page, level) =>
  page.evaluate((lv) => {
    const c = document.getElementById('view-0');
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let bright = 0;
    let sum = 0;
    for (let i = 0; i < d.length; i += 4) {
      const m = Math.max(d[i], d[i + 1], d[i + 2]);
      sum += m;
      if (m > lv) bright++;
    }
    return { share: bright / (d.length / 4), mean: sum / (d.length / 4) };
  }, level);

for (const n of [256, 1024]) {
  test(`N = ${n}, uniform prior: the board is not washed out, and the searcher and its path stay visible`, { timeout: 120_000 }, async () => {
    await withDevice('1366x768', `?seed=3&n=${n}&prior=uniform&autoplay=0&start=${n / 2},${n / 2}`, async (page) => {
      for (let i = 0; i < 12; i++) await page.evaluate(() => window.torusTest.dispatch({ type: 'stepMove' }));
      await page.waitForTimeout(400);
      assert.match(await page.locator('#legend .heat .note').textContent(), /uniform/, 'the legend says why it is dim');
      const { mean } = await brightness(page, 200);
      // Drawn at full strength the uniform prior is the palette's top colour, about 250 of 255.
      assert.ok(mean < 140, `the board's mean brightness ${mean.toFixed(0)} of 255`);
      // The searcher: at least a disc of 5 CSS px radius of near-white around its point.
      const white = await page.evaluate(() => {
        const c = document.getElementById('view-0');
        const r = window.torusTest.runs()[0];
        const pos = window.torusTest.path().at(-1);
        const k = c.width / r.n;
        const [x, y] = [((pos % r.n) + 0.5) * k, (Math.floor(pos / r.n) + 0.5) * k];
        const dpr = c.width / c.getBoundingClientRect().width;
        const half = Math.round(12 * dpr);
        const d = c.getContext('2d').getImageData(Math.round(x) - half, Math.round(y) - half, 2 * half, 2 * half).data;
        let n = 0;
        for (let i = 0; i < d.length; i += 4) if (d[i] > 235 && d[i + 1] > 235 && d[i + 2] > 235) n++;
        return n / (dpr * dpr);
      });
      assert.ok(white >= Math.PI * 4 * 4, `${white.toFixed(0)} CSS px² of white at the searcher`);
      assert.ok((await page.evaluate(() => window.torusTest.drawn().marks)).includes('path'));
    });
  });
}
