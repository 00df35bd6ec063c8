// The whole configuration lives in the URL query string.
//
// parseParams(search) -> { config, messages }: every parameter is checked; an
// invalid value yields a message naming the parameter and its allowed range
// and the default is used instead. serializeConfig(config) -> query string
// (only values that differ from the defaults, so links stay short; `seed` is
// always written so a shared link reproduces the run).
//
// Pure module: no DOM access, so it is unit-testable in Node.

export const SQRT2 = Math.SQRT2;

/** Parameter specifications, in URL order. */
export const SPECS = [
  { key: 'n', kind: 'int', min: 3, max: 1024, def: 40, help: 'integer 3–1024' },
  { key: 'prior', kind: 'enum', values: ['gaussian', 'delta', 'uniform', 'paint'], def: 'gaussian' },
  { key: 'sigma', kind: 'float', min: 0, max: 10000, def: 5, help: 'number 0–10000 (0 = delta)' },
  { key: 'rv', kind: 'float', min: 0, max: 100, def: 1, help: 'number 0–100' },
  { key: 'start', kind: 'cell', def: [1, 1], help: '"x,y" with 1 ≤ x,y ≤ n' },
  { key: 'searcher', kind: 'enum', values: ['mcts', 'rw', 'levy', 'nsarw'], def: 'mcts' },
  { key: 'variant', kind: 'enum', values: ['cells', 'tree'], def: 'cells' },
  { key: 'rollout', kind: 'enum', values: ['rw', 'levy', 'nsarw', 'greedy'], def: 'rw' },
  { key: 'belief', kind: 'enum', values: ['prior', 'posterior'], def: 'posterior' },
  { key: 'loops', kind: 'int', min: 1, max: 1000000, def: 100, help: 'integer 1–1000000' },
  { key: 'ms', kind: 'float', min: 0, max: 60000, def: 0, help: 'number 0–60000 (0 = use loops)' },
  { key: 'c', kind: 'float', min: 0, max: 100, def: SQRT2, help: 'number 0–100' },
  { key: 'mu', kind: 'float', min: 1, max: 3, minOpen: true, def: 2, help: 'number in (1, 3]' },
  { key: 'final', kind: 'enum', values: ['visits', 'mean', 'uct'], def: 'visits' },
  { key: 'seed', kind: 'seed', def: 1n, help: 'integer 0–18446744073709551615' },
  { key: 'speed', kind: 'speed', min: 1, max: 1000000, def: 10, help: 'loops per frame 1–1000000, or "max"' },
  { key: 'autoplay', kind: 'bool', def: true, help: '1/0 or true/false' },
  // Beyond the required names: the page's own view state.
  { key: 'race', kind: 'enum', values: ['', 'mcts-cells', 'mcts-tree', 'rw', 'levy', 'nsarw'], def: '' },
  { key: 'paint', kind: 'paint', def: '', help: 'run-length encoded weight grid' },
];

const SPEC_BY_KEY = Object.fromEntries(SPECS.map((s) => [s.key, s]));
const U64_MAX = (1n << 64n) - 1n;

export function defaults() {
  const c = {};
  for (const s of SPECS) c[s.key] = Array.isArray(s.def) ? [...s.def] : s.def;
  return c;
}

/** Shortens a user-supplied value for display in a message (never as HTML). */
function shown(raw) {
  const s = String(raw);
  return s.length > 40 ? `${s.slice(0, 40)}…` : s;
}

function allowed(spec) {
  if (spec.kind === 'enum') return `one of ${spec.values.filter((v) => v !== '').join(', ')}`;
  return spec.help;
}

/** Parses one raw string for a spec. Returns {ok, value} or {ok:false}. */
export function parseValue(spec, raw, n) {
  const s = String(raw).trim();
  switch (spec.kind) {
    case 'int': {
      if (!/^[+-]?\d+$/.test(s)) return { ok: false };
      const v = Number(s);
      return Number.isSafeInteger(v) && v >= spec.min && v <= spec.max ? { ok: true, value: v } : { ok: false };
    }
    case 'float': {
      if (!/^[+-]?(\d+\.?\d*|\.\d+)(e[+-]?\d+)?$/i.test(s)) return { ok: false };
      const v = Number(s);
      if (!Number.isFinite(v) || v > spec.max) return { ok: false };
      if (spec.minOpen ? v <= spec.min : v < spec.min) return { ok: false };
      return { ok: true, value: v };
    }
    case 'enum':
      return spec.values.includes(s) ? { ok: true, value: s } : { ok: false };
    case 'cell': {
      const m = /^(\d+)\s*,\s*(\d+)$/.exec(s);
      if (!m) return { ok: false };
      const x = Number(m[1]);
      const y = Number(m[2]);
      return x >= 1 && y >= 1 && x <= n && y <= n ? { ok: true, value: [x, y] } : { ok: false };
    }
    case 'seed': {
      if (!/^\d{1,20}$/.test(s)) return { ok: false };
      const v = BigInt(s);
      return v <= U64_MAX ? { ok: true, value: v } : { ok: false };
    }
    case 'speed': {
      if (s === 'max') return { ok: true, value: 'max' };
      if (!/^\d+$/.test(s)) return { ok: false };
      const v = Number(s);
      return v >= spec.min && v <= spec.max ? { ok: true, value: v } : { ok: false };
    }
    case 'bool':
      if (['1', 'true', 'yes', 'on'].includes(s)) return { ok: true, value: true };
      if (['0', 'false', 'no', 'off'].includes(s)) return { ok: true, value: false };
      return { ok: false };
    case 'paint':
      return /^[A-Za-z0-9_-]*$/.test(s) && s.length <= 200000 ? { ok: true, value: s } : { ok: false };
    default:
      return { ok: false };
  }
}

