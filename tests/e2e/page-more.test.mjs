// End-to-end tests of the web page, continued: failures and recovery,
// race mode, the planners' slices, layout at every width, batches in
// workers, and the screenshots for docs/. Helpers: page-helpers.mjs.
import assert from 'node:assert/strict';
import { existsSync } from 'node:fs';
import { copyFile, mkdir } from 'node:fs/promises';
import path from 'node:path';
import { test } from 'node:test';
import { ROOT, SHOT_DIR, canvasIsBlank, screenshot } from './harness.mjs';
import { expectText, mainPath, runToEnd, state, text, useApp, viewShot, waitState, withApp } from './page-helpers.mjs';

useApp();

async function restartsAfterTrap(page) {
  assert.equal(await canvasIsBlank(page, '#view-0'), false);
  await expectText(page, '#play', 'Restart');
  await page.click('#play');
  assert.match(await waitState(page, ['running', 'found'], 30_000), /running|found/);
  await page.waitForFunction(() => Number(document.getElementById('steps').textContent) > 0, null, { timeout: 30_000 });
}

test('a wasm panic shows a readable message and sets state error', { timeout: 120_000 }, async () => {
  await withApp('?autoplay=0&n=12', async (page, report) => {
    // The panic happens in the search worker's wasm instance, as a real one would.
    await page.evaluate(() => window.torusTest.request('panicForTest', { message: 'deliberate test panic' }));
    await waitState(page, 'error', 30_000);
    assert.match(await text(page, '#message'), /wasm panic.*panicForTest: deliberate test panic/);
    assert.ok(report.consoleErrors.some((e) => e.includes('deliberate test panic')), 'the panic hook logs it');
    await restartsAfterTrap(page);
  }, { allowErrors: true });
});

test('running out of wasm memory in the search worker shows a readable message, and Restart recovers', { timeout: 180_000 }, async () => {
  await withApp('?autoplay=0&n=12', async (page, report) => {
    // A real out-of-memory abort: the worker's instance allocates until its
    // linear memory cannot grow (4 GiB), and Rust aborts with a bare trap.
    await page.evaluate(() => window.torusTest.request('oomForTest', {}));
    await waitState(page, 'error', 120_000);
    const msg = await text(page, '#message');
    assert.match(msg, /ran out of memory: it could not allocate \d+ MiB more, with \d+ MiB of WebAssembly memory in use/);
    assert.doesNotMatch(msg, /unreachable/);
    await restartsAfterTrap(page);
    assert.deepEqual(report.consoleErrors.filter((e) => e.startsWith('uncaught')), [], 'nothing escapes uncaught');
  }, { allowErrors: true });
});

test('race mode: same target and seed, side by side, with a scoreboard', { timeout: 180_000 }, async () => {
  await withApp('?race=rw&n=30&sigma=4&seed=11&loops=60&belief=posterior', async (page) => {
    const runs = await page.evaluate(() => window.torusTest.runs());
    const targets = runs.map((r) => r.target);
    assert.equal(targets.length, 2);
    assert.ok(Number.isInteger(targets[0]), `target cell ${targets[0]}`);
    assert.equal(targets[0], targets[1]);
    assert.equal(runs[0].config.seed, '11');
    assert.equal(runs[1].config.seed, runs[0].config.seed);
    assert.equal(await page.locator('#board-1').isVisible(), true);
    await page.waitForFunction(() => Number(document.getElementById('steps').textContent) >= 12, null, { timeout: 60_000 });
    await viewShot(page, 'race-mode');
    await runToEnd(page);
    await page.waitForFunction(() => window.torusTest.runs().every((r) => r.status !== 'running'), null, { timeout: 90_000 });
    await page.evaluate(() => window.torusTest.dispatch({ type: 'redraw' }));
    await page.waitForTimeout(200);
    assert.equal(await page.locator('#score-rows tr').count(), 2);
    assert.ok((await page.locator('#score-rows tr.winner').count()) >= 1);
  });
});

/** Each cell of `cells` is one torus step from the one before. */
function assertUnitSteps(cells, n) {
  for (let i = 1; i < cells.length; i++) {
    const [a, b] = [cells[i - 1], cells[i]];
    const dx = Math.min(Math.abs((a % n) - (b % n)), n - Math.abs((a % n) - (b % n)));
    const dy = Math.min(Math.abs(Math.floor(a / n) - Math.floor(b / n)), n - Math.abs(Math.floor(a / n) - Math.floor(b / n)));
    assert.equal(dx + dy, 1, `step ${i}: ${a} → ${b}`);
  }
}

