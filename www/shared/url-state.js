// The page's whole state lives in the URL query string: the engine's
// configuration parameters, which the engine parses and writes (the schema
// in src/config.rs: the same parser as the CLI's flags), and the page's own
// view parameters (speed, autoplay, race), which only this module knows.
//
// Pure module (no DOM): the engine is passed in, so Node tests use the real one.

/** Shortens a user-supplied value for display in a message (never as HTML). */
function shown(raw) {
  const s = String(raw);
  return s.length > 40 ? `${s.slice(0, 40)}…` : s;
}

/** Speeds of one phase every so many seconds (the worker steps a phase when that long has passed). */
export const PHASE_SPEEDS = ['2s', '1s', '0.5s'];

import { LESSONS, lessonAt, lessonSteps } from '../live/lessons.js';

// A link's `at`: a timeline point, or one for each of a race's two boards.
const POINT = String.raw`\d{1,9}(\.\d{1,9}(\.(select|expand|rollout|backup))?)?`;
const AT = new RegExp(`^${POINT}(/${POINT})?$`);
const BOOL = { 1: true, true: true, yes: true, on: true, 0: false, false: false, no: false, off: false };

/**
 * Race opponents: every searcher in the registry, and for one that reads
 * `variant`, each variant. `pairs` are the parameters that make the opponent.
 */
export function raceOptions(engine, schema) {
  const variant = schema.params.find((p) => p.key === 'variant');
  const base = engine.parseParams([]).config;
  const out = [{ id: '', label: '— nobody —', pairs: [] }];
  for (const s of schema.searchers) {
    const withS = engine.setParam(base, 'searcher', s.name);
    if (engine.applicable(withS).includes('variant')) {
      for (const v of variant.choices) out.push({ id: `${s.name}-${v}`, label: `${s.label} ${v}`, pairs: [['searcher', s.name], ['variant', v]] });
    } else {
      out.push({ id: s.name, label: s.label, pairs: [['searcher', s.name]] });
    }
  }
  return out;
}

/**
 * The tree view's link text (`tree=`): `[b.](best|ID)`, or `b` alone, or
 * empty → { board: 0 | 1 (B with the `b` prefix), focus: 'all' | 'best' | a node id };
 * undefined for anything else.
 */
export function readTreeView(s) {
  const m = /^(?:b(?:\.(best|\d{1,9}))?|(best|\d{1,9}))?$/.exec(s);
  if (!m) return undefined;
  const f = m[1] ?? m[2];
  return { board: s !== '' && m[2] === undefined ? 1 : 0, focus: f === undefined ? 'all' : f === 'best' ? 'best' : Number(f) };
}

/** The link text of a tree view state (readTreeView's inverse). */
export function treeViewText({ board = 0, focus = 'all' }) {
  const f = focus === 'all' ? '' : String(focus);
  return board ? (f ? `b.${f}` : 'b') : f;
}

/** The page's own parameters: key → { def, help, parse(text) → value | undefined, text(value) }. */
export function viewSpecs(races) {
  return {
    speed: {
      def: 10,
      help: 'loops per frame, an integer in 1..=1000000, or max, or one phase every 2s, 1s or 0.5s',
      parse: (s) => (s === 'max' || PHASE_SPEEDS.includes(s) ? s : /^\d{1,7}$/.test(s) && +s >= 1 && +s <= 1e6 ? +s : undefined),
      text: String,
    },
    autoplay: {
      def: true,
      help: 'one of 1, 0, true, false, yes, no, on, off',
      parse: (s) => (Object.hasOwn(BOOL, s) ? BOOL[s] : undefined),
      text: (v) => (v ? '1' : '0'),
    },
    vs: {
      def: '',
      help: 'the race opponent\'s parameters that differ, as key=value pairs separated by spaces (e.g. rollout=levy c=0.5)',
      parse: (s) => (s.length <= 400 && /^[\w.,:=+ -]*$/.test(s) ? s.trim().replace(/\s+/g, ' ') : undefined),
      text: String,
    },
    show: {
      def: '',
      help: 'the layers and options shown, as names separated by commas (e.g. visits,path,rollouts), or empty for the default',
      parse: (s) => (s.length <= 300 && /^[a-z,-]*$/.test(s) ? s : undefined),
      text: String,
    },
    at: {
      def: '',
      help: 'a point of the run to open at, paused: MOVE, MOVE.LOOP or MOVE.LOOP.PHASE (phase: select, expand, rollout or backup); in a race whose boards stand at different points, one for each board joined by / (2.2/0.12)',
      parse: (s) => (AT.test(s) ? s : undefined),
      text: String,
    },
    branch: {
      def: '',
      help: 'where the run branched: MOVE, or MOVE:key=value … naming what the run it branched from had otherwise (e.g. 12:c=2), oldest first, joined by /',
      parse: (s) => (s === '' || parseBranch(s) ? s : undefined),
      text: String,
    },
    tree: {
      def: '',
      help: 'the tree view\'s focus: best (the best line) or a node id, or empty for the whole tree; in a race b, b.best or b.ID for board B\'s tree',
      parse: (s) => (readTreeView(s) ? s : undefined),
      text: String,
    },
    lesson: {
      def: '',
      help: `one of ${LESSONS.map((l) => (l.steps ? `${l.id} (or ${l.id}.1 to ${l.id}.${lessonSteps(l).length}, its steps)` : l.id)).join(', ')}, or empty`,
      parse: (s) => (s === '' || lessonAt(s) ? s : undefined),
      text: String,
    },
    race: {
      def: '',
      help: `one of ${races.filter((r) => r.id).map((r) => r.id).join(', ')}, or empty`,
      parse: (s) => (races.some((r) => r.id === s) ? s : undefined),
      text: String,
    },
  };
}

