// Property tests of every input surface the page has, run in Node with the
// engine (www/pkg) and fast-check: arbitrary and near-valid inputs are
// accepted or refused with an error naming the field; nothing panics the
// wasm instance, hangs, pollutes prototypes or changes the caller's data.
// Cases per property: FC_RUNS (default 10 000; the slow surfaces run a
// stated fraction) with the fixed seed FC_SEED (default 2026); `make fuzz`
// runs ten times as many with a fresh seed.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import path from 'node:path';
import { test } from 'node:test';
import { fileURLToPath } from 'node:url';
import fc from 'fast-check';
import { readUrl, raceOptions, splitView, readExperimentUrl, presetChoices } from '../../www/shared/url-state.js';
import { readEpisode, EPISODE_FORMAT, MAX_EPISODE_BYTES } from '../../www/live/share.js';

const ROOT = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
const engine = await import(path.join(ROOT, 'www/pkg/torus_search.js'));
engine.initSync({ module: readFileSync(path.join(ROOT, 'www/pkg/torus_search_bg.wasm')) });
const schema = engine.schema();
const races = raceOptions(engine, schema);
const list = engine.experimentList();
const presets = presetChoices(engine, schema, list);

const RUNS = Number(process.env.FC_RUNS ?? 10_000);
const SEED = Number(process.env.FC_SEED ?? 2026);
const opts = (runs = RUNS) => ({ numRuns: runs, seed: SEED, endOnFailure: true });
const KEYS = schema.params.map((p) => p.key);
const rate = [];

/** Runs a property and records its cases per second for the report. */
function check(name, prop, runs = RUNS) {
  const t0 = performance.now();
  fc.assert(prop, opts(runs));
  const s = (performance.now() - t0) / 1000;
  rate.push({ name, runs, per_s: Math.round(runs / s) });
}

/** Nothing panicked in wasm and no prototype was polluted. */
function healthy() {
  assert.equal(engine.lastPanic(), undefined, 'no wasm panic');
  assert.equal({}.polluted, undefined, 'Object.prototype is clean');
  assert.equal([].polluted, undefined, 'Array.prototype is clean');
}

/** Calls `f`: a value, or an Error with a message (never a wasm trap). */
function acceptsOrRefuses(f) {
  try {
    return { ok: true, value: f() };
  } catch (e) {
    assert.ok(!(e instanceof WebAssembly.RuntimeError), `a wasm trap: ${e}`);
    assert.ok(e instanceof Error, `threw a non-Error: ${String(e)}`);
    assert.ok(typeof e.message === 'string' && e.message.length > 0, 'an error says what is wrong');
    return { ok: false, error: e };
  }
}

// Values of the kinds a config field may wrongly get from JS.
const nasty = fc.oneof(
  fc.anything({ withNullPrototype: true, withBigInt: true, withDate: true, withTypedArray: true, withSparseArray: true, withBoxedValues: true, maxDepth: 4 }),
  fc.constantFrom(NaN, Infinity, -Infinity, -0, 1e308, -1e308, 2 ** 53 + 1, 'NaN', 'Infinity', '-Infinity', '1e999', '', ' ', '0x10', '1,2', '__proto__'),
  fc.string({ unit: 'grapheme', maxLength: 40 }),
  fc.double(),
  fc.integer(),
);
const defaults = engine.parseParams([]).config;
// A valid config with one field set to anything, or extra keys such as __proto__.
const nearConfig = fc.oneof(
  fc.record({ key: fc.constantFrom(...Object.keys(defaults)), v: nasty }).map(({ key, v }) => ({ ...defaults, [key]: v })),
  fc.record({ key: fc.constantFrom('__proto__', 'constructor', 'prototype', 'extra', 'toString'), v: nasty }).map(({ key, v }) => {
    const c = { ...defaults };
    Object.defineProperty(c, key, { value: v, enumerable: true, configurable: true, writable: true });
    return c;
  }),
  fc.anything({ maxDepth: 3 }),
  fc.constant(JSON.parse('{"__proto__": {"polluted": 1}, "n": 12}')),
  // Deep nesting.
  fc.integer({ min: 1, max: 2000 }).map((d) => {
    let v = { n: 12 };
    for (let i = 0; i < d; i++) v = { n: v };
    return v;
  }),
);