test("race: the paper's MCTS against the belief MCTS, both to found, on the same target and seed", { timeout: 240_000 }, async () => {
  await withApp('?preset=paper-code&race=mcts-pomcp&n=16&sigma=2&seed=5&speed=max', async (page) => {
    const runs = await page.evaluate(() => window.torusTest.runs());
    assert.deepEqual(runs.map((r) => r.config.variant), ['code', 'pomcp']);
    assert.equal(runs[0].target, runs[1].target);
    await page.waitForFunction(() => window.torusTest.runs().every((r) => r.status !== 'running'), null, { timeout: 200_000 });
    const done = await page.evaluate(() => window.torusTest.runs());
    assert.deepEqual(done.map((r) => r.status), ['found', 'found']);
    assert.ok(done.every((r) => r.steps >= r.optimal), 'no run beats the optimum');
  });
});

test("a planner draws its path ahead and the decision panel shows its scores of the four moves", { timeout: 120_000 }, async () => {
  await withApp('?searcher=horizon&n=20&sigma=3&speed=1', async (page) => {
    // Paused as soon as it has scores and a path ahead, so the panel is read
    // on that frame, not on one after the target was found (no move chosen).
    await page.waitForFunction(() => {
      const r = window.torusTest.runs()[0];
      const ready = r && r.steps >= 2 && r.scores && r.intent.length > 1 && r.status === 'running';
      if (ready) window.torusTest.dispatch({ type: 'pause' });
      return ready;
    }, null, { timeout: 60_000 });
    await page.evaluate(() => window.torusTest.ready());
    const [r, path] = await page.evaluate(() => [window.torusTest.runs()[0], window.torusTest.path()]);
    assert.equal(r.scores.score.length, 4);
    assert.ok(r.scores.chosen >= 0 && r.scores.chosen < 4);
    assert.match(r.scores.meaning, /\w/);
    // The path ahead starts where the searcher stands and moves one cell a step.
    assert.equal(r.intent[0], path.at(-1));
    assertUnitSteps(r.intent, r.n);
    await page.waitForFunction(() => !document.getElementById('plan-scores').hidden, null, { timeout: 10_000 });
    assert.equal(await page.locator('#decision').isVisible(), false, 'the UCT table gives way to the scores');
    assert.equal(await page.locator('#plan-scores tbody tr').count(), 4);
    assert.equal(await page.locator('#plan-scores tbody tr.chosen').count(), 1);
    assert.match(await text(page, '#decision-note'), /scores each move by/);
    // Unticking "Planned path" stops the frames carrying it.
    await page.uncheck('#layer-intent');
    await page.waitForFunction(() => window.torusTest.runs()[0].intent.length === 0, null, { timeout: 10_000 });
  });
});

test('the beam planner makes its plan in slices: the board says how far it has got, frames keep coming, then it follows the plan', { timeout: 180_000 }, async () => {
  await withApp('?searcher=beam&n=24&sigma=2&speed=max', async (page) => {
    // Sample the frames while the plan is made: each one answered by the
    // search worker mid-plan, so the progress moves on between them.
    const seen = await page.evaluate(async () => {
      const out = [];
      const t0 = performance.now();
      while (performance.now() - t0 < 120_000) {
        const r = window.torusTest.runs()[0];
        if (r?.planning) out.push({ ...r.planning, steps: r.steps, intent: r.intent.length, banner: document.querySelector('#board-0 .banner')?.textContent ?? '', stepLoop: !document.getElementById('step-loop').disabled });
        if (r && r.steps > 0) break;
        await new Promise((res) => requestAnimationFrame(res));
      }
      return out;
    });
    assert.ok(seen.length >= 3, `progress seen in ${seen.length} frames`);
    assert.ok(seen.every((p) => p.steps === 0), 'no move is made while planning');
    const search = seen.filter((p) => p.stage === 'beam search, depth');
    assert.ok(search.length >= 2, `beam search seen in ${search.length} frames`);
    assert.ok(search.at(-1).done > search[0].done, 'the depth grows from frame to frame');
    assert.ok(search.every((p) => p.total === 200 && p.done <= 200));
    assert.ok(seen.some((p) => p.intent > 1), 'the path being worked on is drawn');
    assert.ok(seen.some((p) => /^Planning: beam search, depth \d+ of 200…$/.test(p.banner)), seen.map((p) => p.banner).join(' | '));
    assert.ok(seen.some((p) => p.stepLoop), 'Step loop steps a slice while the plan is made');
    // Then the plan is followed (a move takes about a microsecond, so at
    // full speed the run ends soon after) and the banner gives the result.
    await page.waitForFunction(() => window.torusTest.runs()[0].status === 'found', null, { timeout: 60_000 });
    const r = (await page.evaluate(() => window.torusTest.runs()))[0];
    assert.equal(r.planning, null);
    assertUnitSteps(await mainPath(page), r.n);
    await page.waitForFunction(() => /^Found in/.test(document.querySelector('#board-0 .banner').textContent), null, { timeout: 10_000 });
    await page.waitForFunction(() => document.getElementById('step-loop').disabled, null, { timeout: 10_000 });
  });
});

