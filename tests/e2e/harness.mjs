// Shared helpers for the browser end-to-end tests (tests/e2e/*.test.mjs).
//
// - startServer(dir): `python3 -m http.server` on a free port of 127.0.0.1 only.
// - launchBrowser(): Debian's Chromium through playwright-core, headless, with a
//   fresh empty profile directory. Never downloads a browser.
// - openPage(context, url): a page plus a report of console errors, page
//   errors, failed requests (network errors and HTTP >= 400) and requests that
//   leave the server's origin (those are blocked, so the page must work offline).
// - withPage(dir, path, fn): all of the above, always closed afterwards.
// - screenshot(page, name): PNG into target/e2e/.
// - cliBinary({ release }): the torus-search CLI, built if stale.
// - canvasIsBlank(page, selector): true if every pixel of the canvas, as shown
//   on screen, has the same colour.
//
// Every wait is bounded by a timeout, and the browser and server are closed in
// `finally` blocks (and the server is killed on process exit as a last resort).

import { execFileSync, spawn } from 'node:child_process';
import { existsSync, readdirSync, statSync } from 'node:fs';
import { mkdir, mkdtemp, rm } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';

export const ROOT = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
export const SHOT_DIR = path.join(ROOT, 'target', 'e2e');
export const CHROMIUM = process.env.CHROMIUM_PATH || '/usr/bin/chromium';
export const CHROMIUM_ARGS = [
  '--headless',
  '--no-sandbox',
  '--disable-gpu',
  '--no-first-run',
  '--disable-background-networking',
  '--disable-component-update',
  '--disable-sync',
];

/**
 * The CLI binary (target/debug/torus-search, or target/release with
 * `release`), built first if missing or older than a file under src/ or Cargo.toml.
 */
export function cliBinary({ release = false } = {}) {
  const bin = path.join(ROOT, 'target', release ? 'release' : 'debug', 'torus-search');
  const newest = (dir) => readdirSync(dir, { withFileTypes: true }).reduce((m, e) => {
    const p = path.join(dir, e.name);
    return Math.max(m, e.isDirectory() ? newest(p) : statSync(p).mtimeMs);
  }, 0);
  const sources = Math.max(newest(path.join(ROOT, 'src')), statSync(path.join(ROOT, 'Cargo.toml')).mtimeMs);
  if (!existsSync(bin) || statSync(bin).mtimeMs < sources) {
    execFileSync('cargo', ['build', '--quiet', ...(release ? ['--release'] : []), '--bin', 'torus-search'], { cwd: ROOT, stdio: 'inherit' });
  }
  return bin;
}

/** Default bound for single waits (ms). Generous: CI has 2 cores shared. */
export const TIMEOUT_MS = 30_000;

const liveChildren = new Set();
process.on('exit', () => {
  for (const child of liveChildren) {
    try { child.kill('SIGKILL'); } catch { /* already gone */ }
  }
});

/** Reject after `ms` with a message naming what timed out. */
export function withTimeout(promise, ms, what) {
  let timer;
  const timeout = new Promise((_, reject) => {
    timer = setTimeout(() => reject(new Error(`timed out after ${ms} ms: ${what}`)), ms);
  });
  return Promise.race([promise, timeout]).finally(() => clearTimeout(timer));
}

/**
 * Serve `dir` with `python3 -m http.server` on 127.0.0.1 and a free port
 * (port 0: the OS picks one). Resolves to { url, origin, port, close() }.
 */
export async function startServer(dir = ROOT, { timeoutMs = TIMEOUT_MS } = {}) {
  const child = spawn(
    'python3',
    ['-u', path.join(ROOT, 'scripts/static_server.py'), '0', dir],
    { stdio: ['ignore', 'pipe', 'pipe'] },
  );
  liveChildren.add(child);
  const log = [];
  const close = async () => {
    if (child.exitCode !== null || child.signalCode !== null) {
      liveChildren.delete(child);
      return;
    }
    const exited = new Promise((resolve) => child.once('exit', resolve));
    child.kill('SIGTERM');
    try {
      await withTimeout(exited, 5_000, 'static server to exit');
    } catch {
      child.kill('SIGKILL');
    }
    liveChildren.delete(child);
  };
  try {
    const port = await withTimeout(
      new Promise((resolve, reject) => {
        const onData = (chunk) => {
          const text = chunk.toString();
          log.push(text);
          const m = /port (\d+)/.exec(log.join(''));
          if (m) resolve(Number(m[1]));
        };
        child.stdout.on('data', onData);
        child.stderr.on('data', (chunk) => log.push(chunk.toString()));
        child.once('error', reject);
        child.once('exit', (code) => reject(new Error(`static server exited (${code}): ${log.join('')}`)));
      }),
      timeoutMs,
      `static server for ${dir} to start`,
    );
    const origin = `http://127.0.0.1:${port}`;
    return { url: `${origin}/`, origin, port, close, log };
  } catch (err) {
    await close();
    throw err;
  }
}