/**
 * Parses a query string (with or without "?"). Every parameter is checked;
 * a bad one keeps its default and yields a message naming it and its range.
 * @returns {{ config: object, view: object, messages: string[] }}
 */
export function readUrl(engine, schema, search, races = raceOptions(engine, schema)) {
  const params = new URLSearchParams(search);
  const specs = viewSpecs(races);
  const view = Object.fromEntries(Object.entries(specs).map(([k, s]) => [k, s.def]));
  const known = new Map(schema.params.map((p) => [p.key, p]));
  const messages = [];
  const pairs = [];
  for (const key of new Set(params.keys())) {
    const raw = params.getAll(key).at(-1); // a repeated key: the last one counts
    if (Object.hasOwn(specs, key)) {
      const v = specs[key].parse(raw.trim());
      if (v === undefined) {
        messages.push(`Invalid ${key}=${JSON.stringify(shown(raw))}: allowed ${specs[key].help}. Using the default ${key}=${specs[key].text(specs[key].def) || '(none)'}.`);
      } else view[key] = v;
    } else if (known.has(key) || key === schema.preset_key) pairs.push([key, raw]);
    else messages.push(`Unknown URL parameter ${JSON.stringify(shown(key))} ignored.`);
  }
  const { config, errors } = engine.parseParams(pairs);
  for (const e of errors) {
    const def = known.get(e.field)?.default;
    messages.push(`Invalid ${e.field}=${JSON.stringify(shown(e.value))}: allowed ${e.allowed}. Using the default ${e.field}=${def || '(none)'}.`);
  }
  if (view.vs) {
    const bad = opponentError(engine, config, view.vs);
    if (bad) {
      messages.push(`Invalid vs=${JSON.stringify(shown(view.vs))}: ${bad}. Using no changes.`);
      view.vs = '';
    }
  }
  return { config, view, messages };
}

/** A timeline point as a link's `at` ("12.3.rollout"), or '' for the start. */
export function pointToAt(p) {
  if (!p) return '';
  const one = (q) => [q.move, ...(q.loop || q.phase ? [q.loop] : []), ...(q.phase ? [q.phase] : [])].join('.');
  // A race's boards at different points (stepped loop by loop): each one's.
  const each = Array.isArray(p) ? p : (p.runs ?? []).map(({ move, loop, phase }) => ({ move, loop, phase }));
  if (each.length > 1 && each.some((q) => one(q) !== one(each[0]))) return each.map(one).join('/');
  const q = each[0] ?? p;
  return !q.move && !q.loop && !q.phase ? '' : one(q);
}

/** A link's `at` as a timeline point { move, loop, phase }, or one per board (null for ''). */
export function atToPoint(at) {
  if (!at) return null;
  const one = (t) => {
    const [move, loop = '0', phase = null] = t.split('.');
    return { move: Number(move), loop: Number(loop), phase };
  };
  return at.includes('/') ? at.split('/').map(one) : one(at);
}

/**
 * A link's `branch` as levels `[{ move, pairs }]`, oldest first: the run
 * shares its first `move` moves with the run it branched from, whose
 * config is this one with `pairs` set ("12:c=2 loops=50/30:c=1"). Null
 * when the text is not of that form (the engine checks the values).
 */