test('Step move on a planner yet to make its plan: frames keep coming and the worker answers while the move is planned', { timeout: 180_000 }, async () => {
  await withApp('?searcher=beam&n=24&sigma=2&autoplay=0', async (page) => {
    await page.evaluate(() => window.torusTest.ready());
    assert.equal((await page.evaluate(() => window.torusTest.runs()))[0].steps, 0);
    await page.click('#step-move');
    const seen = await page.evaluate(async () => {
      const out = [];
      const t0 = performance.now();
      while (performance.now() - t0 < 120_000) {
        const r = window.torusTest.runs()[0];
        if (r && r.steps > 0) break;
        if (r?.planning) {
          // A request to the worker mid-plan is answered between slices.
          const q = performance.now();
          await window.torusTest.request('usage');
          out.push({ ...r.planning, steps: r.steps, answerMs: performance.now() - q });
        }
        await new Promise((res) => requestAnimationFrame(res));
      }
      return out;
    });
    assert.ok(seen.length >= 3, `progress seen in ${seen.length} frames`);
    assert.ok(seen.every((p) => p.steps === 0), 'no move is made while planning');
    const key = (p) => `${p.stage} ${p.done}`;
    assert.ok(new Set(seen.map(key)).size >= 3, `the plan moves on between frames: ${seen.map(key).join(' | ')}`);
    const slowest = Math.max(...seen.map((p) => p.answerMs));
    assert.ok(slowest < 2000, `the worker answered within ${slowest.toFixed(0)} ms`);
    // One move, and the page stays paused.
    await page.waitForFunction(() => window.torusTest.runs()[0].steps === 1, null, { timeout: 60_000 });
    assert.equal(await page.evaluate(() => window.torusTest.state()), 'paused');
    await page.waitForTimeout(300);
    const r = (await page.evaluate(() => window.torusTest.runs()))[0];
    assert.equal(r.steps, 1);
    assert.equal(r.planning, null);
  });
});

test('the belief MCTS draws its plan ahead, one cell a step from where it stands', { timeout: 120_000 }, async () => {
  await withApp('?variant=pomcp&n=20&sigma=3&speed=1', async (page) => {
    await page.waitForFunction(() => {
      const r = window.torusTest.runs()[0];
      // A plan runs to the end of the search; the tree's most visited line
      // (with no plan) is a few cells.
      return r && r.steps >= 2 && r.intent.length > 20;
    }, null, { timeout: 60_000 });
    const [r, path] = await page.evaluate(() => [window.torusTest.runs()[0], window.torusTest.path()]);
    assert.equal(r.config.variant, 'pomcp');
    assert.equal(r.intent[0], path.at(-1));
    assertUnitSteps(r.intent, r.n);
    // The UCT split is still shown for it: it is an MCTS.
    await page.waitForFunction(() => document.getElementById('decision').checkVisibility(), null, { timeout: 10_000 });
  });
});

