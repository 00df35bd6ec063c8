// Screenshots of the live view, to look at after a change to the page: the
// viewport (what a visitor sees without scrolling) at two laptops, a wide
// screen and two phones, into target/e2e/<prefix>-<size>.png.
// Not a test: `node tests/e2e/www-shots.mjs [--prefix www] [--query '?seed=3']
//   [--sizes 1366x768,phone] [--vision deuteranopia] [--found] [--first-visit] [--moves 12]
//   [--loops 20 --phases 3]`: then that many loops and phases stepped (the teaching view mid-loop).
// --vision emulates a colour vision deficiency (Chromium's CDP emulation:
// deuteranopia, protanopia, tritanopia, achromatopsia, blurredVision);
// --found runs the episode to its end; --first-visit shows the tour.
// Needs `make build` first (www/pkg, www/vendor).
import { existsSync } from 'node:fs';
import { mkdir } from 'node:fs/promises';
import path from 'node:path';
import { ROOT, SHOT_DIR, describeProblems, launchBrowser, openPage, startServer } from './harness.mjs';

/** The five viewports of the layout tests; phones with touch and their pixel ratio. */
export const VIEWPORTS = {
  '1366x768': { viewport: { width: 1366, height: 768 } },
  '1440x900': { viewport: { width: 1440, height: 900 } },
  '1920x1080': { viewport: { width: 1920, height: 1080 } },
  pixel7: { viewport: { width: 412, height: 915 }, deviceScaleFactor: 2.625, isMobile: true, hasTouch: true },
  iphone13: { viewport: { width: 390, height: 844 }, deviceScaleFactor: 3, isMobile: true, hasTouch: true },
};

const arg = (name, def) => {
  const i = process.argv.indexOf(`--${name}`);
  return i > 0 ? process.argv[i + 1] : def;
};
const flag = (name) => process.argv.includes(`--${name}`);

async function shoot(server, name, device, opts) {
  const browser = await launchBrowser(device);
  try {
    const { page, report } = await openPage(browser.context, `${server.url}${opts.query}`, { firstVisit: opts.firstVisit });
    if (opts.vision) {
      const cdp = await page.context().newCDPSession(page);
      await cdp.send('Emulation.setEmulatedVisionDeficiency', { type: opts.vision });
    }
    await page.waitForFunction(() => window.torusTest?.runs().length, null, { timeout: 30_000 });
    if (opts.found) {
      await page.evaluate(() => {
        window.torusTest.dispatch({ type: 'speed', speed: 'max' });
        window.torusTest.dispatch({ type: 'play' });
      });
      await page.waitForFunction(() => ['found', 'capped'].includes(window.torusTest.state()), null, { timeout: 120_000 });
      await page.waitForTimeout(400); // mid-animation: the pulse at the target
    } else if (!opts.firstVisit) {
      // A few moves in, then paused: the same picture every time.
      await page.waitForFunction((k) => window.torusTest.runs()[0].steps >= k || window.torusTest.state() === 'idle', opts.moves, { timeout: 60_000 });
      if (await page.evaluate(() => window.torusTest.state() === 'idle')) {
        for (let i = 0; i < opts.moves; i++) await page.evaluate(() => window.torusTest.dispatch({ type: 'stepMove' }));
      }
      await page.evaluate(() => window.torusTest.dispatch({ type: 'pause' }));
      for (let i = 0; i < opts.loops; i++) await page.evaluate(() => window.torusTest.dispatch({ type: 'stepLoop' }));
      for (let i = 0; i < opts.phases; i++) await page.evaluate(() => window.torusTest.dispatch({ type: 'stepPhase' }));
      if (opts.hoverTree) await page.hover('#tree-canvas', { position: { x: 30, y: 40 } }).catch(() => {});
      await page.waitForTimeout(400);
    } else {
      await page.waitForSelector('#tour:not([hidden])', { timeout: 30_000 });
      await page.waitForTimeout(300);
    }
    await mkdir(SHOT_DIR, { recursive: true });
    const file = path.join(SHOT_DIR, `${opts.prefix}-${name}.png`);
    await page.screenshot({ path: file });
    console.log(file);
    const problems = describeProblems(report);
    if (problems) console.error(`${name}: ${problems}`);
    return !problems;
  } finally {
    await browser.close();
  }
}

if (process.argv[1] && path.resolve(process.argv[1]) === path.resolve(new URL(import.meta.url).pathname)) {
  if (!existsSync(path.join(ROOT, 'www', 'pkg', 'torus_search.js'))) {
    console.error('www/pkg is missing: run `make build` first');
    process.exit(1);
  }
  const sizes = arg('sizes', '1366x768,1920x1080,iphone13').split(',');
  const opts = {
    prefix: arg('prefix', 'www'),
    query: arg('query', '?seed=3'),
    vision: arg('vision', ''),
    moves: Number(arg('moves', '12')),
    loops: Number(arg('loops', '0')),
    phases: Number(arg('phases', '0')),
    hoverTree: flag('hover-tree'),
    found: flag('found'),
    firstVisit: flag('first-visit'),
  };
  const server = await startServer(ROOT);
  let ok = true;
  try {
    for (const name of sizes) {
      if (!VIEWPORTS[name]) throw new Error(`unknown size ${name}: one of ${Object.keys(VIEWPORTS).join(', ')}`);
      ok = (await shoot(server, name, VIEWPORTS[name], opts)) && ok;
    }
  } finally {
    await server.close();
  }
  process.exit(ok ? 0 : 1);
}
