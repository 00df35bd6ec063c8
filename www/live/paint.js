// Painting a prior on the grid: a brush of weight levels 0–15 per cell
// (an editor, not game logic). The engine encodes the levels as the `paint`
// parameter, decodes them, and colours the preview.

export class Painter {
  /** @param {object} engine the page's wasm module */
  constructor(engine) {
    this.engine = engine;
    this.levels = null;
    this.n = 0;
    this.preview = null; // RGBA while a stroke is under way
  }

  /** Takes up a config's painting (or an empty grid). */
  load(config) {
    this.n = config.n;
    try {
      this.levels = this.engine.decodePaint(config.paint, config.n);
    } catch {
      this.levels = new Uint8Array(config.n * config.n);
    }
  }

  /** Clears the grid. */
  clear(n) {
    this.n = n;
    this.levels = new Uint8Array(n * n);
    this.preview = null;
  }

  /** Paints (or erases) a round brush of `radius` cells at cell index `idx`, wrapping. */
  stamp(idx, radius, erase) {
    const n = this.n;
    const cx = idx % n;
    const cy = Math.floor(idx / n);
    const r = Math.max(0, radius);
    for (let dy = -r; dy <= r; dy++) {
      for (let dx = -r; dx <= r; dx++) {
        const d2 = dx * dx + dy * dy;
        if (d2 > r * r + r) continue;
        const i = ((cy + dy + n) % n) * n + ((cx + dx + n) % n);
        const add = Math.max(1, Math.round(4 * (1 - Math.sqrt(d2) / (r + 1))));
        this.levels[i] = erase ? 0 : Math.min(15, this.levels[i] + add);
      }
    }
    this.preview = this.engine.colorizeValues(Float64Array.from(this.levels), 'viridis', 'linear', 60, 255);
  }

  /** A painting of one blob at the centre (so prior=paint is valid at once); its text. */
  blob(n) {
    this.clear(n);
    this.stamp(Math.floor(n / 2) * n + Math.floor(n / 2), Math.max(1, Math.round(n / 10)), false);
    this.preview = null;
    return this.encode();
  }

  /** True when some cell has weight. */
  painted() {
    return this.levels.some((v) => v > 0);
  }

  /** The `paint` parameter's text for the current grid. */
  encode() {
    return this.engine.encodePaint(this.levels);
  }
}
