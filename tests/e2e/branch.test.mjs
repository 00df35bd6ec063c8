// End-to-end tests of branching (issue 44): an edit of a searcher parameter
// made while paused after move 0 offers "Branch from move k" or "Restart";
// Cancel and Escape keep the run; a branch keeps the path up to k and goes
// its own way, marked on the board; a world parameter restarts with a note;
// a link holds a branched run, and a bad branch in a link gets a message.
// Every wait is for a state or a value, never a fixed sleep.
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { mainPath, state, text, useApp, waitState, withApp } from './page-helpers.mjs';

useApp();

const QUERY = '?autoplay=0&n=16&sigma=3&loops=10&seed=4&variant=tree';

/** Waits until the first run shows timeline point (move, loop 0) and is paused. */
async function pausedAt(page, move) {
  await page
    .waitForFunction((m) => {
      const t = window.torusTest.timeline();
      return document.body.dataset.state === 'paused' && t && t.move === m && t.loop === 0 && !t.phase;
    }, move, { timeout: 30_000 })
    .catch(async (e) => {
      const seen = await page.evaluate(() => ({ state: document.body.dataset.state, timeline: window.torusTest.timeline(), message: document.getElementById('message')?.textContent, url: location.search }));
      assert.fail(`not paused at move ${move}: ${JSON.stringify(seen)} (${e.message})`);
    });
}

/** Sets parameter `key` in the form as a person does (its field's change event). */
async function edit(page, key, value) {
  await page.evaluate(([k, v]) => {
    const more = document.getElementById('more-settings');
    if (more && more.querySelector(`#${k}`)) more.open = true;
    const el = document.getElementById(k);
    el.value = v;
    el.dispatchEvent(new Event('change', { bubbles: true }));
  }, [key, value]);
}

/** Steps `k` moves with the button, then waits to stand at move k. */
async function stepMoves(page, k) {
  for (let i = 0; i < k; i++) await page.click('#step-move');
  await pausedAt(page, k);
}

test('an edit while paused offers a branch; cancel and Escape keep the run; a branch keeps the path so far', { timeout: 180_000 }, async () => {
  await withApp(QUERY, async (page) => {
    await stepMoves(page, 11);
    const original = await mainPath(page);
    assert.equal(original.length, 12);
    // Back to move 5: the prefix to keep.
    assert.deepEqual(await page.evaluate(() => window.torusTest.seek({ move: 5 })), { ok: true });
    await pausedAt(page, 5);
    const resets = await page.evaluate(() => window.torusTest.resets());

    // Cancel keeps the run and the old value.
    await edit(page, 'c', '0.2');
    await waitState(page, 'choosing');
    assert.equal(await page.locator('#branch-offer').isVisible(), true);
    assert.equal(await text(page, '#branch-go'), 'Branch from move 5');
    assert.match(await text(page, '#branch-offer-text'), /Changed .*c.* → 0\.2\. Keep the path up to move 5/);
    assert.equal(await page.evaluate(() => document.getElementById('c').value), '0.2');
    await page.click('#branch-cancel');
    await waitState(page, 'paused');
    assert.equal(await page.locator('#branch-offer').isVisible(), false);
    assert.notEqual(await page.evaluate(() => document.getElementById('c').value), '0.2');
    assert.deepEqual(await mainPath(page), original.slice(0, 6));
    assert.equal(await page.evaluate(() => window.torusTest.resets()), resets);

    // Escape, from the edited field, does the same.
    await edit(page, 'loops', '40');
    await waitState(page, 'choosing');
    await page.focus('#loops');
    await page.keyboard.press('Escape');
    await waitState(page, 'paused');
    assert.deepEqual(await mainPath(page), original.slice(0, 6));
    assert.equal((await page.evaluate(() => window.torusTest.runs()[0].config)).loops, 10);
    // Playback is refused while the choice waits (no click destroys the run).
    await edit(page, 'c', '0.2');
    await waitState(page, 'choosing');
    await page.click('#play');
    assert.equal(await state(page), 'choosing');

    // Branch: the path up to move 5 kept, the new setting from there.
    await page.click('#branch-go');
    await pausedAt(page, 5);
    assert.deepEqual(await mainPath(page), original.slice(0, 6));
    const run = await page.evaluate(() => window.torusTest.runs()[0]);
    assert.equal(run.config.c, 0.2);
    assert.deepEqual((await page.evaluate(() => window.torusTest.lineage())).map((p) => p.move), [5]);
    assert.match(await text(page, '#branch-note'), /^Branched at move 5 \(.*c.* → 0\.2\)/);
    assert.match(page.url(), /[?&]branch=5%3Ac%3D/);
    // The board draws the shared path and the branch point, and the legend names them.
    await page.waitForFunction(() => {
      const m = window.torusTest.drawn().marks;
      return m.includes('shared') && m.includes('branch');
    }, null, { timeout: 10_000 });
    await page.waitForFunction(() => window.torusTest.legend().marks.includes('branch'), null, { timeout: 10_000 });
    // It goes on its own way: the same first 6 cells, then other moves.
    for (let i = 0; i < 6; i++) await page.click('#step-move');
    await pausedAt(page, 11);
    const branched = await mainPath(page);
    assert.deepEqual(branched.slice(0, 6), original.slice(0, 6));
    assert.notDeepEqual(branched, original);
    // Seeking back into the shared prefix and forward again.
    assert.deepEqual(await page.evaluate(() => window.torusTest.seek({ move: 3 })), { ok: true });
    assert.deepEqual(await mainPath(page), original.slice(0, 4));
    await page.keyboard.press('End');
    await pausedAt(page, 11);
    assert.deepEqual(await mainPath(page), branched);
  });
});

