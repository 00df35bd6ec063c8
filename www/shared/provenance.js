// Where the page's exports come from: the engine's build (version, git
// commit, a mark for uncommitted changes), the date of the export and the
// page's URL (which holds every parameter, as a command line does). Every
// export carries it: episode files, board PNGs, chart SVGs and PNGs; the
// engine stamps results JSON and CSV itself (src/experiment/provenance.rs).
// No DOM here, so workers and Node tests may import it.

let build = { version: 'unknown', commit: 'unknown', dirty: null, label: 'torus-search (engine not loaded)' };

/** Records the engine's build (engine.buildInfo()): main.js calls it once. */
export function setBuild(info) {
  build = info;
}

/** The engine's build: { version, commit, dirty, label }. */
export function currentBuild() {
  return build;
}

/** `d` as UTC, ISO 8601 to the second, as the CLI writes dates. */
export function utcDate(d = new Date()) {
  return d.toISOString().replace(/\.\d{3}Z$/, 'Z');
}

/** The provenance of an export made now: { version, commit, dirty, date, command } (the JSON's field names). */
export function provenance(command = globalThis.location?.href ?? 'the page') {
  return { version: build.version, commit: build.commit, dirty: build.dirty, date: utcDate(), command };
}

/** A provenance in one line, for captions: "torus-search 0.1.0, commit 0123456789ab · 2025-01-31T12:00:00Z". */
export function provenanceLine(p = provenance()) {
  const commit = p.commit === 'unknown' ? 'commit unknown' : `commit ${p.commit.slice(0, 12)}`;
  return `torus-search ${p.version}, ${commit}${p.dirty ? ' (uncommitted changes)' : ''} · ${p.date}`;
}
