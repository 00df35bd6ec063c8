// The door into the wasm engine (www/pkg, built from src/wasm.rs). The page
// loads it for the schema, config edits, palettes and batch summaries; the
// search worker (www/workers/search-worker.js) loads its own instance for the runs;
// the trial workers load one each for batches. No game logic lives here.

import init, * as wasm from '../pkg/torus_search.js';

let ready = null;
let compiled = null;
let schemaCache = null;

/**
 * Loads and instantiates the wasm module once; resolves to the module namespace.
 * `module`: an already compiled WebAssembly.Module (the page hands its own to
 * the workers, so the bytes are fetched and compiled once).
 */
export function loadEngine(module = null) {
  ready ??= (async () => {
    let m = module;
    if (!m) {
      const url = new URL('../pkg/torus_search_bg.wasm', import.meta.url);
      const res = await fetch(url);
      if (!res.ok) throw new Error(`${url.pathname}: HTTP ${res.status}`);
      m = await WebAssembly.compile(await res.arrayBuffer());
    }
    compiled = m;
    await init({ module_or_path: m });
    return wasm;
  })();
  return ready;
}

/** The compiled module (after loadEngine), to share with workers. */
export function engineModule() {
  return compiled;
}

/** The engine's schema: parameters, searchers, layers, palettes, scales (after loadEngine). */
export function schema() {
  schemaCache ??= wasm.schema();
  return schemaCache;
}

let stylesCache = null;

/** How chart series are drawn: [{ colour, dash, marker }] for the first 100 series, as the CLI's charts (after loadEngine). */
export function seriesStyles() {
  stylesCache ??= wasm.seriesStyles(100);
  return stylesCache;
}

/** Turns a caught exception into a readable message, using the Rust panic text if there is one. */
export function describeError(err) {
  if (err instanceof WebAssembly.RuntimeError && compiled) {
    let panic = null;
    let oom = null;
    let memory = null;
    try {
      panic = wasm.lastPanic();
      oom = wasm.lastOutOfMemory();
      memory = wasm.memoryBytes();
    } catch {
      /* the module may be unusable after a trap */
    }
    if (!panic && oom) {
      const mib = (b) => `${(b / 2 ** 20).toFixed(0)} MiB`;
      return `The engine ran out of memory: it could not allocate ${mib(oom)} more, with ${mib(memory ?? 0)} of WebAssembly memory in use (4096 MiB at most). Restart to try again, with a smaller lattice or fewer tree nodes.`;
    }
    return `The engine crashed (wasm panic): ${(panic || err.message).replace(/\s*\n\s*/g, ' ')}. Restart to try again; if it persists please report it with the copied link.`;
  }
  return err && err.message ? err.message : String(err);
}