/**
 * Launch Chromium with a fresh, empty profile directory. `device` options
 * (deviceScaleFactor, isMobile, hasTouch, reducedMotion) go to the context.
 * Resolves to { context, close() }; close() also deletes the profile.
 */
export async function launchBrowser({ timeoutMs = TIMEOUT_MS, viewport = { width: 1280, height: 800 }, ...device } = {}) {
  const profile = await mkdtemp(path.join(tmpdir(), 'torus-e2e-profile-'));
  let context;
  try {
    context = await chromium.launchPersistentContext(profile, {
      executablePath: CHROMIUM,
      headless: true,
      args: CHROMIUM_ARGS,
      viewport,
      timeout: timeoutMs,
      ...device,
    });
  } catch (err) {
    await rm(profile, { recursive: true, force: true });
    throw err;
  }
  context.setDefaultTimeout(timeoutMs);
  context.setDefaultNavigationTimeout(timeoutMs);
  const close = async () => {
    try {
      await withTimeout(context.close(), 10_000, 'browser to close');
    } catch {
      context.browser()?.close().catch(() => {});
    } finally {
      await rm(profile, { recursive: true, force: true });
    }
  };
  return { context, close };
}

/**
 * Open `url` in a new page of `context` and record problems in `report`:
 *   consoleErrors  console.error messages and uncaught page errors
 *   failedRequests network failures and HTTP status >= 400
 *   offOrigin      requests to any other origin (blocked)
 * The page opens as a returning visitor's (the first-visit tour is marked
 * seen) unless `firstVisit`.
 * Resolves to { page, report } after the load event.
 */
export async function openPage(context, url, { timeoutMs = TIMEOUT_MS, firstVisit = false } = {}) {
  const origin = new URL(url).origin;
  const report = { consoleErrors: [], failedRequests: [], offOrigin: [] };
  const page = await context.newPage();
  await page.route('**/*', (route) => {
    const reqUrl = route.request().url();
    const u = new URL(reqUrl);
    if (u.protocol === 'data:' || u.protocol === 'blob:' || u.origin === origin) {
      return route.continue();
    }
    report.offOrigin.push(reqUrl);
    return route.abort('blockedbyclient');
  });
  page.on('console', (msg) => {
    if (msg.type() === 'error') {
      const loc = msg.location();
      report.consoleErrors.push(`${msg.text()}${loc?.url ? ` (${loc.url}:${loc.lineNumber})` : ''}`);
    }
  });
  page.on('pageerror', (err) => report.consoleErrors.push(`uncaught: ${err.stack || err.message}`));
  page.on('requestfailed', (req) => {
    if (!report.offOrigin.includes(req.url())) {
      report.failedRequests.push(`${req.method()} ${req.url()}: ${req.failure()?.errorText}`);
    }
  });
  page.on('response', (res) => {
    if (res.status() >= 400) report.failedRequests.push(`${res.request().method()} ${res.url()}: HTTP ${res.status()}`);
  });
  // Every CSP violation (Trusted Types included) becomes a console error,
  // so every test that checks for console errors checks the CSP too.
  await page.addInitScript(() => {
    document.addEventListener('securitypolicyviolation', (e) => {
      console.error(`CSP violation: ${e.violatedDirective} blocked ${e.blockedURI || 'inline'} (${e.sample || 'no sample'})`);
    });
  });
  if (!firstVisit) {
    await page.addInitScript(() => {
      try {
        localStorage.setItem('torus-search.tour', 'seen');
      } catch {
        /* storage refused: the tour shows */
      }
    });
  }
  await page.goto(url, { waitUntil: 'load', timeout: timeoutMs });
  return { page, report };
}

