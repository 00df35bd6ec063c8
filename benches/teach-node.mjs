#!/usr/bin/env node
// The teaching benchmarks of benches/teach.rs, in wasm under Node.js and
// through the facade the page calls: seeking anywhere in a 200-move
// episode at N = 40, L = 100 (Race.seek), and exporting a tree of 10^5
// nodes (Race.tree as objects, Race.treeColumns as typed arrays). Timed
// here, never in tests. Needs `make build` (www/pkg). Prints one JSON object.
// Usage: node benches/teach-node.mjs
import { readFileSync, existsSync } from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { performance } from 'node:perf_hooks';

const ROOT = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const PKG = path.join(ROOT, 'www/pkg');
if (!existsSync(path.join(PKG, 'torus_search_bg.wasm'))) {
  console.error('error: www/pkg is missing; run `make build` first');
  process.exit(2);
}
const wasm = await import(path.join(PKG, 'torus_search.js'));
wasm.initSync({ module: readFileSync(path.join(PKG, 'torus_search_bg.wasm')) });

// bench::teach_config: N = 40, L = 100, a uniform prior.
const CONFIG = { prior: 'uniform', loops: 100 };
const PHASES = [null, 'select', 'expand', 'rollout', 'backup'];

/** A fixed sequence of numbers in [0, 1) (a linear congruential generator). */
function* lcg(seed) {
  let x = seed >>> 0;
  for (;;) {
    x = (Math.imul(x, 1664525) + 1013904223) >>> 0;
    yield x / 2 ** 32;
  }
}

function seeking() {
  const race = new wasm.Race([CONFIG]);
  let t = performance.now();
  while (race.timeline().move < 200 && race.running() > 0) race.stepMove();
  const playMs = performance.now() - t;
  const moves = race.timeline().end.move;
  const r = lcg(7);
  const times = [];
  let refused = 0;
  for (let i = 0; i < 200; i++) {
    const point = {
      move: Math.floor(r.next().value * Math.max(moves, 1)),
      loop: Math.floor(r.next().value * 100),
      phase: PHASES[Math.floor(r.next().value * 5)],
    };
    t = performance.now();
    try {
      race.seek(point);
    } catch {
      refused += 1; // an escape's decision runs no loops: its start instead
      race.seek({ move: point.move });
    }
    times.push(performance.now() - t);
  }
  times.sort((a, b) => a - b);
  const memory = race.timeline().runs[0].memory;
  return {
    moves,
    play_ms: playMs,
    seeks: times.length,
    refused,
    mean_ms: times.reduce((a, b) => a + b, 0) / times.length,
    median_ms: times[times.length >> 1],
    max_ms: times[times.length - 1],
    snapshot_bytes: memory.bytes,
    snapshots: memory.snapshots,
  };
}

function treeExport() {
  const race = new wasm.Race([{ ...CONFIG, variant: 'tree', loops: 100000, tree_nodes: 100016 }]);
  race.advance(99999);
  const time = (f) => {
    f();
    const t = performance.now();
    let out;
    for (let i = 0; i < 5; i++) out = f();
    return [out, (performance.now() - t) / 5];
  };
  const all = { max_nodes: 1 << 20 };
  const [objects, objectsMs] = time(() => race.tree(0, all));
  const [columns, columnsMs] = time(() => race.treeColumns(0, all));
  const [cut, cutMs] = time(() => race.tree(0, { max_nodes: 2000 }));
  return {
    nodes: objects.nodes.length,
    objects_ms: objectsMs,
    columns_nodes: columns.visits.length,
    columns_ms: columnsMs,
    cut_nodes: cut.nodes.length,
    cut_ms: cutMs,
  };
}

console.log(JSON.stringify({ seek: seeking(), tree_export: treeExport() }, null, 2));
