// Helpers of the one-screen tests (screen.test.mjs, screen-input.test.mjs):
// a page on an emulated device (a laptop or a phone with touch), and reads
// of what is on screen.
import assert from 'node:assert/strict';
import { existsSync } from 'node:fs';
import path from 'node:path';
import { after, before } from 'node:test';
import { ROOT, describeProblems, launchBrowser, openPage, startServer } from './harness.mjs';
import { VIEWPORTS } from './www-shots.mjs';

let server;

/** Starts the server before the file's tests and stops it after. */
export function useServer() {
  before(async () => {
    assert.ok(existsSync(path.join(ROOT, 'www', 'pkg', 'torus_search.js')), 'www/pkg is missing: run `make build` first');
    server = await startServer(ROOT);
  });
  after(async () => server?.close());
}

/**
 * Opens `query` on device `name` (a VIEWPORTS key) in a browser of its own
 * and runs fn(page, report); fails on console errors unless `allowErrors`.
 * `reducedMotion: 'reduce'` emulates the visitor's wish; `firstVisit` shows the tour.
 */
export async function withDevice(name, query, fn, { firstVisit = false, reducedMotion = 'no-preference', allowErrors = false } = {}) {
  const browser = await launchBrowser({ ...VIEWPORTS[name], reducedMotion });
  try {
    const { page, report } = await openPage(browser.context, `${server.url}${query}`, { firstVisit });
    await page.waitForFunction(() => window.torusTest?.runs().length, null, { timeout: 30_000 });
    await fn(page, report);
    if (!allowErrors) assert.equal(describeProblems(report), '', 'the page reported problems');
  } finally {
    await browser.close();
  }
}

/** The client rectangles of `selectors` (the first match each), and the viewport. */
export const boxes = (page, selectors) =>
  page.evaluate((sels) => ({
    view: { width: innerWidth, height: innerHeight, scrollY },
    boxes: Object.fromEntries(sels.map((s) => {
      const r = document.querySelector(s)?.getBoundingClientRect();
      return [s, r ? { left: r.left, top: r.top, right: r.right, bottom: r.bottom, width: r.width, height: r.height } : null];
    })),
  }), selectors);

/** Asserts that each of `selectors` lies wholly inside the viewport (and is not empty). */
export async function assertInView(page, selectors, where) {
  const { view, boxes: b } = await boxes(page, selectors);
  for (const s of selectors) {
    const r = b[s];
    assert.ok(r && r.width > 0 && r.height > 0, `${where}: ${s} is not shown`);
    const inside = r.left >= -0.5 && r.top >= -0.5 && r.right <= view.width + 0.5 && r.bottom <= view.height + 0.5;
    assert.ok(inside, `${where}: ${s} at ${Math.round(r.left)},${Math.round(r.top)}–${Math.round(r.right)},${Math.round(r.bottom)} is not inside ${view.width}×${view.height}`);
  }
}

export const state = (page) => page.evaluate(() => document.body.dataset.state);

/** Runs the main run to its end at full speed. */
export async function runToEnd(page) {
  await page.evaluate(() => {
    window.torusTest.dispatch({ type: 'speed', speed: 'max' });
    window.torusTest.dispatch({ type: 'play' });
  });
  await page.waitForFunction(() => ['found', 'capped'].includes(window.torusTest.state()), null, { timeout: 120_000, polling: 100 });
}

/** Sets a form control's value as a user would and sends its change (no scrolling). */
export const setParam = (page, id, value) =>
  page.evaluate(([i, v]) => {
    const el = document.getElementById(i);
    el.value = v;
    el.dispatchEvent(new Event('change'));
  }, [id, value]);
