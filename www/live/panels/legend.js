// The legend beside the board: the heat layer shown, with its palette as
// drawn (over the board's background) and a scale from 0 to its largest
// value as the engine measured it, and an entry with its icon (the mark's
// own painter) for every mark drawn since the run started. Each entry
// carries data-layer / data-mark, so a test can hold the board to it.

import { setText, fmtInt } from '../../shared/ui.js';
import { drawColorbar } from '../renderer.js';
import { MARKS, paintIcon } from '../marks.js';

const BACKGROUND = [16, 20, 24];

function fmtValue(v, counts) {
  if (counts) return fmtInt(v);
  if (v === 0) return '0';
  return v < 0.01 ? v.toExponential(1) : v.toFixed(3);
}

/** The palette as the board shows it: level i at its alpha over the background. */
function shownLut(lut, [lo, hi]) {
  const out = new Uint8Array(1024);
  for (let i = 0; i < 256; i++) {
    const a = lo === 255 && hi === 255 ? 1 : i === 0 ? 0 : (lo + ((hi - lo) * i) / 255) / 255;
    for (let k = 0; k < 3; k++) out[4 * i + k] = Math.round(BACKGROUND[k] * (1 - a) + lut[4 * i + k] * a);
    out[4 * i + 3] = 255;
  }
  return out;
}

export class Legend {
  /**
   * @param {object} schema the engine's schema (its `layers`)
   * @param {(palette) => Uint8Array} lut a palette's 256×RGBA table
   * @param {HTMLElement} el where the legend goes
   */
  constructor(schema, lut, el) {
    this.info = new Map(schema.layers.map((l) => [l.name, l]));
    this.lut = lut;
    this.el = el;
    this.heatKey = null;
    this.marks = new Set();
    this.heat = this.heatEntry();
    this.none = Object.assign(document.createElement('p'), { className: 'note', textContent: 'No colours: pick a layer above to colour the cells.' });
    this.list = Object.assign(document.createElement('ul'), { className: 'marks' });
    el.replaceChildren(this.heat.entry, this.none, this.list);
  }

  heatEntry() {
    const entry = document.createElement('div');
    entry.className = 'entry heat';
    const name = document.createElement('span');
    name.className = 'name';
    const bar = document.createElement('canvas');
    const ticks = document.createElement('div');
    ticks.className = 'ticks';
    const lo = document.createElement('span');
    const hi = document.createElement('span');
    ticks.append(lo, hi);
    const note = document.createElement('p');
    note.className = 'note';
    entry.append(name, bar, ticks, note);
    return { entry, name, bar, lo, hi, note };
  }

  /** Forgets the marks of the last run (a new run). */
  reset() {
    this.marks = new Set();
    this.list.replaceChildren();
  }

  /**
   * Shows `heat` ({ layer, scale, max, flat } as drawn, or null) and adds an
   * entry for each mark in `drawn` not listed yet (MARKS keys).
   */
  update(heat, drawn) {
    this.showHeat(heat);
    for (const key of drawn) {
      if (this.marks.has(key) || !MARKS[key]) continue;
      this.marks.add(key);
      this.list.append(this.markEntry(key));
    }
    // Legend order, whatever order the marks appeared in.
    const order = Object.keys(MARKS);
    const items = [...this.list.children];
    if (items.some((li, i) => i && order.indexOf(li.dataset.mark) < order.indexOf(items[i - 1].dataset.mark))) {
      items.sort((a, b) => order.indexOf(a.dataset.mark) - order.indexOf(b.dataset.mark));
      this.list.replaceChildren(...items);
    }
  }

  markEntry(key) {
    const [label, meaning] = MARKS[key];
    const li = document.createElement('li');
    li.dataset.mark = key;
    li.title = meaning;
    const icon = document.createElement('canvas');
    icon.setAttribute('aria-hidden', 'true');
    paintIcon(icon, key, Math.min(window.devicePixelRatio || 1, 3));
    li.append(icon, label);
    return li;
  }

  showHeat(heat) {
    const h = this.heat;
    h.entry.hidden = !heat;
    this.none.hidden = !!heat;
    if (!heat) {
      delete h.entry.dataset.layer;
      return;
    }
    const info = this.info.get(heat.layer);
    h.entry.dataset.layer = heat.layer;
    const key = `${heat.layer}:${heat.scale}`;
    if (key !== this.heatKey) {
      this.heatKey = key;
      setText(h.name, `Colours: ${info.label}${heat.scale === 'log' ? ' (log scale)' : ''}`);
      drawColorbar(h.bar, shownLut(this.lut(info.palette), info.alpha));
    }
    setText(h.lo, '0');
    setText(h.hi, `${fmtValue(heat.max, info.counts)}${info.counts ? ' visits' : ' per cell'}`);
    setText(h.note, heat.flat ? 'Every cell alike (a uniform layer), so it is drawn dim.' : '');
  }
}
