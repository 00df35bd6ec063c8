// Small DOM and number-formatting helpers shared by the page's modules.
// Text only: nothing here writes HTML.

import { setBuild } from './provenance.js';

export const $ = (id) => document.getElementById(id);

/** Replaces a <select>'s options with `[value, label]` pairs (text only). */
export function fillSelect(el, options) {
  el.replaceChildren(
    ...options.map(([value, label]) => {
      const o = document.createElement('option');
      o.value = value;
      o.textContent = label;
      return o;
    }),
  );
}

/** Sets an element's text (by id or element) only when it changes, to spare layout. */
export function setText(el, text) {
  const node = typeof el === 'string' ? $(el) : el;
  if (node.textContent !== text) node.textContent = text;
}

/** Shows a message above the board (empty hides it); `append` adds a line. */
export function showMessage(text, { append = false } = {}) {
  const el = $('message');
  el.textContent = append && !el.hidden && el.textContent ? `${el.textContent}\n${text}` : text;
  el.hidden = !text;
}

/** Shows the engine's build (version and commit) in the header and the footer, and keeps it for exports. */
export function showBuild(engine) {
  const b = engine.buildInfo();
  setBuild(b);
  setText('version', `v${b.version}`);
  setText('build-info', `Engine: ${b.label}.`);
}

/** The page cannot run: says why, in the message and the badge. Returns null. */
export function showFatal(text) {
  document.body.dataset.state = 'error';
  setText('state-badge', 'error');
  showMessage(text);
  return null;
}

const INT_FORMAT = new Intl.NumberFormat('en-US', { maximumFractionDigits: 0 });

/** 12,345 */
export const fmtInt = (v) => INT_FORMAT.format(Math.round(v));

/** A rate with a k/M/G suffix. */
export function fmtRate(v) {
  if (v >= 1e9) return `${(v / 1e9).toFixed(2)} G`;
  if (v >= 1e6) return `${(v / 1e6).toFixed(2)} M`;
  if (v >= 1e4) return `${(v / 1e3).toFixed(1)} k`;
  return v.toFixed(0);
}

/** A number for the decision panel: ∞ for missing or infinite values. */
export function fmtNum(v, digits = 4) {
  if (v === null || v === undefined || !Number.isFinite(v)) return '∞';
  if (v === 0) return '0';
  if (Math.abs(v) < 1e-3) return v.toExponential(2);
  return v.toFixed(digits);
}

/** Offers a blob as a download named `name`. */
export function download(blob, name) {
  const url = URL.createObjectURL(blob);
  const a = document.createElement('a');
  a.href = url;
  a.download = name;
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 5000);
}
