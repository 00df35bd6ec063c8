// End-to-end tests of teaching MCTS on the page (issue 44): a loop a phase
// at a time with its narration, the decision panel's two highlights, going
// back over the timeline (buttons, keys, scrubber, seek), and the tree the
// engine reports against the decision panel. Helpers: page-helpers.mjs.
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { expectText, mainPath, state, text, useApp, withApp } from './page-helpers.mjs';

useApp();

const ORDER = ['select', 'expand', 'rollout', 'backup'];
const WORDS = { select: 'Select:', expand: 'Expand:', rollout: 'Roll out:', backup: 'Back up:' };
const point = (page) => page.evaluate(() => {
  const t = window.torusTest.timeline();
  return t && { move: t.move, loop: t.loop, phase: t.phase };
});
/** Waits until the page shows timeline point `want` (the panels draw on the next animation frame). */
async function atPoint(page, want) {
  await page.waitForFunction((w) => {
    const t = window.torusTest.timeline();
    return t && t.move === w.move && t.loop === w.loop && t.phase === (w.phase ?? null);
  }, want, { timeout: 10_000 }).catch(async () => assert.deepEqual(await point(page), { phase: null, ...want }));
}

test('a loop phase by phase: the strip, the narration and the decision panel follow the engine', { timeout: 90_000 }, async () => {
  await withApp('?autoplay=0&n=11&sigma=2&loops=20&seed=3&start=2,2', async (page) => {
    assert.equal(await page.evaluate(() => window.torusTest.phase()), null);
    for (let i = 0; i < 12; i++) {
      // Button, key p, and Shift+→ in turn.
      if (i % 3 === 0) await page.click('#step-phase');
      else if (i % 3 === 1) await page.keyboard.press('p');
      else await page.keyboard.press('Shift+ArrowRight');
      const want = ORDER[i % 4];
      await atPoint(page, { move: 0, loop: Math.floor(i / 4), phase: want });
      assert.equal(await page.evaluate(() => window.torusTest.phase()), want);
      await page.waitForFunction((w) => document.getElementById('narration').textContent.startsWith(w), WORDS[want], { timeout: 5_000 });
      assert.equal(await page.locator('#phase-strip li.now').getAttribute('data-phase'), want);
    }
    const said = await text(page, '#narration');
    assert.match(said, /^Back up: reward \d/);
    assert.match(said, /N \d+ → \d+/);
    await page.click('#step-phase');
    await page.waitForFunction(() => /so the loop tries (Up|Right|Down|Left)/.test(document.getElementById('narration').textContent), null, { timeout: 5_000 });
    // The decision panel marks the final rule's move (◆) and the highest UCT (▲) apart, and explains pass-through visits.
    const note = await text(page, '#decision-note');
    assert.match(note, /◆ If the decision ended now, the final rule/);
    assert.match(note, /▲ Highest UCT: /);
    assert.match(note, /pass-through visits/);
    assert.ok(await page.locator('#decision tr.uct-best').count() >= 1);
    assert.ok(await page.locator('#decision tr.chosen').count() >= 1);
    // One phase every 0.5 s: a second of play advances a few phases, not many loops.
    const before = await point(page);
    await page.evaluate(() => window.torusTest.dispatch({ type: 'speed', speed: '0.5s' }));
    await page.click('#play');
    await page.waitForFunction((b) => {
      const t = window.torusTest.timeline();
      return t.loop !== b.loop || t.phase !== b.phase;
    }, before, { timeout: 10_000 });
    await page.waitForTimeout(1000);
    await page.click('#play');
    const after = await point(page);
    assert.equal(after.move, 0);
    assert.ok(after.loop - before.loop <= 2, `${JSON.stringify(before)} → ${JSON.stringify(after)}: phases, not loops`);
  });
});

