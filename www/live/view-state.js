// What the page shows, as opposed to what it runs: the heat layers (one
// checkbox per layer the engine's schema lists), the log scale, the path,
// rollout traces, arrows, grid, reveal and the periodic view. It turns them
// into the frame request the controller sends with each frame.

import { $ } from '../shared/ui.js';

/** Heat layers ticked on first load. */
const DEFAULT_LAYERS = ['prior', 'visits'];
const OPTION_IDS = ['layer-path', 'layer-intent', 'layer-grid', 'reveal', 'tiling', 'log-scale', 'layer-arrows'];
const TRACE_IDS = ['layer-rollouts', 'layer-practice'];

export class ViewState {
  /**
   * @param {object} schema the engine's schema (its `layers`)
   * @param {{ redraw: () => void, traces: () => void }} on  called when a
   *   view option changes; `traces` when a trace layer is ticked or
   *   unticked (a run keeps traces from its start: see traceCount)
   */
  constructor(schema, on) {
    this.layers = schema.layers;
    const box = $('layer-checks');
    const frag = document.createDocumentFragment();
    for (const l of this.layers) {
      const label = document.createElement('label');
      const input = document.createElement('input');
      input.type = 'checkbox';
      input.id = `layer-${l.name}`;
      input.checked = DEFAULT_LAYERS.includes(l.name);
      input.addEventListener('change', on.redraw);
      label.append(input, ` ${l.label}`);
      frag.append(label);
    }
    box.prepend(frag);
    for (const id of OPTION_IDS) $(id).addEventListener('change', on.redraw);
    for (const id of TRACE_IDS) $(id).addEventListener('change', on.traces);
  }

  /** Heat layers to draw, bottom to top, as frame requests. */
  layerRequests() {
    const log = $('log-scale').checked;
    return this.layers
      .filter((l) => $(`layer-${l.name}`).checked)
      .map((l) => ({
        layer: l.name,
        palette: l.palette,
        scale: l.counts ? (log ? 'log' : 'stretch') : 'linear',
        alpha: l.alpha,
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
    };
  }

  /** Ticks the layers and options of the teaching view. */
  teaching() {
    for (const id of ['layer-rollouts', 'layer-practice', 'layer-intent', 'layer-visits', 'layer-prior', 'layer-arrows', 'layer-grid']) $(id).checked = true;
  }
}