/** A readable summary of everything `report` recorded, or '' if clean. */
export function describeProblems(report) {
  const parts = [];
  if (report.consoleErrors.length) parts.push(`console errors:\n  ${report.consoleErrors.join('\n  ')}`);
  if (report.failedRequests.length) parts.push(`failed requests:\n  ${report.failedRequests.join('\n  ')}`);
  if (report.offOrigin.length) parts.push(`requests leaving the origin:\n  ${report.offOrigin.join('\n  ')}`);
  return parts.join('\n');
}

/**
 * Serve `dir`, launch Chromium, open `urlPath` (relative to the server root)
 * and run `fn({ page, report, server, context })`. Always closes the browser
 * and the server.
 */
export async function withPage(dir, urlPath, fn, { timeoutMs = TIMEOUT_MS } = {}) {
  const server = await startServer(dir, { timeoutMs });
  let browser;
  try {
    browser = await launchBrowser({ timeoutMs });
    const url = new URL(urlPath.replace(/^\//, ''), server.url).href;
    const { page, report } = await openPage(browser.context, url, { timeoutMs });
    return await fn({ page, report, server, context: browser.context });
  } finally {
    if (browser) await browser.close();
    await server.close();
  }
}

/** Save a full-page PNG screenshot as target/e2e/<name>.png; returns its path. */
export async function screenshot(page, name, { timeoutMs = TIMEOUT_MS } = {}) {
  await mkdir(SHOT_DIR, { recursive: true });
  const file = path.join(SHOT_DIR, name.endsWith('.png') ? name : `${name}.png`);
  await page.screenshot({ path: file, fullPage: true, timeout: timeoutMs });
  return file;
}

/**
 * True if every pixel of the first element matching `selector` has the same
 * colour as shown on screen (works for 2-D, WebGL and offscreen-backed
 * canvases alike: it decodes an element screenshot, not the canvas buffer).
 * Throws if no such element is visible within the timeout.
 */
export async function canvasIsBlank(page, selector = 'canvas', { timeoutMs = TIMEOUT_MS } = {}) {
  const png = await page.locator(selector).first().screenshot({ timeout: timeoutMs, animations: 'disabled' });
  // Decode with the browser's own PNG decoder, in a blank page so the app
  // page's CSP and state are not involved.
  const helper = await page.context().newPage();
  try {
    return await withTimeout(
      helper.evaluate(async (b64) => {
        const bytes = Uint8Array.from(atob(b64), (c) => c.charCodeAt(0));
        const bitmap = await createImageBitmap(new Blob([bytes], { type: 'image/png' }));
        const off = new OffscreenCanvas(bitmap.width, bitmap.height);
        const ctx = off.getContext('2d');
        ctx.drawImage(bitmap, 0, 0);
        const data = new Uint32Array(ctx.getImageData(0, 0, bitmap.width, bitmap.height).data.buffer);
        const first = data[0];
        for (let i = 1; i < data.length; i++) if (data[i] !== first) return false;
        return true;
      }, png.toString('base64')),
      timeoutMs,
      `decoding a screenshot of ${selector}`,
    );
  } finally {
    await helper.close();
  }
}

/**
 * Wait until the page reports a live state: `document.body.dataset.state` is
 * set and is not 'error', a <canvas> matching `selector` exists, and it is not
 * blank. Fails at once if the state becomes 'error'. Resolves to the state.
 */
export async function waitUntilRunning(page, { selector = 'canvas', timeoutMs = 60_000, report } = {}) {
  const deadline = Date.now() + timeoutMs;
  let last = 'no state yet';
  while (Date.now() < deadline) {
    // page.evaluate has no timeout of its own (a busy main thread would hang it).
    const { state, hasCanvas } = await withTimeout(
      page.evaluate((sel) => ({
        state: document.body?.dataset.state ?? null,
        hasCanvas: document.querySelector(sel) !== null,
      }), selector),
      Math.max(1_000, deadline - Date.now()),
      'reading the page state (main thread busy?)',
    );
    if (state === 'error') {
      throw new Error(`page state is 'error'${report ? `\n${describeProblems(report)}` : ''}`);
    }
    if (state && hasCanvas) {
      if (!(await canvasIsBlank(page, selector, { timeoutMs: Math.max(1_000, deadline - Date.now()) }))) {
        return state;
      }
      last = `state '${state}', canvas still blank`;
    } else {
      last = `state ${state === null ? 'unset' : `'${state}'`}, ${hasCanvas ? '' : 'no '}canvas`;
    }
    await page.waitForTimeout(250);
  }
  throw new Error(`page not running after ${timeoutMs} ms (${last})${report ? `\n${describeProblems(report)}` : ''}`);
}
