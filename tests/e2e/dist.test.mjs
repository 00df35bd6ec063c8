// Smoke test of the static bundle written by `make dist`: dist/ is served
// under a sub-path (/some/sub/path/) to prove it uses relative URLs only, and
// every request that leaves the origin is blocked and fails the test, to prove
// it works offline from any static host.
import assert from 'node:assert/strict';
import { existsSync } from 'node:fs';
import { copyFile, mkdir, mkdtemp, readFile, rm, symlink } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { test } from 'node:test';
import { ROOT, describeProblems, screenshot, waitUntilRunning, withPage } from './harness.mjs';

const DIST = path.join(ROOT, 'dist');

test('dist/ works from a sub-path of a static host', { timeout: 120_000 }, async () => {
  assert.ok(existsSync(path.join(DIST, 'index.html')), 'dist/ is missing: run `make dist` first');
  const host = await mkdtemp(path.join(tmpdir(), 'torus-e2e-host-'));
  try {
    await mkdir(path.join(host, 'some', 'sub'), { recursive: true });
    await symlink(DIST, path.join(host, 'some', 'sub', 'path'), 'dir');
    // The host reads _headers at its root, as Netlify and Cloudflare Pages do.
    await copyFile(path.join(DIST, '_headers'), path.join(host, '_headers'));
    await withPage(host, '/some/sub/path/', async ({ page, report, server }) => {
      let state;
      try {
        state = await waitUntilRunning(page, { report });
      } finally {
        await screenshot(page, 'dist');
      }
      assert.notEqual(state, 'error');
      assert.equal(describeProblems(report), '', 'the bundled page reported problems');
      // The page and its workers were served with the CSP of index.html as a
      // header (so Trusted Types bind the workers too), and nosniff; the
      // harness turns any CSP violation into a console error, checked above.
      const meta = await page.locator('meta[http-equiv="Content-Security-Policy"]').getAttribute('content');
      assert.match(await readFile(path.join(DIST, '_headers'), 'utf8'), /require-trusted-types-for 'script'/);
      for (const file of ['', 'www/workers/search-worker.js', 'www/workers/trial-worker.js', 'www/pkg/torus_search_bg.wasm']) {
        const res = await page.request.get(`${server.url}some/sub/path/${file}`);
        assert.equal(res.status(), 200, file);
        assert.equal(res.headers()['content-security-policy'], meta, `${file || 'index.html'} has the CSP header`);
        assert.equal(res.headers()['x-content-type-options'], 'nosniff', file);
      }
    });
  } finally {
    await rm(host, { recursive: true, force: true });
  }
});