export function parseBranch(text) {
  if (typeof text !== 'string' || !text || text.length > 800) return null;
  const levels = [];
  for (const level of text.split('/')) {
    const m = /^(\d{1,9})(?::([\w.,:=+ -]*))?$/.exec(level.trim());
    if (!m) return null;
    const pairs = opponentPairs(m[2]?.trim().replace(/\s+/g, ' '));
    if (pairs.some(([k, v]) => !k || v === '')) return null;
    levels.push({ move: Number(m[1]), pairs });
  }
  return levels;
}

/** Levels `[{ move, pairs }]` as a link's `branch` (see parseBranch). */
export function formatBranch(levels) {
  return levels.map(({ move, pairs }) => (pairs.length ? `${move}:${pairs.map(([k, v]) => `${k}=${v}`).join(' ')}` : String(move))).join('/');
}

/** `vs` text ("key=value key=value") as [key, value] pairs. */
export function opponentPairs(vs) {
  return (vs ?? '').split(' ').filter(Boolean).map((kv) => {
    const at = kv.indexOf('=');
    return at < 0 ? [kv, ''] : [kv.slice(0, at), kv.slice(at + 1)];
  });
}

/** The race opponent: `config` with the race option's `pairs`, then the `vs` pairs, set through the engine (throws naming a bad one). */
export function opponentConfig(engine, config, pairs, vs) {
  return [...pairs, ...opponentPairs(vs)].reduce((c, [key, v]) => engine.setParam(c, key, v), config);
}

/** Why `vs` cannot make an opponent of `config` (the engine's message), or ''. */
export function opponentError(engine, config, vs) {
  try {
    opponentConfig(engine, config, [], vs);
    return '';
  } catch (err) {
    return err.message;
  }
}

/**
 * The query string (without "?") for a config and view: with `full` every
 * parameter, else only what differs from the defaults, and the seed (so a
 * shared link reproduces the run).
 */
export function writeUrl(engine, config, view, { full = false, races = [] } = {}) {
  const params = new URLSearchParams(engine.configParams(config, full));
  for (const [key, spec] of Object.entries(viewSpecs(races))) {
    if (view[key] !== undefined && (full || view[key] !== spec.def)) params.set(key, spec.text(view[key]));
  }
  return params.toString();
}

// ---------------------------------------------------------------------------
// Which view the page shows, and the Experiments view's state.
//
// `view=experiments` turns the query into an experiment's: `exp` (a name
// from the engine's experimentList()), `trials`, `seed`, `preset` (a
// preset's name or `none`), and for the custom experiment `sweep=KEY:V1 V2 …` and repeated
// `series=LABEL:key=value key=value`; any engine parameter key is a base
// parameter of the experiment (spec.params). The live view's query is the
// one above (readUrl). Each view's query describes what it shows, so a
// shared link reproduces it; the page keeps the other view's state in memory.

/** The page's views; the first is the default. */
export const VIEWS = ['live', 'experiments'];

/**
 * The preset choices of an experiment: the engine's presets (named readings
 * of the paper, from its schema), the spec's default (what a spec without a
 * preset gets, as the CLI without --preset), and `none`.
 */
export function presetChoices(engine, schema, list) {
  const names = Array.isArray(schema.presets) ? schema.presets.map((p) => (typeof p === 'string' ? p : p.name)) : [];
  const def = list.length ? engine.experimentPlan({ name: list[0].name }).spec.preset : null;
  if (def && !names.includes(def)) names.push(def);
  return [...names, 'none'];
}

/** The experiment that takes a sweep and series (the engine's `custom`, the CLI's `torus-search experiment custom`). */
export const CUSTOM = 'custom';

/**
 * Splits off `view`: resolves to { view, query } where `query` is the rest
 * of the query string, and a message if `view` was bad.
 */
export function splitView(search) {
  const params = new URLSearchParams(search);
  const raw = params.getAll('view').at(-1);
  params.delete('view');
  const messages = [];
  let view = VIEWS[0];
  if (raw !== undefined) {
    if (VIEWS.includes(raw.trim())) view = raw.trim();
    else messages.push(`Invalid view=${JSON.stringify(shown(raw))}: allowed one of ${VIEWS.join(', ')}. Using the default view=${VIEWS[0]}.`);
  }
  return { view, query: params.toString(), messages };
}

/** "key=value key=value" → [[key, value]] (values hold no spaces; the engine checks them). */
export function parsePairs(text) {
  const out = [];
  for (const word of String(text).trim().split(/\s+/).filter(Boolean)) {
    const eq = word.indexOf('=');
    if (eq <= 0) throw new Error(`${JSON.stringify(shown(word))} is not key=value`);
    out.push([word.slice(0, eq), word.slice(eq + 1)]);
  }
  return out;
}

