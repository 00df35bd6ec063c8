// The plain three-line explanation beside the board: what the lattice is,
// what the colours show (it follows the heat layer shown) and what the
// searcher does (from the engine's own help for searchers that do not
// deliberate).

import { $, setText } from '../../shared/ui.js';

const COLOURS = {
  prior: 'The colours show the prior: where the target was likely hidden (brighter is likelier).',
  plan: 'The colours show the prior the searcher plans with (the true prior, unless it knows the target).',
  posterior: 'The colours show its belief: the prior with the cells it has already searched taken out.',
  visits: 'The colours count how often its imagined searches passed through each cell.',
  walker: 'The colours count the walker’s own visits to each cell.',
};
const NONE = 'No colours shown: pick a layer in the legend to colour the cells.';
const MCTS = 'Before each step it imagines many searches (light-blue trails) for practice targets (◇) drawn from its belief, and steps where they went best.';

/** Updates the three lines for `run` with heat layer `heat` (a layer name, or null). */
export function updateExplanation(run, heat) {
  const [lattice, colours, searcher] = $('explain').children;
  setText(lattice, `A searcher (white disc) hunts a target hidden on a ${run.n}×${run.n} lattice whose edges wrap around, like a torus.`);
  setText(colours, heat ? (COLOURS[heat] ?? `The colours show the layer named in the legend.`) : NONE);
  setText(searcher, run.deliberates ? MCTS : `It does not plan ahead with imagined searches: ${run.help}.`);
}
