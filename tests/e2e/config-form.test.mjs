// The configuration form generated from the engine's schema
// (www/live/config-form.js, reading entries through www/shared/schema.js),
// in Debian's Chromium: one control per parameter, by kind; every control's
// change reaches the engine as text (the URL and the run's config follow);
// hidden controls are exactly the parameters that do not apply; and the
// schema's label, group, advanced and choice_labels fields, when the engine
// sends them, shape the form. Needs `make build` first.
import assert from 'node:assert/strict';
import { existsSync, readFileSync } from 'node:fs';
import path from 'node:path';
import { after, before, test } from 'node:test';
import { ROOT, describeProblems, launchBrowser, openPage, startServer } from './harness.mjs';
import { paramEntries, paramEntry } from '../../www/shared/schema.js';

const PKG = path.join(ROOT, 'www', 'pkg');
let server;
let browser;
let engine;

before(async () => {
  assert.ok(existsSync(path.join(PKG, 'torus_search.js')), 'www/pkg is missing: run `make build` first');
  engine = await import(path.join(PKG, 'torus_search.js'));
  engine.initSync({ module: readFileSync(path.join(PKG, 'torus_search_bg.wasm')) });
  server = await startServer(ROOT);
  browser = await launchBrowser({ viewport: { width: 1280, height: 900 } });
});

after(async () => {
  await browser?.close();
  await server?.close();
});

/** Opens the page at `query`, waits for its runs, runs fn(page); fails on any reported problem. */
async function withApp(query, fn) {
  const { page, report } = await openPage(browser.context, `${server.url}${query}`);
  try {
    await page.waitForFunction(() => window.torusTest?.runs().length, null, { timeout: 30_000 });
    await fn(page);
    assert.equal(describeProblems(report), '', 'the page reported problems');
  } finally {
    await page.close();
  }
}

/** What the form shows, per generated field: key, kind, control tag and type, label, description, hidden, disabled. */
const readForm = (page) => page.evaluate(() => [...document.querySelectorAll('#config-fields [data-param]')].map((f) => {
  const el = document.getElementById(f.dataset.param);
  const described = el?.getAttribute('aria-describedby');
  return {
    key: f.dataset.param,
    kind: f.dataset.kind,
    inside: !!el && f.contains(el),
    tag: el?.tagName.toLowerCase(),
    type: el?.type,
    options: el?.tagName === 'SELECT' ? [...el.options].map((o) => [o.value, o.textContent]) : null,
    label: el?.labels?.[0]?.textContent.trim() ?? null,
    description: described ? document.getElementById(described)?.textContent : null,
    hidden: f.hidden || !!f.closest('[hidden]'),
    disabled: !!el?.disabled,
  };
}));

// Configurations that, together, put every parameter to use at least once.
const BASES = [
  '?autoplay=0&n=15&loops=20&seed=5',
  '?autoplay=0&n=15&loops=20&seed=5&variant=pomcp',
  '?autoplay=0&n=15&loops=20&seed=5&variant=code&rollout=levy',
  '?autoplay=0&n=15&loops=20&seed=5&variant=tree&rollout=greedy&ms=5',
  '?autoplay=0&n=15&seed=5&searcher=beam',
  '?autoplay=0&n=15&seed=5&searcher=improve',
  '?autoplay=0&n=15&seed=5&searcher=horizon',
  '?autoplay=0&n=15&seed=5&searcher=sweep',
  '?autoplay=0&n=15&seed=5&searcher=rw&target=3,4',
];

/** The order the form lists parameters in: the main settings, then the
 * advanced ones; within each, by group in order of first appearance, and
 * within a group in the schema's order. */
function formOrder(schema) {
  const out = [];
  for (const advanced of [false, true]) {
    const ps = schema.params.filter((p) => p.advanced === advanced);
    const groups = [...new Set(ps.map((p) => p.group))];
    for (const g of groups) out.push(...ps.filter((p) => p.group === g).map((p) => p.key));
  }
  return out;
}

test('schema entries: every parameter has the engine\'s label, group and advanced flag, and choices their labels', () => {
  const schema = engine.schema();
  const groups = schema.groups.map((g) => g.name);
  for (const e of paramEntries(schema)) {
    assert.ok(typeof e.label === 'string' && e.label.length > 0, `${e.key}: a label`);
    assert.ok(groups.includes(e.group), `${e.key}: group ${e.group} is one of the schema's groups`);
    assert.equal(typeof e.advanced, 'boolean', `${e.key}: advanced`);
    if (e.choice_labels) assert.equal(e.choice_labels.length, e.choices.length, `${e.key}: a label per choice`);
    for (const c of e.choices ?? []) assert.ok(e.choiceLabel(c), `${e.key}: ${c} has a label`);
  }
  const final = paramEntries(schema).find((e) => e.key === 'final');
  assert.equal(final.choiceLabel('visits'), 'most picks');
  assert.equal(paramEntry({ key: 'p', kind: 'choice', choices: ['a'], choice_labels: { a: 'A' } }, schema).choiceLabel('a'), 'A');
  // The searcher choices are labelled by the registry.
  const searcher = paramEntries(schema).find((e) => e.key === 'searcher');
  for (const s of schema.searchers) assert.equal(searcher.choiceLabel(s.name), s.label);
});

