// Unit tests of the Experiments view's pure modules, in Node with the real
// engine: the experiment's URL state (www/shared/url-state.js), the chunk plan and
// the row layout of a run (www/experiments/runner.js).
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import path from 'node:path';
import { test } from 'node:test';
import { fileURLToPath } from 'node:url';
import {
  CUSTOM, defaultExperiment, experimentSpec, formatSeries, formatSweep, parsePairs, parseSeries, parseSweep,
  presetChoices, readExperimentUrl, splitView, writeExperimentUrl,
} from '../../www/shared/url-state.js';
import { chunkPlan } from '../../www/experiments/runner.js';

const PKG = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../../www/pkg');
const engine = await import(path.join(PKG, 'torus_search.js'));
engine.initSync({ module: readFileSync(path.join(PKG, 'torus_search_bg.wasm')) });
const schema = engine.schema();
const list = engine.experimentList();
const presets = presetChoices(engine, schema, list);
const read = (q) => readExperimentUrl(engine, schema, q, list, presets);

test('the view is split off the query; a bad view is reported and the live view used', () => {
  assert.deepEqual(splitView('?n=12&view=experiments&exp=delta'), { view: 'experiments', query: 'n=12&exp=delta', messages: [] });
  assert.deepEqual(splitView('n=12'), { view: 'live', query: 'n=12', messages: [] });
  const bad = splitView('view=charts&n=5');
  assert.equal(bad.view, 'live');
  assert.equal(bad.query, 'n=5');
  assert.match(bad.messages[0], /^Invalid view="charts": allowed one of live, experiments\. Using the default view=live\.$/);
});

test('the experiment list and preset choices come from the engine', () => {
  assert.ok(list.length >= 5, JSON.stringify(list.map((e) => e.name)));
  for (const e of list) {
    assert.equal(typeof e.name, 'string');
    assert.equal(typeof e.title, 'string');
    assert.ok(['episodes', 'targets'].includes(e.kind), e.kind);
    assert.ok(Number.isInteger(e.defaultTrials) && e.defaultTrials > 0, `${e.name} ${e.defaultTrials}`);
  }
  assert.ok(list.some((e) => e.name === 'sigma-sweep'));
  assert.ok(list.some((e) => e.name === CUSTOM), 'the engine has the custom experiment');
  // The spec's default preset, and none; every preset of the schema when it lists them.
  assert.equal(presets[presets.length - 1], 'none');
  assert.ok(presets.includes(engine.experimentPlan({ name: 'delta' }).spec.preset));
  for (const p of schema.presets ?? []) assert.ok(presets.includes(typeof p === 'string' ? p : p.name));
});

test('no query gives the first experiment with the defaults of its spec', () => {
  const { state, messages } = read('');
  assert.deepEqual(messages, []);
  assert.deepEqual(state, defaultExperiment(engine, schema, list));
  const spec = engine.experimentPlan({ name: list[0].name }).spec;
  assert.equal(state.name, list[0].name);
  assert.equal(state.trials, String(list[0].defaultTrials));
  assert.equal(state.seed, '1');
  assert.equal(state.preset, spec.preset);
  // The page's spec of the default state plans to the engine's default spec.
  assert.deepEqual(engine.experimentPlan(experimentSpec(state)).spec, spec);
});

test('a named experiment and a custom sweep round-trip through the URL', () => {
  const named = read('exp=sigma-sweep&trials=7&seed=18446744073709551615&preset=none&n=30');
  assert.deepEqual(named.messages, []);
  assert.deepEqual(read(writeExperimentUrl(named.state).replace(/^view=experiments&/, '')).state, named.state);
  const spec = experimentSpec(named.state);
  assert.deepEqual(spec, {
    name: 'sigma-sweep', trials: 7, seed: '18446744073709551615', preset: 'none', params: { n: '30' }, sweep: null, series: null,
  });
  assert.deepEqual(engine.experimentPlan(spec).spec, {
    name: 'sigma-sweep', trials: 7, seed: '18446744073709551615', preset: null, params: { n: '30' }, sweep: null, series: null,
  });
  // A new experiment takes its own default trials.
  const other = list.find((e) => e.defaultTrials !== list.find((x) => x.name === 'sigma-sweep').defaultTrials);
  assert.equal(read(`exp=${other.name}`).state.trials, String(other.defaultTrials));

  const q = new URLSearchParams([
    ['exp', CUSTOM], ['trials', '3'], ['seed', '9'], ['n', '12'], ['step_cap', '300'], ['start', '2,3'],
    ['sweep', 'sigma:0 2.5 inf'], ['series', 'MCTS:searcher=mcts loops=20'], ['series', 'RW:searcher=rw'],
  ]).toString();
  const custom = read(q);
  assert.deepEqual(custom.messages, []);
  assert.deepEqual(custom.state.params, [['n', '12'], ['step_cap', '300'], ['start', '2,3']]);
  assert.deepEqual(custom.state.sweep, { key: 'sigma', values: ['0', '2.5', 'inf'] });
  assert.deepEqual(custom.state.series, [{ label: 'MCTS', params: [['searcher', 'mcts'], ['loops', '20']] }, { label: 'RW', params: [['searcher', 'rw']] }]);
  const back = splitView(writeExperimentUrl(custom.state));
  assert.equal(back.view, 'experiments');
  assert.deepEqual(read(back.query).state, custom.state);
  const cspec = experimentSpec(custom.state);
  assert.deepEqual(cspec, {
    name: CUSTOM,
    trials: 3,
    seed: '9',
    preset: custom.state.preset,
    params: { n: '12', step_cap: '300', start: '2,3' },
    sweep: { key: 'sigma', values: ['0', '2.5', 'inf'] },
    series: [{ label: 'MCTS', params: { searcher: 'mcts', loops: '20' } }, { label: 'RW', params: { searcher: 'rw' } }],
  });
  const plan = engine.experimentPlan(cspec);
  assert.equal(plan.points.length, 6);
  assert.equal(plan.totalUnits, 18);
  assert.deepEqual(plan.experiment.series, ['MCTS', 'RW']);
});

