// The CLI, the URL and the core agree on every parameter's name, default
// and range (no browser: the engine runs in Node, the CLI as a process).
//
// The core's table (src/config.rs PARAMS, exported by the engine's
// schema()) is pinned in tests/schema.snapshot.json, so a change to a
// parameter is deliberate: rerun with UPDATE_SCHEMA_SNAPSHOT=1 to accept it.
// Then each surface is probed on its own, at and beyond every bound:
// - the core: the engine's parser (parseParams) and its default config;
// - the URL: the page's parser (www/shared/url-state.js readUrl), which hands
//   the engine only what it does not own;
// - the CLI: `torus-search run --dry-run` with each flag, its exit code
//   and the resolved config, and `run --help` for flags and defaults.
// A surface that changes alone (a CLI default written by hand, a URL clamp,
// a core range) makes this test fail.
import assert from 'node:assert/strict';
import { execFileSync, spawnSync } from 'node:child_process';
import { readFileSync, writeFileSync } from 'node:fs';
import path from 'node:path';
import { test } from 'node:test';
import { fileURLToPath } from 'node:url';
import { readUrl } from '../../www/shared/url-state.js';
import { cliBinary } from './harness.mjs';

const ROOT = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
const SNAPSHOT = path.join(ROOT, 'tests/schema.snapshot.json');
const PKG = path.join(ROOT, 'www/pkg');

const engine = await import(path.join(PKG, 'torus_search.js'));
engine.initSync({ module: readFileSync(path.join(PKG, 'torus_search_bg.wasm')) });
const schema = engine.schema();
const DEFAULT = engine.parseParams([]).config;

const BIN = cliBinary();

function cli(args) {
  const r = spawnSync(BIN, ['run', '--dry-run', ...args], { encoding: 'utf8' });
  return { code: r.status, config: r.status === 0 ? JSON.parse(r.stdout) : null, err: r.stderr.trim() };
}

/** The pairs that make `key` apply, found among single choice changes (mu needs a Lévy rollout, …). */
function contextFor(key) {
  if (engine.applicable(DEFAULT).includes(key)) return [];
  for (const p of schema.params.filter((q) => q.kind === 'choice')) {
    for (const choice of p.choices) {
      try {
        const cfg = engine.setParam(DEFAULT, p.key, choice);
        if (engine.applicable(cfg).includes(key)) return [[p.key, choice]];
      } catch {
        /* this choice alone is not a valid config (prior=paint needs paint) */
      }
    }
  }
  // prior=paint needs a painting, which the paint probes supply.
  if (key === 'paint') return [['prior', 'paint']];
  throw new Error(`no context makes ${key} apply`);
}

function paintText(n) {
  const levels = new Uint8Array(n * n);
  levels[0] = 5;
  return engine.encodePaint(levels);
}

/** Values at and beyond each bound: [text, accepted?]. */
function probes(p) {
  const num = (s) => Number(s);
  switch (p.kind) {
    case 'int': {
      const [min, max] = [BigInt(p.min), BigInt(p.max)];
      return [[p.min, true], [p.max, true], [String(min - 1n), false], [String(max + 1n), false], ['1.5', false], ['x', false]];
    }
    case 'float': {
      const [min, max] = [num(p.min), num(p.max)];
      const out = [[p.max, true], [String(min - 1), false], ['nan', false], ['x', false]];
      if (p.min_open) out.push([p.min, false], [String(min + 1e-6), true]);
      else out.push([p.min, true]);
      if (Number.isFinite(max)) out.push([String(max + Math.max(1e-6, max * 1e-6)), false]);
      return out;
    }
    case 'optfloat': {
      const [min, max] = [num(p.min), num(p.max)];
      return [[p.min, true], [p.max, true], ['0', true], [String(min / 2), false], [String(max * 2), false], ['-1', false]];
    }
    case 'choice': {
      // A choice that needs another parameter (prior=paint needs a paint) is
      // probed with that parameter's probes.
      const alone = p.choices.filter((c) => {
        try {
          engine.setParam(DEFAULT, p.key, c);
          return true;
        } catch {
          return false;
        }
      });
      return [...alone.map((c) => [c, true]), ['no-such-choice', false]];
    }
    case 'cell':
      return [['1,1', true], [`${DEFAULT.n},${DEFAULT.n}`, true], [`${DEFAULT.n + 1},1`, false], ['0,1', false], ['a,b', false]];
    case 'optcell':
      return [['2,3', true], [`${DEFAULT.n + 1},1`, false], ['x', false]];
    case 'paint':
      return [[paintText(DEFAULT.n), true], ['!!!', false], [paintText(DEFAULT.n + 1), false]];
    case 'bool':
      return [['1', true], ['0', true], ['maybe', false]];
    default:
      throw new Error(`unknown kind ${p.kind}`);
  }
}

const pinned = (p) => ({ key: p.key, flag: p.flag, aliases: p.aliases, kind: p.kind, default: p.default, min: p.min, max: p.max, min_open: p.min_open, choices: p.choices, allowed: p.allowed });

