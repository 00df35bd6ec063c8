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

/** The page's own parameters: key → { def, help, parse(text) → value | undefined, text(value) }. */
export function viewSpecs(races) {
  return {
    speed: {
      def: 10,
      help: 'loops per frame, an integer in 1..=1000000, or max',
      parse: (s) => (s === 'max' ? 'max' : /^\d{1,7}$/.test(s) && +s >= 1 && +s <= 1e6 ? +s : undefined),
      text: String,
    },
    autoplay: {
      def: true,
      help: 'one of 1, 0, true, false, yes, no, on, off',
      parse: (s) => BOOL[s],
      text: (v) => (v ? '1' : '0'),
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
    if (key in specs) {
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
  return { config, view, messages };
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