test('every parameter of the schema has exactly one generated control, by its kind, labelled and described', { timeout: 60_000 }, async () => {
  const schema = engine.schema();
  await withApp('?autoplay=0', async (page) => {
    const fields = await readForm(page);
    assert.deepEqual(fields.map((f) => f.key), formOrder(schema), 'one field per parameter, main settings then advanced, by group, in the schema\'s order');
    for (const e of paramEntries(schema)) {
      const f = fields.find((x) => x.key === e.key);
      const where = `${e.key} (${e.kind})`;
      assert.ok(f.inside, `${where}: the control with id ${e.key} is in its field`);
      assert.equal(await page.locator(`[id="${e.key}"]`).count(), 1, `${where}: one element has the id`);
      assert.equal(f.label, e.label, `${where}: labelled by the schema's label`);
      assert.equal(f.description, e.help, `${where}: described by the schema's help`);
      const want = {
        int: ['input', ['number', 'range', 'text']],
        float: ['input', ['number', 'text']],
        optfloat: ['input', ['number']],
        choice: ['select', ['select-one']],
        bool: ['input', ['checkbox']],
        cell: ['input', ['text']],
        optcell: ['input', ['text']],
        paint: ['button', ['button']],
      }[e.kind];
      assert.ok(want, `${where}: a kind the form knows`);
      assert.equal(f.tag, want[0], where);
      assert.ok(want[1].includes(f.type), `${where}: type ${f.type}`);
      if (e.kind === 'choice') assert.deepEqual(f.options, e.choices.map((c) => [c, e.choiceLabel(c)]), `${where}: its choices`);
    }
  });
});

test('a control\'s change reaches the engine as text: the URL and the run\'s config follow', { timeout: 300_000 }, async () => {
  const schema = engine.schema();
  const entries = new Map(paramEntries(schema).map((e) => [e.key, e]));
  const tried = new Set();
  for (const base of BASES) {
    await withApp(base, async (page) => {
      const shown = (await readForm(page)).filter((f) => !f.hidden && f.kind !== 'paint').map((f) => f.key);
      for (const key of shown) {
        if (tried.has(key)) continue;
        tried.add(key);
        const config = await page.evaluate(() => window.torusTest.runs()[0].config);
        const before = new Map(engine.configParams(config, true));
        const raw = newValue(entries.get(key), before.get(key));
        // What the engine makes of that text, from the same config.
        const want = new Map(engine.configParams(engine.setParam(config, key, raw), true)).get(key);
        assert.notEqual(want, before.get(key), `${key}: the test's new value ${raw} changes it`);
        await setControl(page, entries.get(key), raw, want);
        // And back, through the same control: the run is the base's again.
        await setControl(page, entries.get(key), before.get(key), before.get(key));
        const back = await page.evaluate(() => window.torusTest.runs()[0].config);
        assert.deepEqual(new Map(engine.configParams(back, true)), before, `${key}: set back to ${before.get(key)}, the config is the base's`);
      }
    });
  }
  const untried = schema.params.filter((p) => p.kind !== 'paint' && !tried.has(p.key)).map((p) => p.key);
  assert.deepEqual(untried, [], 'every parameter but the painting was changed through its control (painting: page.test.mjs)');
});

/**
 * Sets parameter `e`'s control to `raw` as a user does (a checkbox: ticked
 * for a true value), then waits until the URL and the fresh run have
 * `want`, the engine's text for it.
 */
async function setControl(page, e, raw, want) {
  await page.evaluate(([k, v]) => {
    const el = document.getElementById(k);
    if (el.type === 'checkbox') el.checked = v === '1';
    else el.value = v;
    el.dispatchEvent(new Event('change'));
  }, [e.key, e.kind === 'optfloat' && Number(raw) === 0 ? '' : raw]);
  // The URL leaves out a default value.
  const inUrl = want === e.default ? null : want;
  await page.waitForFunction(([k, w]) => new URLSearchParams(location.search).get(k) === w, [e.key, inUrl], { timeout: 10_000 })
    .catch(async () => assert.fail(`${e.key}=${raw}: the URL is ${await page.evaluate(() => location.search)}, message ${await page.locator('#message').textContent()}`));
  const got = await page.evaluate(async () => {
    await window.torusTest.ready();
    return window.torusTest.runs()[0].config;
  });
  assert.equal(new Map(engine.configParams(got, true)).get(e.key), want, `${e.key}: the run's config has ${e.key}=${want}`);
}

