// The board's colours under colour-vision deficiency, in Node (no browser):
// every colour is simulated with the Machado, Oliveira & Fernandes (2009)
// matrices at full severity (protanopia, deuteranopia, tritanopia), applied
// in linear sRGB, and compared in OKLab (ΔE = Euclidean distance; black to
// white is 1.0, a just-noticeable difference about 0.02).
//
// - The marks' colours (www/live/marks.js INK) are pairwise at least
//   MARK_FLOOR apart under normal vision and each deficiency.
// - Each heat palette (the engine's lookup tables) keeps its lightness
//   rising from 0 to the top under each deficiency, so the scale reads the
//   same way, with its ends at least RAMP_FLOOR apart.
// - The mass palettes (prior, posterior) and the counts palette (visits)
//   differ on average by at least PALETTE_FLOOR, so the layer shown can be told.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import path from 'node:path';
import { test } from 'node:test';
import { fileURLToPath } from 'node:url';
import { INK } from '../../www/live/marks.js';

const PKG = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../../www/pkg');
const engine = await import(path.join(PKG, 'torus_search.js'));
engine.initSync({ module: readFileSync(path.join(PKG, 'torus_search_bg.wasm')) });

/** Five just-noticeable differences: marks are told apart at a glance. */
const MARK_FLOOR = 0.1;
const RAMP_FLOOR = 0.5;
const PALETTE_FLOOR = 0.08;
/** Lightness may dip this much between neighbouring levels (gamut clipping under tritanopia). */
const LIGHTNESS_SLACK = 0.005;

/** Machado et al. 2009, severity 1.0 (rows act on linear RGB). */
export const MACHADO = {
  normal: [[1, 0, 0], [0, 1, 0], [0, 0, 1]],
  protanopia: [[0.152286, 1.052583, -0.204868], [0.114503, 0.786281, 0.099216], [-0.003882, -0.048116, 1.051998]],
  deuteranopia: [[0.367322, 0.860646, -0.227968], [0.280085, 0.672501, 0.047413], [-0.01182, 0.04294, 0.968881]],
  tritanopia: [[1.255528, -0.076749, -0.178779], [-0.078411, 0.930809, 0.147602], [0.004733, 0.691367, 0.3039]],
};

const linear = (c) => {
  const v = c / 255;
  return v <= 0.04045 ? v / 12.92 : ((v + 0.055) / 1.055) ** 2.4;
};

/** OKLab of an sRGB colour [r, g, b] (0–255) as seen with `vision`. */
export function oklab(rgb, vision = 'normal') {
  const lin = rgb.map(linear);
  const [r, g, b] = MACHADO[vision].map((row) => Math.min(1, Math.max(0, row[0] * lin[0] + row[1] * lin[1] + row[2] * lin[2])));
  const l = Math.cbrt(0.4122214708 * r + 0.5363325363 * g + 0.0514459929 * b);
  const m = Math.cbrt(0.2119034982 * r + 0.6806995451 * g + 0.1073969566 * b);
  const s = Math.cbrt(0.0883024619 * r + 0.2817188376 * g + 0.6299787005 * b);
  return [
    0.2104542553 * l + 0.793617785 * m - 0.0040720468 * s,
    1.9779984951 * l - 2.428592205 * m + 0.4505937099 * s,
    0.0259040371 * l + 0.7827717662 * m - 0.808675766 * s,
  ];
}

export const deltaE = (a, b) => Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
const hex = (h) => [1, 3, 5].map((i) => parseInt(h.slice(i, i + 2), 16));
const VISIONS = Object.keys(MACHADO);

test('the OKLab and CVD arithmetic agree with known values', () => {
  // White is L = 1, black L = 0; sRGB red in OKLab is (0.628, 0.225, 0.126) (Ottosson).
  assert.ok(Math.abs(oklab([255, 255, 255])[0] - 1) < 1e-3);
  assert.ok(deltaE(oklab([255, 0, 0]), [0.62796, 0.22486, 0.12585]) < 1e-3);
  // Greys are unchanged by every simulation (each matrix's rows sum to 1).
  for (const v of VISIONS) assert.ok(deltaE(oklab([128, 128, 128], v), oklab([128, 128, 128])) < 2e-3, v);
  // Red and green, far apart to normal vision, collapse for a deuteranope:
  // the test can see the very confusion it guards against.
  const [red, green] = [[220, 50, 40], [60, 160, 60]];
  assert.ok(deltaE(oklab(red), oklab(green)) > 0.25);
  assert.ok(deltaE(oklab(red, 'deuteranopia'), oklab(green, 'deuteranopia')) < 0.15);
});