test('bad experiment values name the key and what is allowed, and keep the default', () => {
  const q = new URLSearchParams([
    ['exp', 'no-such'], ['trials', '0'], ['seed', '-1'], ['preset', 'paper-poem'], ['n', '2'], ['bogus', '1'],
  ]).toString();
  const { state, messages } = read(q);
  const d = defaultExperiment(engine, schema, list);
  assert.deepEqual(state, d);
  const msg = (k) => messages.find((m) => m.startsWith(`Invalid ${k}=`));
  assert.equal(msg('exp'), `Invalid exp="no-such": allowed one of ${list.map((e) => e.name).join(', ')}. Using the default exp=${d.name}.`);
  assert.equal(msg('trials'), `Invalid trials="0": allowed ${schema.trials.allowed}. Using the default trials=${d.trials}.`);
  assert.match(msg('seed'), /allowed an integer in 0\.\.=18446744073709551615\. Using the default seed=1\./);
  assert.equal(msg('preset'), `Invalid preset="paper-poem": allowed one of ${presets.join(', ')}. Using the default preset=${d.preset}.`);
  assert.match(msg('n'), /allowed an integer in 3\.\.=1024\. Leaving n out\./);
  assert.ok(messages.includes('Unknown URL parameter "bogus" ignored.'), messages.join(' | '));
  assert.equal(messages.length, 6, messages.join(' | '));
  // A custom sweep: an unknown key, a bad value, bad series.
  const c = read(new URLSearchParams([['exp', CUSTOM], ['sweep', 'sigmaa:1 2']]).toString());
  assert.equal(c.state.sweep, null);
  assert.match(c.messages.join(' | '), /Invalid sweep="sigmaa:1 2": allowed KEY:V1 V2 … .*no parameter is named "sigmaa"/);
  const v = read(new URLSearchParams([['exp', CUSTOM], ['sweep', 'sigma:1 -2 3'], ['series', ':searcher=rw'], ['series', 'A:searcher=astar']]).toString());
  assert.deepEqual(v.state.sweep, { key: 'sigma', values: ['1', '3'] });
  assert.deepEqual(v.state.series, []);
  assert.match(v.messages.join(' | '), /Invalid sweep value sigma="-2": allowed /);
  assert.match(v.messages.join(' | '), /Invalid series=":searcher=rw".*has no label/);
  assert.match(v.messages.join(' | '), /Invalid series="A:searcher=astar".*searcher: one of/);
  // Values are checked in the context of the base parameters: start 15,15 needs n ≥ 15.
  assert.match(read(new URLSearchParams([['exp', CUSTOM], ['n', '10'], ['sweep', 'start:1,1 15,15']]).toString()).messages.join(' '), /Invalid sweep value start="15,15"/);
  // A sweep or series on a named experiment is not silently used.
  assert.match(read('exp=sigma-sweep&sweep=sigma:1').messages.join(' '), /only exp=custom takes a sweep/);
  // Values valid one by one that the engine's plan refuses together: kept, with the engine's reason.
  const x = read('exp=sigma-sweep&sigma=3');
  assert.deepEqual(x.messages, []);
  assert.deepEqual(x.state.params, [['sigma', '3']]);
  assert.match(x.conflict, /^The experiment cannot run as it is: sigma is the x axis of sigma-sweep/);
  assert.equal(read('').conflict, null);
});

test('text forms of pairs, series and sweeps', () => {
  assert.deepEqual(parsePairs(' n=12  start=1,1 '), [['n', '12'], ['start', '1,1']]);
  assert.throws(() => parsePairs('n=12 loops'), /"loops" is not key=value/);
  assert.throws(() => parsePairs('=3'), /is not key=value/);
  assert.deepEqual(parseSeries('MCTS Lévy: searcher=mcts rollout=levy'), { label: 'MCTS Lévy', params: [['searcher', 'mcts'], ['rollout', 'levy']] });
  assert.deepEqual(parseSeries('RW'), { label: 'RW', params: [] });
  assert.equal(formatSeries(parseSeries('A:x=1 y=2')), 'A:x=1 y=2');
  assert.deepEqual(parseSweep('loops: 10 20  40'), { key: 'loops', values: ['10', '20', '40'] });
  assert.equal(formatSweep(parseSweep('loops:10 20')), 'loops:10 20');
  assert.throws(() => parseSweep(':1 2'), /names no parameter/);
});

test('chunks cover every unit once, in order, and are deterministic', () => {
  // An off-by-one in the last short chunk (units not a multiple of the
  // chunk size) leaves a unit out or runs one twice, and fails here.
  for (const [total, workers] of [[12, 2], [5500, 2], [40000, 8], [7, 1], [1, 4], [0, 2], [1025, 1]]) {
    const chunks = chunkPlan(total, workers);
    const seen = new Uint8Array(total);
    let next = 0;
    for (const c of chunks) {
      assert.ok(c.from < c.to, JSON.stringify(c));
      assert.equal(c.from, next, 'consecutive');
      next = c.to;
      for (let u = c.from; u < c.to; u++) seen[u]++;
    }
    assert.ok(seen.every((k) => k === 1), `${total}/${workers}: every unit exactly once`);
    assert.deepEqual(chunkPlan(total, workers), chunks, 'the split is deterministic');
  }
  assert.throws(() => chunkPlan(-1, 2), /-1 is not a number of units/);
});
