// Smoke test of the static bundle written by `make dist`: dist/ is served
// under a sub-path (/some/sub/path/) to prove it uses relative URLs only, and
// every request that leaves the origin is blocked and fails the test, to prove
// it works offline from any static host.
import assert from 'node:assert/strict';
import { existsSync } from 'node:fs';
import { mkdir, mkdtemp, rm, symlink } from 'node:fs/promises';
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
    await withPage(host, '/some/sub/path/', async ({ page, report }) => {
      let state;
      try {
        state = await waitUntilRunning(page, { report });
      } finally {
        await screenshot(page, 'dist');
      }
      assert.notEqual(state, 'error');
      assert.equal(describeProblems(report), '', 'the bundled page reported problems');
    });
  } finally {
    await rm(host, { recursive: true, force: true });
  }
});