test('going back: buttons, keys and the scrubber; seeking back then forward shows the same run', { timeout: 120_000 }, async () => {
  await withApp('?autoplay=0&n=16&sigma=3&loops=10&seed=4&variant=tree', async (page) => {
    for (let i = 0; i < 6; i++) await page.click('#step-move');
    for (let i = 0; i < 5; i++) await page.click('#step-phase');
    await atPoint(page, { move: 6, loop: 1, phase: 'select' });
    const forward = await mainPath(page);
    const note = await text(page, '#decision-note');
    const said = await text(page, '#narration');
    assert.equal(forward.length, 7);
    // Seek into the middle of a loop.
    assert.deepEqual(await page.evaluate(() => window.torusTest.seek({ move: 2, loop: 3, phase: 'rollout' })), { ok: true });
    await atPoint(page, { move: 2, loop: 3, phase: 'rollout' });
    assert.deepEqual(await mainPath(page), forward.slice(0, 3));
    assert.equal(await page.locator('#phase-strip li.now').getAttribute('data-phase'), 'rollout');
    // End: the furthest point, the same path, panel and narration.
    await page.keyboard.press('End');
    await atPoint(page, { move: 6, loop: 1, phase: 'select' });
    assert.deepEqual(await mainPath(page), forward);
    await expectText(page, '#decision-note', note);
    await expectText(page, '#narration', said);
    // Back a move (to this decision's start, then the one before), a loop, a phase.
    await page.keyboard.press('ArrowLeft');
    await atPoint(page, { move: 6, loop: 0 });
    await page.click('#back-move');
    await atPoint(page, { move: 5, loop: 0 });
    await page.keyboard.press('Control+ArrowLeft');
    await atPoint(page, { move: 4, loop: 9 });
    await page.keyboard.press('Shift+ArrowLeft');
    await atPoint(page, { move: 4, loop: 8, phase: 'rollout' });
    await page.click('#back-phase');
    await atPoint(page, { move: 4, loop: 8, phase: 'expand' });
    // Forward again from there: the same moves as before.
    await page.click('#step-move');
    await atPoint(page, { move: 5, loop: 0 });
    assert.deepEqual(await mainPath(page), forward.slice(0, 6));
    // The scrubber seeks to a move; Home to the start.
    await page.locator('#scrub').fill('3');
    await atPoint(page, { move: 3, loop: 0 });
    await page.locator('#view-0').focus();
    await page.keyboard.press('Home');
    await atPoint(page, { move: 0, loop: 0 });
    assert.equal((await mainPath(page)).length, 1);
    // A seek past the end: a message naming the range; the run stays where it was.
    const answer = await page.evaluate(() => window.torusTest.seek({ move: 40 }));
    assert.equal(answer.ok, false);
    assert.match(answer.error, /move 40.*past the end.*up to move 6, loop 1, phase select/);
    assert.match(await text(page, '#message'), /past the end of the run so far/);
    assert.equal(await state(page), 'paused');
    await atPoint(page, { move: 0, loop: 0 });
    assert.equal(await text(page, '#tl-point'), 'move 0, loop 0');
    assert.equal(await page.locator('#tl-end').getAttribute('aria-label'), 'To the furthest point reached: move 6, loop 1, Select (End)');
  });
});

test('the tree the engine reports matches the decision panel', { timeout: 60_000 }, async () => {
  await withApp('?autoplay=0&n=16&sigma=3&loops=30&seed=4&variant=tree', async (page) => {
    for (let i = 0; i < 9; i++) await page.click('#step-loop');
    await page.waitForFunction(() => window.torusTest.runs()[0].work >= 9, null, { timeout: 10_000 });
    const tree = await page.evaluate(() => window.torusTest.tree());
    assert.equal(tree.shape, 'tree');
    const root = tree.nodes[0];
    assert.equal(root.parent, null);
    assert.equal(root.visits, 9);
    const children = tree.nodes.filter((n) => n.parent === 0);
    assert.equal(children.reduce((a, n) => a + n.visits, 0), 9);
    // The decision panel's visits column, row by move.
    await page.waitForFunction(() => /N\(v\) = 9,/.test(document.getElementById('decision-note').textContent), null, { timeout: 5_000 });
    const shown = await page.evaluate(() => [...document.querySelectorAll('#decision tbody tr')].map((tr) => Number(tr.cells[1].firstChild.nodeValue)));
    const byMove = { up: 0, right: 1, down: 2, left: 3 };
    for (const n of children) assert.equal(shown[byMove[n.move]], n.visits, `${n.move}`);
  });
});

