// The legend: a colour bar per heat layer drawn, with its range as the
// engine measured it, and the markers' key.

import { $, setText, fmtInt } from '../../shared/ui.js';
import { drawColorbar } from '../renderer.js';

const MARKS = [['m-searcher', 'searcher'], ['m-start', 'start'], ['m-target', 'target'], ['m-practice', 'practice target'], ['m-path', 'path'], ['m-rollout', 'rollout']];
const BACKGROUND = [16, 20, 24];

function fmtValue(v, counts) {
  if (counts) return fmtInt(v);
  if (v === 0) return '0';
  return v < 0.01 ? v.toExponential(1) : v.toFixed(3);
}

export class Legend {
  /**
   * @param {object} schema the engine's schema (its `layers`)
   * @param {(palette) => Uint8Array} lut a palette's 256×RGBA table
   */
  constructor(schema, lut) {
    this.info = new Map(schema.layers.map((l) => [l.name, l]));
    this.lut = lut;
    this.key = '';
  }

  /** Shows `layers`: [{ layer, scale, min_nonzero, max }] as drawn, bottom to top. */
  update(layers) {
    const el = $('legend');
    // Rebuild the DOM only when the set of layers changes; otherwise update the ticks.
    const key = layers.map((l) => `${l.layer}:${l.scale}`).join('|');
    if (key !== this.key) {
      this.key = key;
      const frag = document.createDocumentFragment();
      for (const l of layers) {
        const info = this.info.get(l.layer);
        const entry = document.createElement('div');
        entry.className = 'entry';
        const name = document.createElement('span');
        name.textContent = info.binary ? info.label : `${info.label}${l.scale === 'log' ? ' (log)' : ''}`;
        const bar = document.createElement('canvas');
        const lut = this.lut(info.palette);
        if (info.binary) {
          // Two swatches: the background, and the top colour at the layer's alpha over it.
          const a = info.alpha[1] / 255;
          const mix = BACKGROUND.map((c, k) => Math.round(c * (1 - a) + lut[1020 + k] * a));
          const half = (rgb) => Array.from({ length: 128 }, () => [...rgb, 255]).flat();
          drawColorbar(bar, Uint8Array.from([...half(BACKGROUND), ...half(mix)]));
        } else drawColorbar(bar, lut);
        const ticks = document.createElement('div');
        ticks.className = 'ticks';
        ticks.append(document.createElement('span'), document.createElement('span'));
        entry.append(name, bar, ticks);
        frag.append(entry);
      }
      const marks = document.createElement('div');
      marks.className = 'marks';
      for (const [cls, label] of MARKS) {
        const m = document.createElement('span');
        m.className = cls;
        m.textContent = label;
        marks.append(m);
      }
      frag.append(marks);
      el.replaceChildren(frag);
    }
    layers.forEach((l, i) => {
      const info = this.info.get(l.layer);
      const [lo, hi] = el.children[i].querySelector('.ticks').children;
      if (info.binary) {
        setText(lo, 'no');
        setText(hi, 'within rᵥ of the path');
      } else {
        setText(lo, l.scale === 'stretch' ? fmtValue(l.min_nonzero, true) : '0');
        setText(hi, `${fmtValue(l.max, info.counts)}${info.counts ? '' : ' per cell'}`);
      }
    });
  }
}