test('teaching view, picking the start on the grid, painting a prior', { timeout: 180_000 }, async () => {
  await withApp('?autoplay=0', async (page) => {
    await page.click('#teaching');
    assert.match(await page.evaluate(() => location.search), /n=11/);
    await page.waitForFunction(() => Number(document.getElementById('steps').textContent) >= 2, null, { timeout: 60_000 });
    await page.click('#play');
    for (let i = 0; i < 3; i++) await page.click('#step-loop');
    // Mid-loop: the phase strip, the narration and the tree show the rollout just run.
    for (let i = 0; i < 3; i++) await page.click('#step-phase');
    await page.waitForFunction(() => window.torusTest.phase() === 'rollout' && window.torusTest.treeView().shown, null, { timeout: 10_000 });
    await page.waitForTimeout(100);
    await viewShot(page, 'teaching-view');
    // Setting the start is an explicit mode: its "Pick on grid" toggle, then
    // a click on the cell in the middle of the grid: start becomes (6,6).
    const box = await page.locator('#view-0').boundingBox();
    await page.click('#start-pick');
    await page.mouse.click(box.x + box.width * (5.5 / 11), box.y + box.height * (5.5 / 11));
    assert.equal(await page.inputValue('#start'), '6,6');
    assert.match(await page.evaluate(() => location.search), /start=6%2C6/);
    // Paint a prior.
    await page.selectOption('#prior', 'paint');
    await page.mouse.move(box.x + box.width * 0.2, box.y + box.height * 0.2);
    await page.mouse.down();
    await page.mouse.move(box.x + box.width * 0.3, box.y + box.height * 0.25, { steps: 5 });
    await page.mouse.up();
    const search = await page.evaluate(() => location.search);
    assert.match(search, /prior=paint/);
    assert.match(search, /paint=[A-Za-z0-9_-]+/);
    // The stroke restarted the run: wait for it.
    const cfg = await page.evaluate(async () => {
      await window.torusTest.ready();
      return window.torusTest.runs()[0].config;
    });
    assert.equal(cfg.prior, 'paint');
    assert.ok(cfg.paint && search.includes(`paint=${cfg.paint}`), 'the run uses the painted prior of the URL');
  });
});

test('phone-sized screen: no horizontal scrolling, touch-friendly controls', { timeout: 120_000 }, async () => {
  await withApp('', async (page) => {
    await page.waitForFunction(() => Number(document.getElementById('steps').textContent) >= 2, null, { timeout: 60_000 });
    const { scroll, width, canvasW } = await page.evaluate(() => ({
      scroll: document.documentElement.scrollWidth,
      width: window.innerWidth,
      canvasW: document.getElementById('view-0').getBoundingClientRect().width,
    }));
    assert.ok(scroll <= width, `page scrolls sideways: ${scroll} > ${width}`);
    assert.ok(canvasW >= width * 0.9, 'the lattice uses the screen width');
    const h = await page.locator('#play').boundingBox();
    assert.ok(h.height >= 32, 'buttons are big enough to tap');
    await screenshot(page, 'phone');
  }, { viewport: { width: 390, height: 844 } });
});

/**
 * Sends the search worker `count` usage requests, `gapMs` apart: how long
 * each answer took (ms), and the text of `selector` after each (with `also`,
 * the texts of both, read at once).
 */
async function askWorker(page, count, gapMs, selector, also) {
  const waits = [];
  const seen = [];
  for (let i = 0; i < count; i++) {
    waits.push(await page.evaluate(async () => {
      const t = performance.now();
      await window.torusTest.request('usage');
      return Math.round(performance.now() - t);
    }));
    // Read in one evaluate, so that `also` shows the same moment as `selector`.
    seen.push(await page.evaluate(([a, b]) => {
      const text = (sel) => document.querySelector(sel)?.textContent ?? '';
      return b ? [text(a), text(b)] : text(a);
    }, [selector, also]));
    await page.waitForTimeout(gapMs);
  }
  return { waits, seen };
}

test('a planner whose moves take seconds keeps the search worker answering at full speed, and shows how far its decision has got', { timeout: 120_000 }, async () => {
  // Rollout improvement with base horizon at N = 128 and a wide prior takes
  // about 2 s a move in wasm (four completions of thousands of horizon moves).
  // The worker sizes its calls from the moves it has timed, and the cheap
  // first ones once sized a call at dozens of such moves: 30 s without an
  // answer. Then each move's decision was one call: seconds without one.
  // Now a decision is made in slices of bounded work.
  await withApp('?searcher=improve&base=horizon&n=128&sigma=16&speed=max', async (page) => {
    const { waits, seen } = await askWorker(page, 8, 500, '#decision-loops');
    const progress = new Set(seen);
    assert.ok(Math.max(...waits) < 1_000, `the worker answered in ${waits.join(', ')} ms`);
    assert.equal(await page.locator('#decision-loops-label').textContent(), 'This move');
    const shown = [...progress].filter((t) => /^completing the search after each move \d+ of \d+ \([\d,]+ moves into the one under way\)$/.test(t));
    assert.ok(shown.length >= 2, `the decision's progress shows: ${[...progress].join(' | ')}`);
    // A decision made every move does not take the board's banner.
    assert.ok(await page.locator('#board-0 .banner').isHidden(), 'no planning banner');
    await page.waitForFunction(() => Number(document.getElementById('steps').textContent) >= 2, null, { timeout: 60_000 });
  });
});