test('the tree view beside the lattice: linked both ways, cut by visits or to the best line; a focus gone gets a message', { timeout: 90_000 }, async () => {
  await withApp('?autoplay=0&n=11&sigma=2&loops=40&seed=3&start=2,2&variant=tree', async (page) => {
    for (let i = 0; i < 20; i++) await page.click('#step-loop');
    for (let i = 0; i < 3; i++) await page.click('#step-phase');
    // The root, 20 loops' nodes and the one just expanded, drawn (read in the same turn).
    const ready = () => page.waitForFunction(() => {
      const t = window.torusTest.treeView();
      return t.shown && t.nodes === 22 && t.at ? t : null;
    }, null, { timeout: 10_000 }).then((h) => h.jsonValue());
    await ready();
    // Beside the board at this size: to its right, its top within the board's height.
    const [board, panel] = await page.evaluate(() => ['view-0', 'tree-canvas'].map((id) => document.getElementById(id).getBoundingClientRect().toJSON()));
    assert.ok(panel.left >= board.right && panel.top < board.bottom, JSON.stringify({ board, panel }));
    await page.waitForTimeout(300); // the rollout's reveal and any fetch under way settle
    const before = await ready();
    // Hovering a node: its words, with the engine's UCT split for a root child, and its line on the lattice.
    await page.mouse.move(...before.at);
    await page.waitForFunction(() => window.torusTest.drawn().marks.includes('treeLine'), null, { timeout: 5_000 });
    assert.match(await text(page, '#tree-info'), /^(Up|Right|Down|Left) \(depth 1\), cell \(\d+, \d+\): N = \d+, Q\/N = [\d.]+, picked \d+ times this decision\. UCT = [\d.]+ \+ [\d.]+ = [\d.]+\.$/);
    await page.waitForFunction(() => window.torusTest.legend().marks.includes('treeLine'), null, { timeout: 5_000 });
    // A depth-2 node: its UCT split as its parent's selection weighs it, the engine's numbers.
    const engineTree = await page.evaluate(() => window.torusTest.tree());
    const deep = engineTree.nodes.findIndex((n) => n.depth === 2 && n.visits > 0);
    assert.ok(deep > 0, 'a visited depth-2 node');
    const node = engineTree.nodes[deep];
    const at = await page.evaluate((i) => window.torusTest.treeView(i).at, deep);
    await page.mouse.move(...at);
    await page.waitForFunction((i) => window.torusTest.treeView().hover === i, deep, { timeout: 5_000 });
    const words = await text(page, '#tree-info');
    const m = /^(Up|Right|Down|Left) → (Up|Right|Down|Left) \(depth 2\), cell \(\d+, \d+\): N = (\d+), Q\/N = [\d.]+\. UCT = ([\d.]+) \+ ([\d.]+) = ([\d.]+)\.$/.exec(words);
    assert.ok(m, words);
    assert.equal(Number(m[3]), node.visits);
    // fmtNum shows 4 decimals: the page's figures are the engine's, rounded.
    for (const [shown, want] of [[m[4], node.mean], [m[5], node.explore], [m[6], node.uct]]) assert.ok(Math.abs(Number(shown) - want) <= 5e-5, `${shown} against ${want}`);
    assert.equal(node.uct, node.mean + node.explore);
    // Its parent's visits, not the root's, are under the log.
    const parent = engineTree.nodes.find((n) => n.id === node.parent);
    const c = await page.evaluate(() => window.torusTest.runs()[0].config.c);
    assert.ok(Math.abs(node.explore - c * Math.sqrt(Math.log(parent.visits) / node.visits)) < 1e-9, JSON.stringify({ node, parent, c }));
    // Hovering that node's cell on the lattice marks the nodes that reach it (the node among them).
    const cellPoint = await page.evaluate((cell) => {
      const c = document.getElementById('view-0').getBoundingClientRect();
      const n = window.torusTest.runs()[0].n;
      return [c.left + ((cell % n) + 0.5) * (c.width / n), c.top + (Math.floor(cell / n) + 0.5) * (c.height / n)];
    }, before.cell);
    await page.mouse.move(...cellPoint);
    await page.waitForFunction(() => window.torusTest.treeView().marked.includes(1), null, { timeout: 5_000 });
    assert.match(await text(page, '#tree-info'), /nodes? of the tree reach/);
    // A visit threshold and the best line cut the tree; the engine says how many are shown.
    await page.fill('#tree-min', '3');
    await page.locator('#tree-min').dispatchEvent('change');
    await page.waitForFunction((n) => window.torusTest.treeView().nodes < n, before.nodes, { timeout: 5_000 });
    const cut = await page.evaluate(() => window.torusTest.tree({ min_visits: 3 }));
    assert.ok(cut.nodes.every((n, i) => i === 0 || n.visits >= 3));
    assert.equal(await page.evaluate(() => window.torusTest.treeView().nodes), cut.nodes.length);
    assert.match(await text(page, '#tree-count'), new RegExp(`^${cut.nodes.length} of ${before.nodes} nodes shown$`));
    await page.fill('#tree-min', '0');
    await page.locator('#tree-min').dispatchEvent('change');
    await page.check('#tree-best');
    const best = await page.evaluate(() => window.torusTest.tree({ focus: 'best' }));
    await page.waitForFunction((n) => window.torusTest.treeView().nodes === n, best.nodes.length, { timeout: 5_000 });
    // A focus on a node the tree does not hold: a message, the whole tree again, the run as it was.
    const path = await mainPath(page);
    await page.evaluate(() => window.torusTest.treeFocus(999999));
    await page.waitForFunction(() => /Tree view: tree focus: node 999999 is not in the tree/.test(document.getElementById('message').textContent), null, { timeout: 5_000 });
    await page.waitForFunction(() => window.torusTest.treeView().focus === 'all', null, { timeout: 5_000 });
    assert.equal(await state(page), 'paused');
    assert.deepEqual(await mainPath(page), path);
  });
});

