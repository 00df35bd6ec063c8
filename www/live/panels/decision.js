// The decision panel: for each of the four moves, its visits and picks,
// mean reward, exploration term and UCT value, with the formula worked out
// for the move the final rule leads with. All values come from the engine's
// frame (`decision`, with `leading`: the moves the final rule would choose
// among now).

import { $, setText, fmtInt, fmtNum } from '../../shared/ui.js';
import { schema } from '../../shared/engine.js';
import { paramByKey } from '../../shared/schema.js';
import { MOVE_NAMES } from '../renderer.js';
import { planningText } from './stats.js';

const ARROWS = ['↑', '→', '↓', '←'];

let finalRule = null;
/** The final rule's name for people (the schema's label of that choice of `final`). */
const ruleLabel = (rule) => (finalRule ??= paramByKey(schema(), 'final'))?.choiceLabel(rule) ?? rule;

function rows() {
  const body = $('decision').tBodies[0];
  if (!body.rows.length) {
    for (let m = 0; m < 4; m++) {
      const tr = body.insertRow();
      for (let k = 0; k < 5; k++) tr.insertCell();
      tr.cells[0].className = 'move';
    }
  }
  return body.rows;
}

function scoreRows() {
  const body = $('plan-scores').tBodies[0];
  if (!body.rows.length) {
    for (let m = 0; m < 4; m++) {
      const tr = body.insertRow();
      for (let k = 0; k < 3; k++) tr.insertCell();
      tr.cells[0].className = 'move';
    }
  }
  return body.rows;
}

/** A planner's scores of the four moves, as the engine sent them. */
function showScores(run, s) {
  setText('plan-score-h', s.meaning);
  const trs = scoreRows();
  const running = run.frame.status === 'running';
  s.score.forEach((v, m) => {
    const tr = trs[m];
    tr.classList.toggle('chosen', running && m === s.chosen);
    setText(tr.cells[0], `${ARROWS[m]} ${MOVE_NAMES[m]}`);
    const scored = v !== null && Number.isFinite(v);
    setText(tr.cells[1], scored ? fmtNum(v) : '–');
    const d = scored && Number.isFinite(s.score[s.chosen]) ? v - s.score[s.chosen] : null;
    setText(tr.cells[2], d === null ? '–' : m === s.chosen ? 'chosen' : (d > 0 ? '+' : '') + fmtNum(d));
  });
  const better = s.higher_is_better ? 'higher' : 'lower';
  setText('decision-note', `${run.label} scores each move by ${s.meaning} (${better} is better) and took ${MOVE_NAMES[s.chosen]}.`);
}

const names = (flags) => flags.flatMap((l, m) => (l ? [MOVE_NAMES[m]] : [])).join(', ');

/** The UCT split of move `m` worked out, from the engine's terms. */
function worked(d, m) {
  const c = d.children[m];
  if (!c.visits) return `${MOVE_NAMES[m]}: never tried, UCT = ∞`;
  return `${MOVE_NAMES[m]}: ${fmtNum(c.mean)} + ${fmtNum(d.c, 3)}·√(ln ${fmtInt(d.parent_visits)} / ${fmtInt(c.visits)}) = ${fmtNum(c.mean)} + ${fmtNum(c.explore)} = ${fmtNum(c.uct)}`;
}

/**
 * The note under the table: the final rule's move (◆) and why, apart from
 * the highest UCT (▲, what selection tries next), and under `cells` what
 * the visits count.
 */
function decisionNote(run, d, running) {
  let note = `N(v) = ${fmtInt(d.parent_visits)}, c = ${fmtNum(d.c, 3)}.`;
  const leads = d.leading.flatMap((l, m) => (l ? [m] : []));
  const best = d.highest_uct.flatMap((l, m) => (l ? [m] : []));
  if (running && leads.length) {
    const tie = leads.length > 1 ? ` (tied: one at random)` : '';
    note += ` ◆ If the decision ended now, the final rule (${ruleLabel(d.rule)}) would move ${names(d.leading)}${tie}.`;
  } else note += ` Final move: ${ruleLabel(d.rule)}.`;
  if (running && best.length) {
    note += ` ▲ Highest UCT: ${names(d.highest_uct)}${best.length > 1 ? ' (tied)' : ''}, the move the next loop selects. ${worked(d, best[0])}.`;
  }
  if (run.config.variant === 'cells') {
    note += ` Under cells, N(v) = ${fmtInt(d.parent_visits)} counts this cell's table entry, while the four N(vᵢ) add up to ${fmtInt(d.children_visits)}:`
      + ' the table counts every rollout that passed through a neighbour (pass-through visits, in this move and earlier ones), not only the loops that picked it. "Picked" counts the loops of this decision that selected the move.';
  }
  return note;
}

/** Shows the decision under way of `run`. */
export function updateDecision(run) {
  const scores = run.frame.scores;
  $('plan-scores').hidden = !scores || !!run.frame.decision;
  $('decision').hidden = !!scores && !run.frame.decision;
  if (scores && !run.frame.decision) {
    showScores(run, scores);
    return;
  }
  const trs = rows();
  const d = run.frame.decision;
  if (!d) {
    for (const tr of trs) for (const td of tr.cells) setText(td, '–');
    const p = run.frame.planning;
    const note = p
      ? p.per_move
        ? `${run.label} is deciding its move (${planningText(p)}); the Planned path layer shows the path it follows until a completion beats it.`
        : `${run.label} is making its plan (${planningText(p)}); the Planned path layer shows the path it is working on.`
      : run.deliberates ? '' : `${run.label} does not deliberate: ${run.help}.`;
    setText('decision-note', note);
    return;
  }
  const running = run.frame.status === 'running';
  const totalSel = d.children.reduce((a, c) => a + c.selected, 0) || 1;
  d.children.forEach((c, m) => {
    const tr = trs[m];
    tr.classList.toggle('chosen', running && d.leading[m]);
    tr.classList.toggle('uct-best', running && d.highest_uct[m]);
    // Marked by glyph as well as colour: ◆ the final rule's move, ▲ the highest UCT.
    setText(tr.cells[0], `${ARROWS[m]} ${MOVE_NAMES[m]}${running && d.leading[m] ? ' ◆' : ''}${running && d.highest_uct[m] ? ' ▲' : ''}`);
    // Visits: N(vᵢ) of the child, picks this decision, and a bar.
    const td = tr.cells[1];
    // A run without a decision yet (or a walker) left plain text here.
    if (td.childNodes.length !== 3) {
      td.replaceChildren(document.createTextNode(''), document.createElement('span'), document.createElement('span'));
      td.childNodes[1].className = 'split';
      td.childNodes[2].className = 'bar';
    }
    td.childNodes[0].nodeValue = fmtInt(c.visits);
    td.childNodes[1].textContent = `picked ${fmtInt(c.selected)}`;
    td.childNodes[2].style.width = `${Math.round((100 * c.selected) / totalSel)}%`;
    setText(tr.cells[2], c.visits ? fmtNum(c.mean) : '–');
    setText(tr.cells[3], c.visits ? fmtNum(c.explore) : '∞');
    setText(tr.cells[4], c.visits ? fmtNum(c.uct) : '∞');
  });
  let note = decisionNote(run, d, running);
  // The belief MCTS makes its plan before the decision's first loop.
  const p = run.frame.planning;
  if (p) note = `${run.label} is making its plan before the first loop (${planningText(p)}); the Planned path layer shows the path it is working on. ${note}`;
  setText('decision-note', note);
}