/**
 * Parses a query string (with or without the leading "?").
 * @returns {{config: object, messages: string[]}}
 */
export function parseParams(search) {
  const params = new URLSearchParams(search);
  const config = defaults();
  const messages = [];
  const bad = (key, raw, why) => {
    const spec = SPEC_BY_KEY[key];
    const def = spec.kind === 'cell' ? spec.def.join(',') : String(spec.def);
    messages.push(`Invalid ${key}=${JSON.stringify(shown(raw))}${why ? ` (${why})` : ''}: allowed ${allowed(spec)}. Using the default ${key}=${def || '(none)'}.`);
  };
  // n first: `start` is checked against it.
  const order = ['n', ...SPECS.map((s) => s.key).filter((k) => k !== 'n')];
  for (const key of order) {
    if (!params.has(key)) continue;
    const spec = SPEC_BY_KEY[key];
    const raw = params.getAll(key).at(-1);
    const r = parseValue(spec, raw, config.n);
    if (r.ok) config[key] = r.value;
    else bad(key, raw);
  }
  for (const key of new Set(params.keys())) {
    if (!(key in SPEC_BY_KEY)) messages.push(`Unknown URL parameter ${JSON.stringify(shown(key))} ignored.`);
  }
  // Cross-field rules.
  if (config.prior === 'paint' && !config.paint) {
    messages.push('prior=paint needs a painted prior (parameter paint); using prior=gaussian.');
    config.prior = 'gaussian';
  }
  return { config, messages };
}

function fmt(spec, v) {
  if (spec.kind === 'cell') return `${v[0]},${v[1]}`;
  if (spec.kind === 'bool') return v ? '1' : '0';
  if (spec.kind === 'float') return String(+v.toPrecision(12));
  return String(v);
}

function equal(a, b) {
  return Array.isArray(a) ? a[0] === b[0] && a[1] === b[1] : a === b;
}

/** Serializes a config to a query string without the "?". */
export function serializeConfig(config, { full = false } = {}) {
  const params = new URLSearchParams();
  for (const spec of SPECS) {
    const v = config[spec.key];
    if (v === undefined) continue;
    if (!full && spec.key !== 'seed' && equal(v, spec.def)) continue;
    // Parameters that do not apply to this config are left out.
    if (!full && spec.key === 'paint' && config.prior !== 'paint') continue;
    params.set(spec.key, fmt(spec, v));
  }
  return params.toString();
}

/** A config's human summary, e.g. for the race scoreboard. */
export function describeSearcher(config) {
  if (config.searcher !== 'mcts') return config.searcher.toUpperCase();
  const budget = config.ms > 0 ? `${config.ms} ms` : `L=${config.loops}`;
  return `MCTS ${config.variant} · ${config.rollout} rollouts · ${budget}`;
}

// ---- Painted prior: run-length encoding of a weight grid (levels 0–15). ----

const B64 = 'ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789-_';

/** Encodes Uint8Array levels (0–15) as base64url runs: [level, run-1] pairs, run ≤ 4096. */
export function encodePaint(levels) {
  let out = '';
  let i = 0;
  while (i < levels.length) {
    const lv = levels[i] & 15;
    let run = 1;
    while (i + run < levels.length && (levels[i + run] & 15) === lv && run < 4096) run++;
    // 18 bits: 4 bits level + 12 bits (run - 1), padded into three base64 digits.
    const word = (lv << 12) | (run - 1);
    out += B64[(word >> 12) & 63] + B64[(word >> 6) & 63] + B64[word & 63];
    i += run;
  }
  return out;
}

/** Decodes encodePaint output into a Uint8Array of n*n levels, or null if malformed. */
export function decodePaint(s, n) {
  if (s.length % 3 !== 0) return null;
  const levels = new Uint8Array(n * n);
  let i = 0;
  for (let k = 0; k < s.length; k += 3) {
    const d = [0, 1, 2].map((j) => B64.indexOf(s[k + j]));
    if (d.some((x) => x < 0)) return null;
    const word = (d[0] << 12) | (d[1] << 6) | d[2];
    const lv = word >> 12;
    const run = (word & 4095) + 1;
    if (lv > 15 || i + run > levels.length) return null;
    levels.fill(lv, i, i + run);
    i += run;
  }
  return i === levels.length ? levels : null;
}