/** [[key, value]] → "key=value key=value". */
export const formatPairs = (pairs) => pairs.map(([k, v]) => `${k}=${v}`).join(' ');

/** "LABEL:key=value …" → { label, params: [[key, value]] }. */
export function parseSeries(text) {
  const s = String(text);
  const colon = s.indexOf(':');
  const label = (colon < 0 ? s : s.slice(0, colon)).trim();
  if (!label) throw new Error(`${JSON.stringify(shown(s))} has no label (write LABEL:key=value …)`);
  return { label, params: parsePairs(colon < 0 ? '' : s.slice(colon + 1)) };
}

export const formatSeries = ({ label, params }) => `${label}:${formatPairs(params)}`;

/** "KEY:V1 V2 …" → { key, values }. */
export function parseSweep(text) {
  const s = String(text);
  const colon = s.indexOf(':');
  const key = (colon < 0 ? s : s.slice(0, colon)).trim();
  const values = colon < 0 ? [] : s.slice(colon + 1).trim().split(/\s+/).filter(Boolean);
  if (!key) throw new Error(`${JSON.stringify(shown(s))} names no parameter (write KEY:V1 V2 …)`);
  return { key, values };
}

export const formatSweep = ({ key, values }) => `${key}:${values.join(' ')}`;

/**
 * The default experiment state: the first experiment of `list`, its
 * default trials and preset (the engine's normalised spec of just its
 * name), the schema's default seed, no parameters, no custom sweep.
 */
export function defaultExperiment(engine, schema, list) {
  const name = list[0]?.name ?? CUSTOM;
  const spec = engine.experimentPlan({ name }).spec;
  return {
    name,
    trials: String(spec.trials),
    seed: spec.seed,
    preset: spec.preset ?? 'none',
    params: [],
    sweep: null,
    series: [],
  };
}

/**
 * Reads an experiment's query (without `view`). Every value is checked
 * (names against `list` and `presets`, numbers and parameters by the
 * engine); a bad one keeps its default, or is left out, with a message
 * naming it and what is allowed.
 * @param {object[]} list     the engine's experimentList()
 * @param {string[]} presets  preset choices (presetChoices)
 * @returns {{ state: object, messages: string[], conflict: string | null }}
 *   conflict: the engine's reason the state cannot run, if any
 */