/** A valid new value for a parameter, as text. */
function newValue(e, now) {
  switch (e.kind) {
    case 'choice':
      return e.choices.find((c) => c !== now && c !== 'paint');
    case 'bool':
      return now === '1' ? '0' : '1';
    case 'cell':
    case 'optcell':
      return now === '2,3' ? '3,2' : '2,3';
    case 'optfloat':
      return Number(now) === 25 ? '30' : '25';
    default: {
      const v = Number(now);
      const max = Math.min(Number(e.max), e.key === 'n' ? 30 : Infinity);
      if (e.kind === 'int') return String(v + 1 <= max ? v + 1 : v - 1);
      return String(v + 0.5 <= max ? v + 0.5 : v / 2);
    }
  }
}

test('hidden controls are exactly the parameters that do not apply, and they are disabled', { timeout: 180_000 }, async () => {
  const schema = engine.schema();
  for (const base of [...BASES, '?autoplay=0&prior=uniform', '?autoplay=0&searcher=levy&known=1']) {
    await withApp(base, async (page) => {
      // The running config, through the engine, says which apply.
      const config = await page.evaluate(() => window.torusTest.runs()[0].config);
      const applies = new Set(engine.applicable(config));
      // Advanced settings are folded away; open them to see every control.
      await page.locator('#more-settings').evaluate((d) => { d.open = true; });
      const fields = await readForm(page);
      const hidden = fields.filter((f) => f.hidden).map((f) => f.key);
      assert.deepEqual(hidden.sort(), schema.params.map((p) => p.key).filter((k) => !applies.has(k)).sort(), `${base}: hidden controls`);
      for (const f of fields) {
        assert.equal(f.disabled, f.hidden, `${base}: ${f.key} is ${f.hidden ? 'hidden but enabled' : 'shown but disabled'}`);
        if (!f.hidden) assert.ok(await page.locator(`[id="${f.key}"]`).isVisible(), `${base}: ${f.key} is visible`);
      }
    });
  }
});

test('the engine\'s groups, advanced flags, labels and choice labels shape the form', { timeout: 60_000 }, async () => {
  await withApp('?autoplay=0', async (page) => {
    const out = await page.evaluate(async () => {
      const { ConfigForm } = await import('./www/live/config-form.js');
      const box = document.createElement('div');
      const preset = document.createElement('select');
      document.body.append(box, preset);
      const schema = {
        presets: [],
        preset_key: 'preset',
        searchers: [],
        groups: [{ name: 'mcts', label: 'Tree search' }],
        params: [
          { key: 't_n', kind: 'int', min: '3', max: '1024', help: 'side', allowed: 'an integer', label: 'Lattice side N', group: 'game' },
          { key: 't_c', kind: 'float', min: '0', max: '10', help: 'explore', allowed: 'a number', label: 'Exploration c', group: 'mcts' },
          { key: 't_final', kind: 'choice', choices: ['visits', 'uct'], help: 'rule', allowed: 'one of', group: 'mcts', advanced: true, choice_labels: ['most picks', 'best UCT'] },
        ],
      };
      const sent = [];
      const form = new ConfigForm({ schema, onParam: (k, v) => sent.push([k, v]), onPaintClear: () => {}, box, preset });
      form.sync({ text: new Map([['t_n', '7'], ['t_c', '2'], ['t_final', 'uct']]), applicable: new Set(['t_n', 't_c', 't_final']), preset: null });
      const groupOf = (key) => box.querySelector(`[data-param="${key}"]`).closest('fieldset');
      const more = box.querySelector('details.more');
      const fin = document.getElementById('t_final');
      fin.value = 'visits';
      fin.dispatchEvent(new Event('change'));
      const res = {
        legends: [...box.querySelectorAll('fieldset > legend')].map((l) => [l.textContent, l.hidden]),
        groups: ['t_n', 't_c', 't_final'].map((k) => groupOf(k).dataset.group),
        inMore: ['t_n', 't_c', 't_final'].map((k) => more.contains(groupOf(k))),
        moreOpen: more.open,
        moreHidden: more.hidden,
        labels: ['t_n', 't_c'].map((k) => document.getElementById(k).labels[0].textContent),
        finals: [...fin.options].map((o) => o.textContent),
        sent,
      };
      box.remove();
      preset.remove();
      return res;
    });
    assert.deepEqual(out.legends, [['game', false], ['Tree search', false], ['Tree search', false]]);
    assert.deepEqual(out.groups, ['game', 'mcts', 'mcts']);
    assert.deepEqual(out.inMore, [false, false, true], 'advanced parameters go under More settings');
    assert.equal(out.moreOpen, false, 'More settings starts collapsed');
    assert.equal(out.moreHidden, false, 'More settings shows when an advanced parameter applies');
    assert.deepEqual(out.labels, ['Lattice side N', 'Exploration c']);
    assert.deepEqual(out.finals, ['most picks', 'best UCT']);
    assert.deepEqual(out.sent, [['t_final', 'visits']], 'a change is sent as text');
  });
});