test('facade: a config from JS is accepted or refused naming a field; nothing panics or changes', () => {
  check('facade config (checkConfig, configParams, applicable, presetOf, describeConfig, setParam)', fc.property(nearConfig, fc.constantFrom(...KEYS), fc.string({ maxLength: 20 }), (config, key, raw) => {
    const before = (() => {
      try {
        return JSON.stringify(config);
      } catch {
        return null; // BigInt or cycles: compared by nothing
      }
    })();
    const checked = acceptsOrRefuses(() => engine.checkConfig(config));
    for (const f of [() => engine.configParams(config, true), () => engine.applicable(config), () => engine.presetOf(config), () => engine.describeConfig(config)]) {
      const r = acceptsOrRefuses(f);
      if (checked.ok) assert.ok(r.ok, `a valid config is refused: ${r.error}`);
    }
    const set = acceptsOrRefuses(() => engine.setParam(config, key, raw));
    if (!set.ok) assert.ok(/./.test(set.error.message));
    if (before !== null) assert.equal(JSON.stringify(config), before, 'the caller\'s object is unchanged');
    healthy();
  }), Math.ceil(RUNS / 5)); // describeConfig computes the bound (up to N = 1024): the slowest surface
});

test('facade: a refused config names the field', () => {
  // Each known field set to a wrong type must be refused with its name.
  check('facade wrong-typed field', fc.property(fc.constantFrom(...Object.keys(defaults)), fc.constantFrom({}, [], 'x'.repeat(3), -1.5, true, null), (key, v) => {
    const r = acceptsOrRefuses(() => engine.configParams({ ...defaults, [key]: v }, true));
    if (!r.ok) {
      const spelled = key === 'final_rule' ? 'final' : key;
      assert.ok(r.error.message.includes(spelled) || r.error.message.includes(key), `"${r.error.message}" names ${key}`);
    }
    healthy();
  }), 2_000);
});

test('facade: a Race is built or refused, and methods out of order throw errors', () => {
  const valid = { ...defaults, n: 8, step_cap: 50 };
  check('facade Race', fc.property(nearConfig, (config) => {
    // Runs are cheap only on small lattices: cap n so a case stays fast.
    const c = config && typeof config === 'object' && typeof config.n === 'number' && config.n > 64 ? { ...config, n: 64 } : config;
    const r = acceptsOrRefuses(() => new engine.Race([c]));
    if (r.ok) {
      const race = r.value;
      race.advance(3);
      acceptsOrRefuses(() => race.frames([{ layers: [{ layer: 'walker', palette: 'viridis', scale: 'linear', alpha: [0, 255] }], path_from: 0, traces: true, intent: true, live: false }]));
      race.free();
      for (const f of [() => race.advance(1), () => race.frames([]), () => race.describe(), () => race.stepMove()]) {
        const after = acceptsOrRefuses(f);
        assert.equal(after.ok, false, 'a freed race refuses');
      }
    }
    healthy();
  }), Math.min(RUNS, 2_000));
  // Frame requests of every shape against a live race.
  const race = new engine.Race([valid]);
  check('facade frame requests', fc.property(fc.oneof(fc.anything({ maxDepth: 3 }), fc.array(fc.record({ layers: fc.array(fc.record({ layer: fc.constantFrom(...schema.layers.map((l) => l.name), 'nope'), palette: fc.string(), scale: fc.string(), alpha: fc.anything() })), path_from: nasty }))), (req) => {
    acceptsOrRefuses(() => race.frames(req));
    healthy();
  }), Math.min(RUNS, 5_000));
  race.free();
});

// Query strings: repeated keys, percent-encoding, long values, Unicode.
const queryKey = fc.oneof(fc.constantFrom(...KEYS, 'speed', 'autoplay', 'race', 'preset', 'view', 'exp', 'trials', 'sweep', 'series'), fc.string({ maxLength: 8 }));
const queryValue = fc.oneof(fc.string({ unit: 'grapheme', maxLength: 30 }), fc.stringMatching(/^(%[0-9A-Fa-f]{0,2}|[0-9.,e+-]|inf|nan){0,12}$/), fc.constantFrom('', 'max', '1e999', '%', '%zz', '\u0000', '<script>alert(1)</script>', 'x'.repeat(100_000)));
const query = fc.oneof(
  fc.array(fc.tuple(queryKey, queryValue), { maxLength: 8 }).map((pairs) => pairs.map(([k, v]) => `${encodeURIComponent(k)}=${Math.random() < 0 ? v : encodeURIComponent(v)}`).join('&')),
  fc.array(fc.tuple(queryKey, queryValue), { maxLength: 8 }).map((pairs) => pairs.map(([k, v]) => `${k}=${v}`).join('&')),
  fc.string({ unit: 'binary', maxLength: 200 }),
);