test('race any two configurations: titles name what differs, and a paired batch on the same targets', { timeout: 120_000 }, async () => {
  await withApp('?autoplay=0&n=16&sigma=3&loops=20&seed=4&vs=rollout%3Dlevy', async (page) => {
    const runs = await page.evaluate(() => window.torusTest.runs());
    assert.equal(runs.length, 2);
    assert.deepEqual([runs[0].config.rollout, runs[1].config.rollout], ['rw', 'levy']);
    assert.equal(runs[0].target, runs[1].target);
    const titles = await page.evaluate(() => [...document.querySelectorAll('.board-title')].map((e) => e.textContent));
    assert.deepEqual(titles, ['A: rollout=rw — MCTS cells · rw rollouts · L=20', 'B: rollout=levy — MCTS cells · levy rollouts · L=20']);
    await page.fill('#batch-trials', '6');
    await page.fill('#batch-cap', '400');
    await page.click('#batch-run');
    await page.waitForFunction(() => document.body.dataset.batch === 'done', null, { timeout: 90_000 });
    const p = await page.evaluate(() => window.torusTest.batch.paired());
    assert.equal(p.trials, 6);
    assert.equal(p.a_wins + p.ties + p.b_wins, 6);
    // The engine's own summary of the same pairs, run here.
    const again = await page.evaluate(() => {
      const [a, b] = window.torusTest.runs().map((r) => ({ ...r.config, step_cap: 400, keep_traces: 0 }));
      const e = window.torusTest.engine;
      const flat = [];
      for (let i = 0; i < 6; i++) flat.push(...e.runPairedTrial(a, b, i));
      return e.summarizePaired(Float64Array.from(flat));
    });
    assert.deepEqual(p, again);
    assert.ok(await page.locator('#batch-paired').isVisible());
    assert.match(await text(page, '#batch-paired-note'), /^Race: A against B on the same 6 targets: /);
    assert.match(await page.locator('#batch-paired').innerText(), /A faster \/ tie \/ B faster\s+\d+ \/ \d+ \/ \d+/);
    // Another change through the form: the same searcher with another c.
    await page.fill('#vs', 'c=0.5');
    await page.locator('#vs').dispatchEvent('change');
    await page.waitForFunction(() => window.torusTest.runs()[1]?.config.c === 0.5, null, { timeout: 10_000 });
    assert.match(await page.evaluate(() => location.search), /vs=c%3D0\.5/);
    await expectText(page, '#board-1 .board-title', 'B: c=0.5 — MCTS cells · rw rollouts · L=20');
  });
  await withApp('?autoplay=0&n=16&vs=cc%3D1', async (page) => {
    assert.match(await text(page, '#message'), /Invalid vs="cc=1": .*got cc\. Using no changes\./);
    assert.equal((await page.evaluate(() => window.torusTest.runs())).length, 1);
  });
});

