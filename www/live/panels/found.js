// The found moment's next steps, under the result on the main board:
// replay the same run, race the belief MCTS on the same target (the same
// seed draws the same target), or draw a new target. The result is also
// announced to screen readers.

import { $, setText } from '../../shared/ui.js';
import { resultLine } from './stats.js';

/** The opponent offered: the belief MCTS, or the paper's MCTS when the run is the belief MCTS. */
function opponent(run, races) {
  const belief = races.find((r) => r.id === 'mcts-pomcp');
  const paper = races.find((r) => r.id === 'mcts-code');
  return run.config.searcher === 'mcts' && run.config.variant === 'pomcp' ? [paper, 'Race the paper’s MCTS'] : [belief, 'Race the belief MCTS'];
}

/**
 * @param {object} o
 * @param {object} o.controller   the playback state machine
 * @param {object} o.live         the LiveState (view, change, playback)
 * @param {object[]} o.races      the race options
 */
export function bindFound({ controller, live, races }) {
  const box = $('next-steps');
  const result = $('board-0').querySelector('.result');
  let offered = null;
  controller.on('state', (s) => {
    const done = s === 'found' || s === 'capped';
    box.hidden = !done;
    result.classList.remove('dismissed');
    if (!done) return;
    const run = controller.runs[0];
    setText('announce', resultLine(run));
    const [race, label] = opponent(run, races);
    offered = race && race.id !== live.view.race ? race : null;
    $('next-race').hidden = !offered;
    setText('next-race', label);
  });
  $('next-replay').addEventListener('click', () => controller.dispatch({ type: 'toggle' }));
  $('next-new').addEventListener('click', () => live.playback('newSeed'));
  $('next-race').addEventListener('click', () => offered && live.change({ view: { race: offered.id }, autoplay: true }));
  $('result-hide').addEventListener('click', () => result.classList.add('dismissed'));
}
