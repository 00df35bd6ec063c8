// Named starting points of the page: engine parameters (as URL pairs) and
// view parameters, plus what to tell the user; and their buttons.

import { $ } from '../shared/ui.js';

export const PRESETS = {
  default: { pairs: [], view: { speed: 10, race: '' }, note: '' },
  teaching: {
    pairs: [['n', '11'], ['sigma', '2'], ['loops', '40'], ['seed', '3'], ['start', '2,2'], ['keep_traces', '3']],
    view: { speed: 1, race: '' },
    note: 'Teaching view: one MCTS loop per frame. Each loop draws a practice target (◇) from the belief (the prior, or the posterior: the prior with searched cells removed), picks the neighbour with the highest UCT value, runs a random rollout from it until the rollout finds the practice target, then adds one visit to every cell the loop passed and credits each with 1/(its own steps to the practice target): the picked neighbour gets 1/τ. Pause and press ↑ to step a single loop.',
  },
};

/** Wires the Teaching view and Default demo buttons: each starts its preset, playing. */
export function bindPresets({ engine, live, viewState }) {
  const start = (name) => {
    const p = PRESETS[name];
    if (name === 'teaching') {
      viewState.teaching();
      live.controller.dispatch({ type: 'view', view: viewState.frameView() });
    }
    live.change({ config: engine.parseParams(p.pairs).config, view: p.view, autoplay: true, note: p.note });
  };
  $('teaching').addEventListener('click', () => start('teaching'));
  $('defaults').addEventListener('click', () => start('default'));
}