test('in a race the tree view shows either board\'s tree: an A/B switch by keys or taps, in the link, the lattice linked to that board', { timeout: 120_000 }, async () => {
  let link;
  let linkedWork;
  // A makes a move every 5 loops, B every 40: after 12 loops only B is still in its first decision.
  await withApp('?autoplay=0&n=16&sigma=3&loops=5&seed=4&variant=tree&vs=loops%3D40', async (page) => {
    for (let i = 0; i < 12; i++) await page.click('#step-loop');
    await page.waitForFunction(() => window.torusTest.runs()[1].work >= 12, null, { timeout: 10_000 });
    const workB = (await page.evaluate(() => window.torusTest.runs()))[1].work;
    linkedWork = workB;
    const [treeA, treeB] = await page.evaluate(async () => [await window.torusTest.tree({}, 0), await window.torusTest.tree({}, 1)]);
    // Under `tree` a first decision's root has one visit per loop; A's kept subtree has fewer.
    assert.equal(treeB.nodes[0].visits, workB);
    assert.notEqual(treeA.nodes[0].visits, workB);
    const shows = (board, rootVisits) => page.waitForFunction(([b, v]) => {
      const t = window.torusTest.treeView();
      return t.shown && t.board === b && t.rootVisits === v;
    }, [board, rootVisits], { timeout: 10_000 });
    await shows(0, treeA.nodes[0].visits);
    await page.locator('#tree-canvas').scrollIntoViewIfNeeded();
    assert.ok(await page.locator('#tree-board').isVisible());
    assert.equal(await page.getAttribute('#tree-board-0', 'aria-pressed'), 'true');
    // The switch by keyboard: B's tree, its root's visits B's loops, and the link says so.
    await page.focus('#tree-board-1');
    await page.keyboard.press('Enter');
    await shows(1, workB);
    assert.equal(await page.getAttribute('#tree-board-1', 'aria-pressed'), 'true');
    assert.equal(await page.evaluate(() => window.torusTest.treeView().nodes), treeB.nodes.length);
    await page.waitForFunction(() => /[?&]tree=b(&|$)/.test(location.search), null, { timeout: 5_000 });
    // Hovering a node of B's tree draws its line on board B, not A.
    // Where node 1 is drawn and its cell, read in one turn (a fetch could replace the layout between two reads).
    await page.locator('#tree-canvas').scrollIntoViewIfNeeded();
    const { at, cell } = await page.waitForFunction(() => {
      const t = window.torusTest.treeView();
      return t.board === 1 && t.at ? t : null;
    }, null, { timeout: 5_000 }).then((h) => h.jsonValue());
    await page.mouse.move(...at);
    await page.waitForFunction(() => window.torusTest.drawn(1).marks.includes('treeLine'), null, { timeout: 5_000 });
    assert.ok(!(await page.evaluate(() => window.torusTest.drawn(0).marks)).includes('treeLine'));
    // Hovering that node's cell on board B marks the nodes of B's tree that reach it.
    const cellPoint = await page.evaluate((c) => {
      const r = document.getElementById('view-1').getBoundingClientRect();
      const n = window.torusTest.runs()[1].n;
      return [r.left + ((c % n) + 0.5) * (r.width / n), r.top + (Math.floor(c / n) + 0.5) * (r.height / n)];
    }, cell);
    await page.mouse.move(...cellPoint);
    await page.waitForFunction(() => window.torusTest.treeView().marked.includes(1), null, { timeout: 5_000 });
    // B's best line goes into the link with the board.
    await page.check('#tree-best');
    await page.waitForFunction(() => /[?&]tree=b\.best(&|$)/.test(location.search), null, { timeout: 5_000 });
    link = await page.evaluate(() => location.href);
  });
  // The link reopens on B's best line; a tap on A goes back to A's tree.
  await withApp(link.slice(link.indexOf('?')), async (page) => {
    // Once the link's point is replayed: B's tree is read there, not at move 0.
    await page.waitForFunction((w) => {
      const t = window.torusTest.timeline();
      return document.body.dataset.state === 'paused' && window.torusTest.runs()[1]?.work === w && t;
    }, linkedWork, { timeout: 30_000 });
    const bestB = await page.evaluate(() => window.torusTest.tree({ focus: 'best' }, 1));
    await page.waitForFunction((n) => {
      const t = window.torusTest.treeView();
      return t.shown && t.board === 1 && t.focus === 'best' && t.nodes === n;
    }, bestB.nodes.length, { timeout: 15_000 });
    await page.locator('#tree-board-0').scrollIntoViewIfNeeded();
    await page.click('#tree-board-0');
    await page.waitForFunction(() => window.torusTest.treeView().board === 0 && /[?&]tree=best(&|$)/.test(location.search), null, { timeout: 5_000 });
  });
  // Board B without a race: a message naming the value, and A's tree.
  await withApp('?autoplay=0&n=12&variant=tree&tree=b.best', async (page) => {
    await page.waitForFunction(() => /Tree view: tree=b\.best shows board B's tree, but there is no race/.test(document.getElementById('message').textContent), null, { timeout: 10_000 });
    await page.waitForFunction(() => window.torusTest.treeView().board === 0 && /[?&]tree=best(&|$)/.test(location.search), null, { timeout: 5_000 });
    assert.ok(await page.locator('#tree-board').isHidden());
  });
});

test('a link holds the whole picture: layers, the race, the point in the run; reopened paused, and Restart does not play', { timeout: 120_000 }, async () => {
  let link;
  let want;
  await withApp('?autoplay=0&n=16&sigma=3&loops=10&seed=4&variant=tree&vs=c%3D0.5', async (page) => {
    for (let i = 0; i < 4; i++) await page.click('#step-move');
    for (let i = 0; i < 6; i++) await page.click('#step-phase');
    await atPoint(page, { move: 4, loop: 1, phase: 'expand' });
    await page.click('#layer-visits');
    await page.click('#layer-path');
    await page.check('#tree-best');
    await page.waitForFunction(() => /at=4\.1\.expand/.test(location.search) && /tree=best/.test(location.search), null, { timeout: 5_000 });
    link = await page.evaluate(() => location.href);
    want = await page.evaluate(() => ({
      runs: window.torusTest.runs().map((r) => ({ config: r.config, steps: r.steps })),
      paths: [window.torusTest.path(0), window.torusTest.path(1)],
      layers: window.torusTest.drawn().layers,
      narration: window.torusTest.narration(),
      note: document.getElementById('decision-note').textContent,
    }));
  });
  assert.match(link, /vs=c%3D0\.5/);
  assert.match(link, /show=[^&]*visits/);
  await withApp(link.slice(link.indexOf('?')), async (page) => {
    await atPoint(page, { move: 4, loop: 1, phase: 'expand' });
    assert.equal(await state(page), 'paused');
    const got = await page.evaluate(() => ({
      runs: window.torusTest.runs().map((r) => ({ config: r.config, steps: r.steps })),
      paths: [window.torusTest.path(0), window.torusTest.path(1)],
      layers: window.torusTest.drawn().layers,
    }));
    assert.deepEqual(got, { runs: want.runs, paths: want.paths, layers: want.layers });
    assert.ok(!(await page.isChecked('#layer-path')));
    assert.ok(await page.isChecked('#tree-best'));
    assert.equal(await page.evaluate(() => window.torusTest.treeView().focus), 'best');
    await expectText(page, '#narration', want.narration);
    await expectText(page, '#decision-note', want.note);
    // Restart keeps it waiting: a link that shows a stopped run never plays by itself.
    await page.keyboard.press('r');
    await page.waitForFunction(() => window.torusTest.resets() > 1 && window.torusTest.timeline()?.move === 0, null, { timeout: 10_000 });
    await page.waitForTimeout(300);
    assert.equal(await state(page), 'paused');
    assert.equal((await mainPath(page)).length, 1);
  });
  // A point the run never reaches: the engine's message, the run at its end.
  await withApp('?n=12&sigma=2&loops=10&seed=2&at=900', async (page) => {
    await page.waitForFunction(() => /Could not open the run at at=900: seek to move 900/.test(document.getElementById('message').textContent), null, { timeout: 30_000 });
    assert.notEqual(await state(page), 'running');
  });
});
