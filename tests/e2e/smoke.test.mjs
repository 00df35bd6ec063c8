// Smoke test: the page served from the repository root loads the wasm
// package, reaches a live state and draws a non-blank canvas, with no console
// error, no failed request and no request leaving the origin.
// Needs `make build` first (www/pkg, www/vendor); `make test` does that.
import assert from 'node:assert/strict';
import { existsSync } from 'node:fs';
import path from 'node:path';
import { test } from 'node:test';
import { ROOT, describeProblems, screenshot, waitUntilRunning, withPage } from './harness.mjs';

test('served page runs and draws a non-blank canvas', { timeout: 120_000 }, async () => {
  assert.ok(
    existsSync(path.join(ROOT, 'www', 'pkg', 'torus_search.js')),
    'www/pkg is missing: run `make build` first',
  );
  await withPage(ROOT, '/', async ({ page, report }) => {
    let state;
    try {
      state = await waitUntilRunning(page, { report });
    } finally {
      await screenshot(page, 'smoke');
    }
    assert.notEqual(state, 'error');
    assert.equal(describeProblems(report), '', 'the page reported problems');
  });
});
