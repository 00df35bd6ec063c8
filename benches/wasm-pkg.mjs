// What the Node benchmarks share: the repository root, the `--seconds S`
// flag, and the engine of the page (www/pkg) loaded in Node.
import { existsSync, readFileSync } from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

export const ROOT = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');

/** `--seconds S` from `args` (default `def`), or exit 2 naming the range. */
export function secondsArg(args, def) {
  const at = args.indexOf('--seconds');
  const seconds = at >= 0 ? Number(args[at + 1]) : def;
  if (!(seconds > 0 && seconds <= 600)) {
    console.error(`error: --seconds must be a number in (0, 600], got ${args[at + 1]}`);
    process.exit(2);
  }
  return seconds;
}

/** The wasm package the page uses, instantiated in Node; exits 2 if it is not built. */
export async function loadPkg() {
  const pkg = path.join(ROOT, 'www/pkg');
  if (!existsSync(path.join(pkg, 'torus_search_bg.wasm'))) {
    console.error('error: www/pkg is missing; run `make build` first');
    process.exit(2);
  }
  const wasm = await import(path.join(pkg, 'torus_search.js'));
  wasm.initSync({ module: readFileSync(path.join(pkg, 'torus_search_bg.wasm')) });
  return wasm;
}