test('the belief MCTS makes its plan in slices: on a large lattice the worker answers and the board shows the plan growing', { timeout: 120_000 }, async () => {
  // At N = 1024 its plan (the horizon rule's path, up to the rollout cap of
  // 10 000 moves) once took the first loop 9.3 s, with no answer meanwhile.
  await withApp('?variant=pomcp&n=1024&speed=max', async (page) => {
    const { waits, seen } = await askWorker(page, 8, 150, '#board-0 .banner', '#decision-note');
    assert.ok(Math.max(...waits) < 1_000, `the worker answered in ${waits.join(', ')} ms`);
    const planning = seen.filter(([b]) => /^Planning: the horizon rule's plan, moves \d+…$/.test(b));
    const moves = planning.map(([b]) => Number(/moves (\d+)/.exec(b)[1]));
    assert.ok(moves.length >= 2 && moves.at(-1) > moves[0], `the plan grows on the banner: ${seen.map(([b]) => b).join(' | ')}`);
    // While it plans, the decision panel says why no loop has run yet (the
    // plan can be done before a later read, so both are read at once).
    for (const [, note] of planning) {
      assert.match(note, /is making its plan before the first loop \(the horizon rule's plan, moves \d+\)/);
    }
  });
});

test('the spiral planner makes its plan in slices on a large lattice, then follows it with unit moves', { timeout: 120_000 }, async () => {
  // At N = 1024 each of its 16 shapes is a walk of up to 350 000 moves:
  // about 0.2 s in all, made a slice at a time between frames.
  await withApp('?searcher=spiral&n=1024&sigma=128&speed=8', async (page) => {
    const seen = await page.evaluate(async () => {
      const out = [];
      const t0 = performance.now();
      while (performance.now() - t0 < 60_000) {
        const r = window.torusTest.runs()[0];
        if (r?.planning) out.push({ ...r.planning, steps: r.steps, banner: document.querySelector('#board-0 .banner')?.textContent ?? '' });
        if (r && r.steps > 0) break;
        await new Promise((res) => requestAnimationFrame(res));
      }
      return out;
    });
    assert.ok(seen.length >= 3, `progress seen in ${seen.length} frames`);
    assert.ok(seen.every((p) => p.steps === 0 && p.stage === 'spiral shape' && p.total === 16));
    const shapes = seen.map((p) => p.done);
    assert.ok(shapes.at(-1) > shapes[0], `the shape under way moves on: ${shapes.join(', ')}`);
    assert.ok(seen.some((p) => /^Planning: spiral shape \d+ of 16 \([\d,]+ moves into the one under way\)…$/.test(p.banner)), seen.map((p) => p.banner).join(' | '));
    await page.waitForFunction(() => window.torusTest.runs()[0].steps >= 200, null, { timeout: 60_000 });
    const r = (await page.evaluate(() => window.torusTest.runs()))[0];
    assert.equal(r.planning, null);
    assertUnitSteps(await mainPath(page), r.n);
  });
});

test('every control lies within its panel and the page never scrolls sideways, at phone to wide widths, in both views', { timeout: 120_000 }, async () => {
  // A select is as wide as its longest option unless the layout says
  // otherwise: the configuration's right column once stuck out of its panel
  // (and the window) by 20 px at every width.
  const outside = (page) => page.evaluate(() => {
    const out = [];
    for (const el of document.querySelectorAll('.panel input, .panel select, .panel button, .panel textarea')) {
      const r = el.getBoundingClientRect();
      if (r.width === 0) continue; // hidden
      const p = el.closest('.panel').getBoundingClientRect();
      if (r.right > p.right + 0.5 || r.left < p.left - 0.5) out.push(`#${el.id || el.tagName}: ${Math.round(r.left)}–${Math.round(r.right)} in ${Math.round(p.left)}–${Math.round(p.right)}`);
    }
    const de = document.documentElement;
    if (de.scrollWidth > de.clientWidth) out.push(`the page scrolls sideways: ${de.scrollWidth} > ${de.clientWidth}`);
    return out;
  });
  await withApp('?race=horizon', async (page) => {
    // A painted prior shows the paint tools in the configuration too.
    await page.selectOption('#prior', 'paint');
    assert.ok(await page.locator('#paint-brush').isVisible(), 'the paint tools show');
    for (const width of [380, 800, 1000, 1400, 1920]) {
      await page.setViewportSize({ width, height: 900 });
      await page.click('#tab-live');
      await page.waitForFunction(() => document.body.dataset.view !== 'experiments');
      assert.deepEqual(await outside(page), [], `live view, ${width} px wide`);
      await page.click('#tab-experiments');
      await page.waitForFunction(() => document.body.dataset.view === 'experiments');
      assert.deepEqual(await outside(page), [], `experiments view, ${width} px wide`);
      // The custom sweep's form, with its textarea, shows only when chosen.
      await page.selectOption('#exp-name', 'custom');
      assert.ok(await page.locator('#exp-series').isVisible(), 'the custom form shows');
      assert.deepEqual(await outside(page), [], `custom experiment, ${width} px wide`);
      await page.selectOption('#exp-name', 'priors');
    }
  });
});

test('batch trials in Web Workers: same results for any number of workers, trial 0 = the page episode', { timeout: 240_000 }, async () => {
  await withApp('?n=16&sigma=3&loops=15&belief=posterior&seed=21&autoplay=0', async (page) => {
    const batch = async () => {
      await page.evaluate(() => delete document.body.dataset.batch);
      await page.click('#batch-run');
      await page.waitForFunction(() => ['done', 'error', 'stopped'].includes(document.body.dataset.batch), null, { timeout: 120_000 });
      assert.equal(await page.evaluate(() => document.body.dataset.batch), 'done', await text(page, '#batch-progress'));
      return page.evaluate(() => window.torusTest.batch.results());
    };
    await page.fill('#batch-trials', '12');
    const one = await batch();
    assert.equal(one.length, 12);
    await page.evaluate(() => window.torusTest.batch.usePool(3));
    const three = await batch();
    assert.deepEqual(three, one);
    // Fault injection: a worker dies mid-run. The pool replaces it, re-runs
    // its trial on the fresh worker, and the results are the same.
    await page.fill('#batch-trials', '200');
    const many = await batch();
    await page.evaluate(() => delete document.body.dataset.batch);
    await page.click('#batch-run');
    // Killed in the same task as the progress is read, so surely mid-run.
    const doneAtKill = await (
      await page.waitForFunction(() => {
        const m = /^(\d+) \//.exec(document.getElementById('batch-progress').textContent);
        return m && Number(m[1]) >= 1 && window.torusTest.batch.killWorker(1) ? Number(m[1]) : false;
      }, null, { timeout: 60_000, polling: 5 })
    ).jsonValue();
    assert.ok(doneAtKill < 200, `killed mid-run (${doneAtKill} of 200 done)`);
    await page.waitForFunction(() => ['done', 'error', 'stopped'].includes(document.body.dataset.batch), null, { timeout: 120_000 });
    assert.equal(await page.evaluate(() => document.body.dataset.batch), 'done', await text(page, '#batch-progress'));
    assert.equal(await page.evaluate(() => window.torusTest.batch.replaced()), 1, 'one worker was replaced');
    assert.deepEqual(await page.evaluate(() => window.torusTest.batch.results()), many, 'a lost worker changes no result');
    await page.fill('#batch-trials', '12');
    assert.match(await page.locator('#batch-summary').innerText(), /ASOO/);
    await runToEnd(page);
    const steps = (await mainPath(page)).length - 1;
    assert.equal(one[0][0], steps, 'trial 0 of the batch is the episode on the page');
  });
});

test('copy the best screenshots to docs/', { timeout: 30_000 }, async () => {
  await mkdir(path.join(ROOT, 'docs'), { recursive: true });
  for (const name of ['default-demo', 'teaching-view', 'race-mode']) {
    const src = path.join(SHOT_DIR, `${name}.png`);
    if (existsSync(src) && process.env.UPDATE_DOCS_SCREENSHOTS) await copyFile(src, path.join(ROOT, 'docs', `${name}.png`));
  }
});