test('Restart takes the edit from move 0; a world parameter restarts with a note', { timeout: 120_000 }, async () => {
  await withApp(QUERY, async (page) => {
    await stepMoves(page, 4);
    await edit(page, 'c', '0.5');
    await waitState(page, 'choosing');
    await page.click('#branch-restart');
    await pausedAt(page, 0);
    assert.equal((await page.evaluate(() => window.torusTest.runs()[0].config)).c, 0.5);
    assert.deepEqual(await page.evaluate(() => window.torusTest.lineage()), []);
    assert.equal(await page.locator('#branch-note').isVisible(), false);
    // A world parameter cannot branch: it restarts at once, saying why.
    await stepMoves(page, 3);
    await edit(page, 'sigma', '4');
    await pausedAt(page, 0);
    assert.equal(await page.locator('#branch-offer').isVisible(), false);
    assert.match(await text(page, '#message'), /Restarted from move 0: sigma cannot change in a branch \(3 → 4\)/);
    // Paused at move 0, or running, an edit restarts as before (no offer).
    await edit(page, 'c', '0.7');
    await pausedAt(page, 0);
    assert.equal((await page.evaluate(() => window.torusTest.runs()[0].config)).c, 0.7);
  });
});

test('a link holds a branched run; a bad branch in a link gets a message', { timeout: 180_000 }, async () => {
  let link;
  let want;
  await withApp(QUERY, async (page) => {
    await stepMoves(page, 6);
    await edit(page, 'c', '0.3');
    await waitState(page, 'choosing');
    await page.click('#branch-go');
    await pausedAt(page, 6);
    // A branch of the branch: both branch points are kept.
    for (let i = 0; i < 4; i++) await page.click('#step-move');
    await pausedAt(page, 10);
    await edit(page, 'loops', '30');
    await waitState(page, 'choosing');
    await page.click('#branch-go');
    await pausedAt(page, 10);
    for (let i = 0; i < 3; i++) await page.click('#step-move');
    await pausedAt(page, 13);
    want = await mainPath(page);
    // The address bar follows the run a moment later.
    await page.waitForFunction(() => new URLSearchParams(location.search).get('at') === '13', null, { timeout: 10_000 });
    link = page.url();
    // Oldest first: what each parent had otherwise than this run.
    assert.equal(new URL(link).searchParams.get('branch'), '6:loops=10 c=1.4142135623730951/10:loops=10');
  });
  await withApp(link.slice(link.indexOf('?')), async (page) => {
    await pausedAt(page, 13);
    assert.deepEqual(await mainPath(page), want);
    assert.deepEqual((await page.evaluate(() => window.torusTest.lineage())).map((p) => p.move), [6, 10]);
    await page.waitForFunction(() => window.torusTest.drawn().marks.includes('branch'), null, { timeout: 10_000 });
    assert.match(await text(page, '#branch-note'), /^Branched at move 10/);
  });
  // A move past the parent run: the message names the value and the range; the link's own run from move 0.
  await withApp(`${QUERY}&start=1,1&target=9,9&step_cap=5&branch=500:c=0.3`, async (page) => {
    await page.waitForFunction(() => /Could not open the branch/.test(document.getElementById('message').textContent), null, { timeout: 60_000 });
    assert.match(await text(page, '#message'), /branch=500:c=0\.3: branch at move 500 is past the run's moves: allowed moves 0 to 5\./);
    await pausedAt(page, 0);
    assert.deepEqual(await page.evaluate(() => window.torusTest.lineage()), []);
  }, { allowErrors: true });
  // A malformed value, and a parent that changes the world.
  await withApp(`${QUERY}&branch=five`, async (page) => {
    await page.waitForFunction(() => /Invalid branch="five": allowed where the run branched/.test(document.getElementById('message').textContent), null, { timeout: 30_000 });
  }, { allowErrors: true });
  await withApp(`${QUERY}&branch=3:n=20`, async (page) => {
    await page.waitForFunction(() => /Could not open the branch branch=3:n=20: n cannot change in a branch \(20 → 16\)/.test(document.getElementById('message').textContent), null, { timeout: 30_000 });
    await pausedAt(page, 0);
  }, { allowErrors: true });
});