test('the core schema is the pinned one (a change is deliberate)', () => {
  const got = { params: schema.params.map(pinned), searchers: schema.searchers.map((s) => s.name), trials: pinned(schema.trials) };
  if (process.env.UPDATE_SCHEMA_SNAPSHOT) writeFileSync(SNAPSHOT, `${JSON.stringify(got, null, 1)}\n`);
  const want = JSON.parse(readFileSync(SNAPSHOT, 'utf8'));
  assert.deepEqual(got, want, 'the schema changed: if on purpose, rerun with UPDATE_SCHEMA_SNAPSHOT=1 and commit tests/schema.snapshot.json');
});

test('names agree: schema keys are the config fields, the URL keys and (dashed) the CLI flags', () => {
  const keys = schema.params.map((p) => p.key);
  assert.deepEqual(Object.keys(DEFAULT).sort(), [...keys].sort(), 'the core config fields');
  const { config } = cli([]);
  assert.deepEqual(Object.keys(config).sort(), [...keys].sort(), 'the CLI config fields');
  const help = execFileSync(BIN, ['run', '--help'], { encoding: 'utf8' });
  for (const p of schema.params) {
    assert.equal(p.flag, `--${p.key.replaceAll('_', '-')}`, p.key);
    assert.match(help, new RegExp(`^\\s+${p.flag}\\b`, 'm'), `the CLI has no ${p.flag}`);
    for (const a of p.aliases) assert.match(help, new RegExp(`alias: ${a}\\b`), `the CLI lacks the alias ${a}`);
    const url = readUrl(engine, schema, `${p.key}=${encodeURIComponent(p.default)}`);
    assert.deepEqual(url.messages, [], `the URL refuses its own ${p.key}=${p.default}`);
  }
});

test('defaults agree: core, URL and CLI', () => {
  const url = readUrl(engine, schema, '');
  assert.deepEqual(url.messages, []);
  assert.deepEqual(url.config, DEFAULT, 'URL default config');
  assert.deepEqual(cli([]).config, DEFAULT, 'CLI default config');
  const text = new Map(engine.configParams(DEFAULT, true));
  const help = execFileSync(BIN, ['run', '--help'], { encoding: 'utf8' }).replace(/\s+/g, ' ');
  for (const p of schema.params) {
    assert.equal(text.get(p.key), p.default, `${p.key}: the default config writes ${text.get(p.key)}, the schema says ${p.default}`);
    const shown = p.kind === 'bool' ? (p.default === '1' ? 'on' : 'off') : p.default || 'none';
    const at = help.indexOf(`${p.flag} `);
    const entry = help.slice(at, help.indexOf(' --', at + p.flag.length));
    assert.ok(entry.includes(`[default: ${shown}]`), `CLI help for ${p.flag} does not show [default: ${shown}]: ${entry}`);
  }
});

test('ranges agree: every bound is accepted or refused alike by the core, the URL and the CLI', () => {
  let checked = 0;
  for (const p of schema.params) {
    const context = contextFor(p.key);
    for (const [raw, ok] of probes(p)) {
      const what = `${p.key}=${raw}`;
      // The core.
      const core = engine.parseParams([...context, [p.key, raw]]);
      assert.equal(core.errors.length === 0, ok, `core ${what}: ${JSON.stringify(core.errors)}`);
      // The URL.
      const q = new URLSearchParams([...context, [p.key, raw]]).toString();
      const url = readUrl(engine, schema, q);
      assert.equal(url.messages.length === 0, ok, `URL ${what}: ${url.messages.join(' ')}`);
      if (!ok) assert.match(url.messages.join(' '), new RegExp(`Invalid ${p.key}=.*allowed`), `URL ${what}`);
      // The CLI (a bool is a flag without a value).
      const flags = context.flatMap(([k, v]) => [`--${k.replaceAll('_', '-')}`, v]);
      if (p.kind === 'bool') {
        if (raw === '1') flags.push(p.flag);
        else if (raw === '0') continue; // off is the absence of the flag
        else continue; // a flag takes no value to refuse
      } else flags.push(p.flag, raw);
      const c = cli(flags);
      assert.equal(c.code, ok ? 0 : 2, `CLI ${flags.join(' ')}: ${c.err}`);
      if (ok) {
        assert.deepEqual(c.config, url.config, `CLI and URL read ${what} differently`);
        assert.deepEqual(c.config, core.config, `CLI and core read ${what} differently`);
      } else assert.match(c.err, new RegExp(`^error: ${p.flag} must be .*, got `), `CLI ${what}: ${c.err}`);
      checked++;
    }
  }
  assert.ok(checked > 100, `${checked} probes`);
});

test('the batch trials range agrees between the schema, the CLI and the page', () => {
  const t = schema.trials;
  const page = (raw) => {
    try {
      engine.parseTrials(raw);
      return true;
    } catch {
      return false;
    }
  };
  for (const [raw, ok] of [[t.min, true], [t.max, true], [String(BigInt(t.min) - 1n), false], [String(BigInt(t.max) + 1n), false], ['x', false]]) {
    assert.equal(page(raw), ok, `page trials=${raw}`);
    if (raw === t.max) continue; // a run of 10^8 trials is not a probe
    const run = spawnSync(BIN, ['run', '--n', '3', '--searcher', 'rw', '--trials', raw], { encoding: 'utf8' });
    assert.equal(run.status, ok ? 0 : 2, `CLI --trials ${raw}: ${run.stderr}`);
    if (!ok) assert.ok(run.stderr.includes(`--trials must be ${t.allowed}, got ${raw}`), run.stderr);
  }
});
