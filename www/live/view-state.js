// What the page shows, as opposed to what it runs: ONE heat layer at a time
// (a switch of chips by the board, one per layer of the engine's schema that
// the run has; clicking the one shown turns the colours off), the yes/no
// layers as a hatch over it (never a second colour ramp), the log scale, the
// path, rollout traces, arrows, grid, reveal and the periodic view. It turns
// them into the frame request the controller sends with each frame.

import { $ } from '../shared/ui.js';

/** The heat layer shown on first load. */
const DEFAULT_HEAT = 'prior';
/** The teaching view's heat layer: the visits of the imagined searches. */
const TEACHING_HEAT = 'visits';
const OPTION_IDS = ['layer-path', 'layer-intent', 'layer-grid', 'reveal', 'tiling', 'log-scale', 'layer-arrows'];
const TRACE_IDS = ['layer-rollouts', 'layer-practice'];
/** A box by its name in a link: a layer's name, or an option's id. */
const boxOf = (name) => document.getElementById(OPTION_IDS.includes(name) || TRACE_IDS.includes(name) ? name : `layer-${name}`) ?? document.getElementById(name);

/** A yes/no layer is a mask for the hatch: opaque where yes. */
const MASK_ALPHA = [0, 255];

export class ViewState {
  /**
   * @param {object} schema the engine's schema (its `layers`)
   * @param {{ redraw: () => void, traces: () => void }} on  called when a
   *   view option changes; `traces` when a trace layer is ticked or
   *   unticked (a run keeps traces from its start: see traceCount)
   */
  constructor(schema, on) {
    this.layers = schema.layers;
    this.heats = this.layers.filter((l) => !l.binary);
    this.masks = new Set(this.layers.filter((l) => l.binary).map((l) => l.name));
    const chips = document.createDocumentFragment();
    const checks = document.createDocumentFragment();
    for (const l of this.layers) {
      const label = document.createElement('label');
      const input = document.createElement('input');
      input.type = 'checkbox';
      input.id = `layer-${l.name}`;
      input.dataset.layer = l.name;
      if (l.binary) {
        label.append(input, ` ${l.label} (hatched)`);
        input.addEventListener('change', on.redraw);
        checks.append(label);
      } else {
        label.className = 'chip';
        input.checked = l.name === DEFAULT_HEAT;
        label.append(input, ` ${l.label}`);
        input.addEventListener('change', () => this.pick(input.checked ? l.name : null, on.redraw));
        chips.append(label);
      }
    }
    $('heat-switch').append(chips);
    $('layer-checks').prepend(checks);
    for (const id of OPTION_IDS) $(id).addEventListener('change', on.redraw);
    for (const id of TRACE_IDS) $(id).addEventListener('change', on.traces);
  }

  /** Shows heat layer `name` alone (null: none). */
  pick(name, then = () => {}) {
    for (const l of this.heats) $(`layer-${l.name}`).checked = l.name === name;
    then();
  }

  /** The heat layer shown, or null. */
  heat() {
    return this.heats.find((l) => $(`layer-${l.name}`).checked)?.name ?? null;
  }

  /**
   * Shows a chip for each heat layer the run has (`names`: the engine's
   * list); a heat layer it lacks gives way to the first it has.
   */
  setAvailable(names) {
    const has = new Set(names);
    for (const l of this.heats) $(`layer-${l.name}`).closest('label').hidden = !has.has(l.name);
    const heat = this.heat();
    if (heat && !has.has(heat)) this.pick(this.heats.find((l) => has.has(l.name))?.name ?? null);
  }

  /** Layers to draw, bottom to top, as frame requests: the heat layer, then the hatched ones. */
  layerRequests() {
    const log = $('log-scale').checked;
    return this.layers
      .filter((l) => $(`layer-${l.name}`).checked)
      .map((l) => ({
        layer: l.name,
        palette: l.palette,
        // Counts from 0, linear or logarithmic: never from their minimum.
        scale: l.counts && log ? 'log' : 'linear',
        alpha: l.binary ? MASK_ALPHA : l.alpha,
      }));
  }

  /** What each frame must carry: { layers, traces, intent }. */
  frameView() {
    return {
      layers: this.layerRequests(),
      traces: $('layer-rollouts').checked || $('layer-practice').checked,
      intent: $('layer-intent').checked,
    };
  }

  /**
   * How many rollout traces a run keeps (its keep_traces) for the traces
   * drawn: `k` (the config's keep_traces, at least 1) with the rollouts
   * shown, 1 for the practice target alone, else none.
   */
  traceCount(k) {
    if ($('layer-rollouts').checked) return Math.max(1, k);
    return $('layer-practice').checked ? 1 : 0;
  }

  /** The drawing options. */
  options() {
    return {
      path: $('layer-path').checked,
      intent: $('layer-intent').checked,
      rollouts: $('layer-rollouts').checked,
      practice: $('layer-practice').checked,
      arrows: $('layer-arrows').checked,
      grid: $('layer-grid').checked,
      reveal: $('reveal').checked,
      tiling: $('tiling').checked,
      masks: this.masks,
    };
  }

  /** Every box of the view (heat chips, hatched layers, options, traces): their ids without `layer-`. */
  boxes() {
    return [...this.layers.map((l) => `layer-${l.name}`), ...OPTION_IDS, ...TRACE_IDS].map((id) => id.replace(/^layer-/, ''));
  }

  /** What is ticked, for a link: the names of the ticked boxes joined by commas, or '' when it is the page's default. */
  shown() {
    const on = this.boxes().filter((b) => boxOf(b).checked).join(',');
    this.defaults ??= on;
    return on === this.defaults ? '' : on;
  }

  /**
   * Ticks exactly the boxes named in `text` (a link's `show`); returns the
   * names it does not know (ticking nothing for them). A second heat layer
   * named is left out: one ramp at a time.
   */
  applyShown(text) {
    this.defaults ??= this.boxes().filter((b) => boxOf(b).checked).join(',');
    const want = new Set(text.split(',').filter(Boolean));
    const known = new Set(this.boxes());
    let heat = null;
    for (const b of this.boxes()) {
      const on = want.has(b);
      const isHeat = this.heats.some((l) => l.name === b);
      if (isHeat && on && heat) continue;
      if (isHeat && on) heat = b;
      boxOf(b).checked = on && (!isHeat || heat === b);
    }
    return [...want].filter((b) => !known.has(b));
  }

  /** Ticks the layers and options of the teaching view. */
  teaching() {
    for (const id of ['layer-rollouts', 'layer-practice', 'layer-intent', 'layer-arrows', 'layer-grid']) $(id).checked = true;
    this.pick(TEACHING_HEAT);
  }
}
