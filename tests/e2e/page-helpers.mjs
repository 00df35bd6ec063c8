// Shared set-up and helpers of the page's end-to-end tests
// (page.test.mjs, page-more.test.mjs): a server and a browser per test
// file, and ways to open the page, wait for its states and read it.
import assert from 'node:assert/strict';
import { existsSync } from 'node:fs';
import { mkdir } from 'node:fs/promises';
import path from 'node:path';
import { after, before } from 'node:test';
import { ROOT, SHOT_DIR, describeProblems, launchBrowser, openPage, startServer } from './harness.mjs';

let server;
let browser;

/** Starts the server and the browser before the file's tests, and stops them after. */
export function useApp() {
  before(async () => {
    assert.ok(existsSync(path.join(ROOT, 'www', 'pkg', 'torus_search.js')), 'www/pkg is missing: run `make build` first');
    server = await startServer(ROOT);
    browser = await launchBrowser({ viewport: { width: 1280, height: 900 } });
  });
  after(async () => {
    await browser?.close();
    await server?.close();
  });
}

/** The running server (after `useApp`'s set-up). */
export const appServer = () => server;
/** The running browser (after `useApp`'s set-up). */
export const appBrowser = () => browser;

/** Opens a page at `query` and runs fn; closes it afterwards. */
export async function withApp(query, fn, { allowErrors = false, viewport } = {}) {
  const { page, report } = await openPage(browser.context, `${server.url}${query}`);
  try {
    if (viewport) await page.setViewportSize(viewport);
    // The runs come from the search worker, a moment after the controller exists.
    await page.waitForFunction(() => {
      const t = window.torusTest;
      return t && (t.runs().length || t.state() === 'error');
    }, null, { timeout: 30_000 });
    await fn(page, report);
    if (!allowErrors) assert.equal(describeProblems(report), '', 'the page reported problems');
    else assert.deepEqual(report.offOrigin, [], 'requests left the origin');
  } finally {
    await page.close();
  }
}

export const state = (page) => page.evaluate(() => document.body.dataset.state);
export const text = (page, sel) => page.locator(sel).textContent();

/** Waits (briefly) until `sel` shows `want`: panels update on the next animation frame. */
export async function expectText(page, sel, want) {
  try {
    await page.waitForFunction(([q, w]) => document.querySelector(q)?.textContent === w, [sel, want], { timeout: 5_000, polling: 50 });
  } catch {
    assert.equal(await text(page, sel), want, sel);
  }
}
export const mainPath = (page) => page.evaluate(() => window.torusTest.path(0));

export async function waitState(page, states, timeout = 90_000) {
  const want = Array.isArray(states) ? states : [states];
  await page.waitForFunction((w) => w.includes(document.body.dataset.state), want, { timeout, polling: 100 });
  return state(page);
}

export async function runToEnd(page) {
  await page.evaluate(() => {
    window.torusTest.dispatch({ type: 'speed', speed: 'max' });
    window.torusTest.dispatch({ type: 'play' });
  });
  const end = await waitState(page, ['found', 'capped']);
  // The state changes when the last frame arrives; the panels show it at
  // the next animation frame, which on a loaded machine can come later
  // than a poll of the state.
  await page.waitForFunction(() => /^(Found in|Step cap reached)/.test(document.querySelector('#board-0 .banner').textContent), null, { timeout: 10_000 });
  return end;
}

/** A viewport (not full-page) PNG in target/e2e/, the size the README shows. */
export async function viewShot(page, name) {
  await mkdir(SHOT_DIR, { recursive: true });
  await page.evaluate(() => window.scrollTo(0, 0));
  await page.screenshot({ path: path.join(SHOT_DIR, `${name}.png`) });
}

/** A hash of the main canvas's pixels. */
export function canvasHash(page, id = 'view-0') {
  return page.evaluate((cid) => {
    const c = document.getElementById(cid);
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let h = 2166136261;
    for (let i = 0; i < d.length; i += 7) h = Math.imul(h ^ d[i], 16777619);
    return h >>> 0;
  }, id);
}