test(`the marks' colours are pairwise at least ${MARK_FLOOR} apart (OKLab ΔE) under each colour-vision deficiency`, () => {
  const names = Object.keys(INK);
  assert.ok(names.length >= 6, 'every distinct mark colour is in INK');
  const worst = [];
  for (const v of VISIONS) {
    let min = [Infinity, ''];
    for (let i = 0; i < names.length; i++) {
      for (let j = i + 1; j < names.length; j++) {
        const d = deltaE(oklab(hex(INK[names[i]]), v), oklab(hex(INK[names[j]]), v));
        if (d < min[0]) min = [d, `${names[i]}/${names[j]}`];
      }
    }
    worst.push(`${v}: ${min[0].toFixed(3)} (${min[1]})`);
    assert.ok(min[0] >= MARK_FLOOR, `${v}: ${min[1]} only ${min[0].toFixed(3)} apart`);
  }
  console.log(`# closest mark colours: ${worst.join('; ')}`);
});

test('the old picture fails the same check (so the check can fail)', () => {
  // The page before: the start, the practice target and the rollouts in near-identical
  // light blues, the target pink, the searcher white.
  const old = { white: '#ffffff', start: '#7fd4ff', practice: '#7fd4ff', target: '#ff5fa2', rollout: '#78c8ff' };
  const names = Object.keys(old);
  let min = Infinity;
  for (let i = 0; i < names.length; i++) for (let j = i + 1; j < names.length; j++) min = Math.min(min, deltaE(oklab(hex(old[names[i]]), 'deuteranopia'), oklab(hex(old[names[j]]), 'deuteranopia')));
  assert.ok(min < MARK_FLOOR, `the old marks were ${min.toFixed(3)} apart at the closest`);
});

test(`each heat palette rises in lightness under each deficiency, its ends at least ${RAMP_FLOOR} apart`, () => {
  for (const { palette, name } of engine.schema().layers) {
    const lut = engine.paletteLut(palette);
    const at = (i) => [lut[4 * i], lut[4 * i + 1], lut[4 * i + 2]];
    for (const v of VISIONS) {
      let prev = -Infinity;
      for (let i = 0; i < 256; i++) {
        const L = oklab(at(i), v)[0];
        assert.ok(L >= prev - LIGHTNESS_SLACK, `${name} (${palette}), ${v}: lightness falls at level ${i}`);
        prev = Math.max(prev, L);
      }
      const span = deltaE(oklab(at(0), v), oklab(at(255), v));
      assert.ok(span >= RAMP_FLOOR, `${name} (${palette}), ${v}: ends ${span.toFixed(3)} apart`);
    }
  }
});

test(`the mass and count palettes differ by at least ${PALETTE_FLOOR} on average under each deficiency`, () => {
  const layers = engine.schema().layers.filter((l) => !l.binary);
  const masses = new Set(layers.filter((l) => !l.counts).map((l) => l.palette));
  const counts = new Set(layers.filter((l) => l.counts).map((l) => l.palette));
  assert.ok(masses.size && counts.size);
  for (const a of masses) {
    for (const b of counts) {
      const [la, lb] = [engine.paletteLut(a), engine.paletteLut(b)];
      for (const v of VISIONS) {
        let sum = 0;
        let k = 0;
        for (let i = 0; i < 256; i += 5, k++) sum += deltaE(oklab([la[4 * i], la[4 * i + 1], la[4 * i + 2]], v), oklab([lb[4 * i], lb[4 * i + 1], lb[4 * i + 2]], v));
        assert.ok(sum / k >= PALETTE_FLOOR, `${a} vs ${b}, ${v}: ${(sum / k).toFixed(3)}`);
      }
    }
  }
});