export function readExperimentUrl(engine, schema, search, list, presets) {
  const params = new URLSearchParams(search);
  const state = defaultExperiment(engine, schema, list);
  const messages = [];
  const keys = new Set(schema.params.map((p) => p.key));
  const last = (k) => params.getAll(k).at(-1);
  const bad = (key, raw, allowed, then) => messages.push(`Invalid ${key}=${JSON.stringify(shown(raw))}: allowed ${allowed}. ${then}`);
  const names = list.map((e) => e.name);
  if (params.has('exp')) {
    const raw = last('exp').trim();
    if (names.includes(raw)) state.name = raw;
    else bad('exp', raw, `one of ${names.join(', ')}`, `Using the default exp=${state.name}.`);
  }
  const named = list.find((e) => e.name === state.name);
  if (named) {
    state.trials = String(named.defaultTrials);
    state.preset = named.defaultPreset ?? 'none';
  }
  if (params.has('trials')) {
    const raw = last('trials');
    try {
      state.trials = String(engine.parseTrials(raw.trim()));
    } catch (err) {
      bad('trials', raw, `${schema.trials.allowed}`, `Using the default trials=${state.trials}.`);
    }
  }
  if (params.has('seed')) {
    const raw = last('seed');
    const { config, errors } = engine.parseParams([['seed', raw]]);
    if (errors.length) bad('seed', raw, errors[0].allowed, `Using the default seed=${state.seed}.`);
    else state.seed = config.seed;
  }
  if (params.has('preset')) {
    const raw = last('preset').trim();
    if (presets.includes(raw)) state.preset = raw;
    else bad('preset', raw, `one of ${presets.join(', ')}`, `Using the default preset=${state.preset}.`);
  }
  // Base parameters: each checked by the engine, in the context of the ones before it.
  for (const key of new Set(params.keys())) {
    if (['exp', 'trials', 'seed', 'preset', 'sweep', 'series'].includes(key)) continue;
    if (!keys.has(key)) {
      messages.push(`Unknown URL parameter ${JSON.stringify(shown(key))} ignored.`);
      continue;
    }
    const raw = last(key);
    const { errors } = engine.parseParams([...state.params, [key, raw]]);
    const e = errors.find((x) => x.field === key);
    if (e) bad(key, raw, e.allowed, `Leaving ${key} out.`);
    else state.params.push([key, raw]);
  }
  const custom = state.name === CUSTOM;
  if (params.has('sweep')) {
    const raw = last('sweep');
    try {
      const sweep = parseSweep(raw);
      if (!keys.has(sweep.key)) throw new Error(`no parameter is named ${JSON.stringify(shown(sweep.key))}`);
      const values = [];
      for (const v of sweep.values) {
        const e = engine.parseParams([...state.params, [sweep.key, v]]).errors.find((x) => x.field === sweep.key);
        if (e) messages.push(`Invalid sweep value ${sweep.key}=${JSON.stringify(shown(v))}: allowed ${e.allowed}. Leaving it out.`);
        else values.push(v);
      }
      if (!values.length) throw new Error('no valid value to sweep');
      if (custom) state.sweep = { key: sweep.key, values };
      else messages.push(`sweep=${JSON.stringify(shown(raw))} ignored: only exp=${CUSTOM} takes a sweep.`);
    } catch (err) {
      bad('sweep', raw, `KEY:V1 V2 … with KEY a parameter and valid values (${err.message})`, 'Leaving the sweep out.');
    }
  }
  for (const raw of params.getAll('series')) {
    try {
      const s = parseSeries(raw);
      for (const [k, v] of s.params) {
        if (!keys.has(k)) throw new Error(`no parameter is named ${JSON.stringify(shown(k))}`);
        const e = engine.parseParams([...state.params, [k, v]]).errors.find((x) => x.field === k);
        if (e) throw new Error(`${k}: ${e.allowed}`);
      }
      if (custom) state.series.push(s);
      else messages.push(`series=${JSON.stringify(shown(raw))} ignored: only exp=${CUSTOM} takes series.`);
    } catch (err) {
      bad('series', raw, `LABEL:key=value … (${err.message})`, 'Leaving this series out.');
    }
  }
  // Values that pass one by one can still conflict (a base parameter that
  // is the experiment's x axis): the engine's plan says so, and the state is kept to be fixed.
  let conflict = null;
  try {
    engine.experimentPlan(experimentSpec(state));
  } catch (err) {
    conflict = `The experiment cannot run as it is: ${err.message}.`;
  }
  return { state, messages, conflict };
}

/** The query string (without "?") of an experiment's state, `view=experiments` first. */
export function writeExperimentUrl(state) {
  const params = new URLSearchParams([['view', 'experiments'], ['exp', state.name], ['trials', state.trials], ['seed', state.seed], ['preset', state.preset]]);
  for (const [k, v] of state.params) params.append(k, v);
  if (state.name === CUSTOM) {
    if (state.sweep) params.set('sweep', formatSweep(state.sweep));
    for (const s of state.series) params.append('series', formatSeries(s));
  }
  return params.toString();
}

/** The facade's experiment spec for a state (the engine validates it in experimentPlan). */
export function experimentSpec(state) {
  const custom = state.name === CUSTOM;
  return {
    name: state.name,
    trials: Number(state.trials),
    seed: state.seed,
    preset: state.preset,
    params: Object.fromEntries(state.params),
    sweep: custom && state.sweep ? { key: state.sweep.key, values: state.sweep.values } : null,
    series: custom && state.series.length ? state.series.map((s) => ({ label: s.label, params: Object.fromEntries(s.params) })) : null,
  };
}

/**
 * Reads the page's whole query: which view, the live view's config and view
 * parameters (the defaults when the Experiments view is shown), and the
 * Experiments view's state, with every message about bad values.
 * @returns {{ page: string, config: object, view: object, experiment: object, messages: string[] }}
 */
export function readPage(engine, schema, search, races) {
  const split = splitView(search);
  const live = readUrl(engine, schema, split.view === 'live' ? split.query : '', races);
  const list = engine.experimentList();
  const exp = split.view === 'experiments'
    ? readExperimentUrl(engine, schema, split.query, list, presetChoices(engine, schema, list))
    : { state: defaultExperiment(engine, schema, list), messages: [], conflict: null };
  const messages = [...split.messages, ...live.messages, ...exp.messages, ...(exp.conflict ? [exp.conflict] : [])];
  return { page: split.view, config: live.config, view: live.view, experiment: exp.state, messages };
}
