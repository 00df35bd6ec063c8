// The statistics panel, the result banner over each board and the race
// scoreboard. Every number comes from a run's latest frame (the engine
// computed it) or from the controller's meter.

import { $, setText, fmtInt, fmtRate } from '../../shared/ui.js';

/** "1.23", or a dash until the engine reports a ratio. */
const fmtRatio = (r) => (r === null || r === undefined ? '–' : r.toFixed(2));

/** "beam search, depth 37 of 200", from the engine's progress of a plan being made. */
export const planningText = (p) =>
  `${p.stage} ${p.total ? `${p.done} of ${p.total}` : p.done}${p.inner_unit ? ` (${fmtInt(p.inner)} ${p.inner_unit})` : ''}`;

function resultLine(run) {
  const f = run.frame;
  // A plan made once gets the banner; a decision made every move (rollout
  // improvement) shows in the statistics instead, or the banner would
  // blink at every move.
  if (f.planning && !f.planning.per_move) return `Planning: ${planningText(f.planning)}…`;
  if (f.status === 'found') return `Found in ${f.steps} steps (optimal ${run.optimal}, ratio ${f.ratio === null ? '—' : f.ratio.toFixed(2)})`;
  if (f.status === 'capped') return `Step cap reached after ${f.steps} steps: not found`;
  return '';
}

/** Updates the statistics of the main run, the banners and (in a race) the scoreboard. */
export function updateStats(runs, meter, { reveal }) {
  const run = runs[0];
  const f = run.frame;
  const known = f.status === 'found' || reveal;
  setText('steps', fmtInt(f.steps));
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
    const banner = $(`board-${i}`).querySelector('.banner');
    const line = resultLine(r);
    banner.hidden = !line;
    banner.classList.toggle('capped', r.frame.status === 'capped');
    banner.classList.toggle('planning', !!r.frame.planning && !r.frame.planning.per_move);
    setText(banner, line);
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