test('URL: any query string gives a valid config, a view and messages; it never throws', () => {
  check('URL live view', fc.property(query, (q) => {
    const { config, view, messages } = readUrl(engine, schema, q, races);
    assert.ok(acceptsOrRefuses(() => engine.checkConfig(config)).ok, 'the config is valid');
    assert.ok(Array.isArray(messages) && messages.every((m) => typeof m === 'string' && m.length < 2_000), 'messages are short text');
    assert.ok(view && typeof view.autoplay === 'boolean');
    healthy();
  }));
  check('URL experiments view', fc.property(query, (q) => {
    const split = splitView(q);
    const r = readExperimentUrl(engine, schema, split.query ?? q, list, presets);
    assert.ok(r && typeof r === 'object');
    healthy();
  }), Math.min(RUNS, 3_000));
});

test('imported results: truncated, mutated, oversized or foreign files are refused with a message', () => {
  const good = engine.experimentResult({ name: 'delta', trials: 2, params: { n: '8' } }, engine.experimentRun({ name: 'delta', trials: 2, params: { n: '8' } }, 0, engine.experimentPlan({ name: 'delta', trials: 2, params: { n: '8' } }).totalUnits));
  assert.ok(engine.experimentRead(good), 'the unmodified file reads');
  const mutate = fc.oneof(
    fc.nat(good.length).map((k) => good.slice(0, k)),
    fc.tuple(fc.nat(good.length - 1), fc.string({ maxLength: 5 })).map(([k, s]) => good.slice(0, k) + s + good.slice(k + 1)),
    fc.tuple(fc.nat(good.length - 1), fc.nat(good.length - 1)).map(([a, b]) => good.slice(0, Math.min(a, b)) + good.slice(Math.max(a, b))),
    fc.constantFrom(good.replace('"torus-search', '"other-tool'), good.replace(/"version":\s*\d+/, '"version": 99'), '{"__proto__": {"polluted": 1}}', '[]', 'null', '{}', ''),
    fc.json({ maxDepth: 4 }),
  );
  check('results import', fc.property(mutate, (text) => {
    const r = acceptsOrRefuses(() => engine.experimentRead(text));
    if (r.ok) assert.ok(r.value && typeof r.value === 'object');
    healthy();
  }));
});

test('imported episodes: truncated, oversized, wrong version or foreign files are refused with a message', async () => {
  const good = JSON.stringify({ format: EPISODE_FORMAT, version: 2, url_query: 'n=8&seed=3', episode: { path: [0, 1, 2] } });
  const mutate = fc.oneof(
    fc.nat(good.length).map((k) => good.slice(0, k)),
    fc.tuple(fc.nat(good.length - 1), fc.string({ maxLength: 5 })).map(([k, s]) => good.slice(0, k) + s + good.slice(k + 1)),
    fc.json({ maxDepth: 4 }),
    fc.constantFrom(good.replace('"version":2', '"version":99'), good.replace(EPISODE_FORMAT, 'other'), '{"__proto__":{"polluted":1},"format":"x"}'),
  );
  let runs = 0;
  const t0 = performance.now();
  await fc.assert(fc.asyncProperty(mutate, async (text) => {
    runs++;
    try {
      const { query, path: p } = await readEpisode(new File([text], 'e.json'));
      assert.equal(typeof query, 'string');
      assert.ok(p.every((c) => Number.isInteger(c) && c >= 0));
      readUrl(engine, schema, query, races); // what the page does with it next
    } catch (e) {
      assert.ok(e instanceof Error && e.message.length > 0);
    }
    healthy();
  }), opts());
  rate.push({ name: 'episode import', runs, per_s: Math.round(runs / ((performance.now() - t0) / 1000)) });
  // Oversized: refused by size before reading.
  const big = { size: MAX_EPISODE_BYTES + 1, text: () => assert.fail('an oversized file is not read') };
  await assert.rejects(readEpisode(big), /bytes; episode files are at most/);
});

test('report cases per second', () => {
  for (const r of rate) console.log(`# property ${r.name}: ${r.runs} cases, ${r.per_s} cases/s`);
  assert.ok(rate.length >= 6);
});
