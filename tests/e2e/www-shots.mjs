// Screenshots of the live view at a laptop, a wide screen and a phone, into
// target/e2e/<prefix>-<size>.png, to look at after a change to the page.
// Not a test: `node tests/e2e/www-shots.mjs [--prefix www] [--query '?seed=3']`.
// Needs `make build` first (www/pkg, www/vendor).
import { existsSync } from 'node:fs';
import path from 'node:path';
import { ROOT, describeProblems, launchBrowser, openPage, screenshot, startServer } from './harness.mjs';

const SIZES = [
  ['1366x768', { width: 1366, height: 768 }],
  ['1920x1080', { width: 1920, height: 1080 }],
  ['phone', { width: 390, height: 844 }],
];

const arg = (name, def) => {
  const i = process.argv.indexOf(`--${name}`);
  return i > 0 ? process.argv[i + 1] : def;
};
const prefix = arg('prefix', 'www');
const query = arg('query', '?seed=3');

if (!existsSync(path.join(ROOT, 'www', 'pkg', 'torus_search.js'))) {
  console.error('www/pkg is missing: run `make build` first');
  process.exit(1);
}
const server = await startServer(ROOT);
let failed = false;
try {
  for (const [name, viewport] of SIZES) {
    const browser = await launchBrowser({ viewport });
    try {
      const { page, report } = await openPage(browser.context, `${server.url}${query}`);
      await page.waitForFunction(() => window.torusTest?.runs().length, null, { timeout: 30_000 });
      // A few moves in, then paused: the same picture every time.
      await page.waitForFunction(() => window.torusTest.runs()[0].steps >= 12, null, { timeout: 60_000 });
      await page.evaluate(() => window.torusTest.dispatch({ type: 'pause' }));
      await page.waitForTimeout(300);
      console.log(await screenshot(page, `${prefix}-${name}`));
      const problems = describeProblems(report);
      if (problems) {
        failed = true;
        console.error(`${name}: ${problems}`);
      }
    } finally {
      await browser.close();
    }
  }
} finally {
  await server.close();
}
process.exit(failed ? 1 : 0);
