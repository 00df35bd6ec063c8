// Sharing a run: the link, a PNG of the boards, and episode files that
// replay exactly. An episode file carries the page's URL query (every
// parameter, the seed included), each run's engine config and its path.
// Both carry their provenance (www/shared/provenance.js): the PNG as a
// caption under the boards, the file as a `provenance` object.

import { $, download, showMessage } from '../shared/ui.js';
import { provenance, provenanceLine } from '../shared/provenance.js';

export const EPISODE_FORMAT = 'torus-search-episode';
/** Files this page writes; it reads versions 1 and 2 (both carry url_query). */
export const EPISODE_VERSION = 2;
/** Larger files are refused before they are read. */
export const MAX_EPISODE_BYTES = 64 << 20;

/** Copies `link` to the clipboard; resolves to a message for the user. */
export async function copyLink(link) {
  try {
    await navigator.clipboard.writeText(link);
    return 'Link copied: it reproduces this exact run.';
  } catch {
    return `Copy this link to share the run: ${link}`;
  }
}

/** `text` broken at spaces into lines no wider than `max` pixels in ctx's font (a long word is cut). */
export function wrapText(ctx, text, max) {
  const lines = [];
  let line = '';
  for (const word of text.split(' ')) {
    const joined = line ? `${line} ${word}` : word;
    if (ctx.measureText(joined).width <= max || !line) line = joined;
    else {
      lines.push(line);
      line = word;
    }
    while (ctx.measureText(line).width > max && line.length > 1) {
      let k = line.length - 1;
      while (k > 1 && ctx.measureText(line.slice(0, k)).width > max) k--;
      lines.push(line.slice(0, k));
      line = line.slice(k);
    }
  }
  lines.push(line);
  return lines;
}

/**
 * The boards side by side on one canvas, with a caption under them: the
 * build, the date of the export and the page's URL (every parameter).
 */
export function boardsImage(canvases, p = provenance()) {
  const w = Math.max(480, canvases.reduce((a, c) => a + c.width, 0) + 8 * (canvases.length - 1));
  const boardsH = Math.max(...canvases.map((c) => c.height));
  const out = document.createElement('canvas');
  const ctx = out.getContext('2d');
  const font = '13px system-ui, sans-serif';
  ctx.font = font;
  const lines = [provenanceLine(p), ...wrapText(ctx, p.command, w - 16)];
  out.width = w;
  out.height = boardsH + 10 + 18 * lines.length;
  ctx.fillStyle = '#0b0e11';
  ctx.fillRect(0, 0, out.width, out.height);
  let x = 0;
  for (const c of canvases) {
    ctx.drawImage(c, x, 0);
    x += c.width + 8;
  }
  ctx.font = font;
  ctx.fillStyle = '#c9d1d9';
  ctx.textBaseline = 'top';
  lines.forEach((l, i) => ctx.fillText(l, 8, boardsH + 6 + 18 * i));
  return out;
}

/** Saves the boards side by side as one PNG, with its caption. */
export function exportPng(canvases, name) {
  boardsImage(canvases).toBlob((blob) => blob && download(blob, `${name}.png`), 'image/png');
}

/** Saves an episode file: `runs` as the engine exported them, `query` the full URL query. */
export function exportEpisode({ engineVersion, query, runs, name }) {
  const [main, race] = runs;
  const data = {
    format: EPISODE_FORMAT,
    version: EPISODE_VERSION,
    engine: engineVersion,
    provenance: provenance(),
    url_query: query,
    cells: 'path entries are 0-based cell indices y*n + x; users see (x+1, y+1)',
    episode: main,
    race: race ?? null,
  };
  download(new Blob([JSON.stringify(data, null, 1)], { type: 'application/json' }), `${name}.json`);
}

/**
 * Reads an episode file; resolves to { query, path } or rejects with an
 * Error saying what is wrong. Nothing in it is evaluated.
 */
export async function readEpisode(file) {
  if (file.size > MAX_EPISODE_BYTES) throw new Error(`the file is ${file.size} bytes; episode files are at most ${MAX_EPISODE_BYTES}`);
  let data;
  try {
    data = JSON.parse(await file.text());
  } catch (err) {
    throw new Error(`it is not JSON (${err.message})`);
  }
  if (!data || typeof data !== 'object' || data.format !== EPISODE_FORMAT) throw new Error('not a torus-search episode file');
  if (data.version !== 1 && data.version !== EPISODE_VERSION) throw new Error(`episode file version ${JSON.stringify(data.version)} is not 1 or ${EPISODE_VERSION}`);
  const path = data.episode?.path;
  if (typeof data.url_query !== 'string' || !Array.isArray(path) || !path.every((c) => Number.isInteger(c) && c >= 0)) {
    throw new Error('the file lacks url_query or a path of cell indices');
  }
  return { query: data.url_query, path };
}

/**
 * Wires the share panel's buttons.
 * @param {object} o
 * @param {() => string} o.link            the page's link, up to date
 * @param {() => string} o.name            a file name for this run, without extension
 * @param {() => HTMLCanvasElement[]} o.canvases  the boards to save
 * @param {() => Promise<object>} o.episode       { engineVersion, query, runs } or null
 * @param {(query, path) => Promise<void>} o.replay  loads a query and replays, checking the path
 */
export function bindShare({ link, name, canvases, episode, replay }) {
  $('copy-link').addEventListener('click', async () => showMessage(await copyLink(link())));
  $('export-png').addEventListener('click', () => exportPng(canvases(), name()));
  $('export-json').addEventListener('click', async () => {
    const e = await episode();
    if (!e) showMessage('Could not export: the engine is not available.');
    else exportEpisode({ ...e, name: name() });
  });
  $('import-json').addEventListener('change', async (ev) => {
    const file = ev.target.files?.[0];
    ev.target.value = '';
    if (!file) return;
    try {
      const { query, path } = await readEpisode(file);
      await replay(query, path);
    } catch (err) {
      // The run on the page stays as it was.
      showMessage(`Could not import ${file.name}: ${err.message}`);
    }
  });
}

/** The message after a replay ends: does `got` match the imported path `want`? */
export function replayVerdict(got, want, timed) {
  const same = got.length === want.length && got.every((v, i) => v === want[i]);
  const note = timed ? ' (this run used a time budget per move, so the machine’s speed changes the loops per move)' : '';
  return {
    same,
    message: same
      ? `Replayed exactly: the path matches the imported episode (${got.length - 1} steps).`
      : `The replay differs from the imported episode (${got.length - 1} vs ${want.length - 1} steps)${note}.`,
  };
}
