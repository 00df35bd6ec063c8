// The statistics panel, the result over each board (in plain words), the
// race scoreboard, and the board's text description. Every number comes
// from a run's latest frame (the engine computed it) or from the
// controller's meter.

import { $, setText, fmtInt, fmtRate } from '../../shared/ui.js';

/** "1.23", or a dash until the engine reports a ratio. */
const fmtRatio = (r) => (r === null || r === undefined ? '–' : r.toFixed(2));

/** "beam search, depth 37 of 200", from the engine's progress of a plan being made. */
export const planningText = (p) =>
  `${p.stage} ${p.total ? `${p.done} of ${p.total}` : p.done}${p.inner_unit ? ` (${fmtInt(p.inner)} ${p.inner_unit})` : ''}`;

const steps = (k) => `${fmtInt(k)} step${k === 1 ? '' : 's'}`;

/** A cell as people count it: (x, y) from 1. */
export const cellText = (idx, n) => `(${(idx % n) + 1}, ${Math.floor(idx / n) + 1})`;

/** What a finished run found, in plain words (the bound is the engine's, for this prior). */
export function resultLine(run) {
  const f = run.frame;
  // A plan made once gets the banner; a decision made every move (rollout
  // improvement) shows in the statistics instead, or the banner would
  // blink at every move.
  if (f.planning && !f.planning.per_move) return `Planning: ${planningText(f.planning)}…`;
  const bound = `Over many targets from this prior, no searcher can average fewer than ${run.lower_bound.toFixed(1)} steps.`;
  if (f.status === 'found') {
    if (run.optimal === 0) return `Found in ${steps(f.steps)}: the target was in sight from the start. ${bound}`;
    return `Found in ${steps(f.steps)}. The shortest path was ${steps(run.optimal)}. ${bound}`;
  }
  if (f.status === 'capped') return `Step cap reached after ${steps(f.steps)}: not found. The shortest path was ${steps(run.optimal)}.`;
  return '';
}

/** The board's description for screen readers (and the line under the board). */
export function describeRun(run) {
  const f = run.frame;
  const where = cellText(f.position, run.n);
  const searched = `${(100 * f.searched_mass).toFixed(1)}% of the prior searched`;
  if (f.status === 'found') return `Found the target at ${cellText(run.target, run.n)} after ${steps(f.steps)}; ${searched}.`;
  if (f.status === 'capped') return `Stopped at the step cap at ${where} after ${steps(f.steps)}; ${searched}.`;
  return `Searcher at ${where} after ${steps(f.steps)}; ${searched}.`;
}

/** Updates the statistics of the main run, the banners and (in a race) the scoreboard. */
export function updateStats(runs, meter, { reveal }) {
  const run = runs[0];
  const f = run.frame;
  const known = f.status === 'found' || reveal;
  setText('steps', fmtInt(f.steps));
  setText('revisits', f.revisits === undefined ? '–' : `${fmtInt(f.revisits)} of ${fmtInt(f.steps)} moves`);
  setText('optimal', known ? String(run.optimal) : '?');
  setText('ratio', f.status === 'found' && f.ratio === null ? '— (optimal 0)' : fmtRatio(f.ratio));
  setText('lower-bound', run.lower_bound.toFixed(1));
  const cfg = run.config;
  const budget = cfg.ms !== null ? `${cfg.ms} ms` : fmtInt(cfg.loops);
  const deciding = f.planning?.per_move ? planningText(f.planning) : '—';
  setText('decision-loops-label', run.deliberates ? 'Loops this move' : 'This move');
  setText('decision-loops', run.deliberates ? `${fmtInt(f.loops_done)} / ${budget}` : deciding);
  setText('rollouts', `${fmtInt(f.decision_rollouts)} / ${fmtInt(f.rollouts)}`);
  setText('rollout-steps', `${fmtRate(f.decision_rollout_steps)} / ${fmtRate(f.rollout_steps)}`);
  setText('truncated', fmtInt(f.truncated));
  setText('searched-mass', `${(100 * f.searched_mass).toFixed(1)}%`);
  setText('loops-per-s', fmtRate(meter.loopsPerS));
  setText('steps-per-s', fmtRate(meter.stepsPerS));
  setText('fps', meter.fps.toFixed(0));
  runs.forEach((r, i) => {
    const board = $(`board-${i}`);
    const banner = board.querySelector('.banner');
    const line = resultLine(r);
    banner.hidden = !line;
    banner.classList.toggle('capped', r.frame.status === 'capped');
    banner.classList.toggle('planning', !!r.frame.planning && !r.frame.planning.per_move);
    setText(banner, line);
    // Over the half of the board away from the target, so the found moment shows.
    const row = Math.floor(r.target / r.n);
    board.querySelector('.result').dataset.at = row < r.n / 2 ? 'bottom' : 'top';
  });
  if (runs.length > 1) updateScoreboard(runs, reveal);
}

function updateScoreboard(runs, reveal) {
  const body = $('score-rows');
  while (body.rows.length < runs.length) {
    const tr = body.insertRow();
    for (let k = 0; k < 5; k++) tr.insertCell();
  }
  const done = runs.every((r) => r.frame.status !== 'running');
  const found = runs.filter((r) => r.frame.status === 'found');
  const best = found.length ? Math.min(...found.map((r) => r.frame.steps)) : -1;
  runs.forEach((r, i) => {
    const f = r.frame;
    const tr = body.rows[i];
    const cells = [
      `${i === 0 ? 'A' : 'B'}: ${r.label}`,
      fmtInt(f.steps),
      f.status === 'found' || reveal ? String(r.optimal) : '?',
      fmtRatio(f.ratio),
      f.status,
    ];
    cells.forEach((t, k) => setText(tr.cells[k], t));
    tr.classList.toggle('winner', done && f.status === 'found' && f.steps === best);
  });
}
