// The phase strip (Select › Expand › Roll out › Back up, the phase just
// done marked) and the narration line beside the board: what the phase just
// did, in plain words, with the engine's numbers from the frame's phase
// record (`frame.phase`, see src/searchers/phase.rs). Nothing here computes
// a game quantity: it words what the engine recorded.

import { $, setText, fmtInt, fmtNum } from '../../shared/ui.js';
import { MOVE_NAMES } from '../renderer.js';
import { cellText } from './stats.js';

/** The phases in loop order, with their names for people. */
export const PHASES = [
  ['select', 'Select'],
  ['expand', 'Expand'],
  ['rollout', 'Roll out'],
  ['backup', 'Back up'],
];
const MOVE_INDEX = { up: 0, right: 1, down: 2, left: 3 };
const moveName = (m) => MOVE_NAMES[MOVE_INDEX[m]] ?? m;

/** The selection in words: the root's choice with its UCT split, then the levels below. */
function selectText(rec, n) {
  const practice = `The practice target ◇ is drawn at ${cellText(rec.practice, n)}.`;
  const [first, ...below] = rec.select;
  if (!first) return `Select: ${practice}`;
  const name = moveName(first.chosen);
  const c = first.candidates[MOVE_INDEX[first.chosen]];
  let why;
  if (first.rule === 'plan') why = `the belief MCTS replays its plan, so the loop tries ${name}.`;
  else if (first.rule === 'unvisited') why = `${name} has never been tried, so the loop tries it first.`;
  else if (!Number.isFinite(c.explore)) why = `${name} has not been tried yet (UCT = ∞), so the loop tries ${name}.`;
  else why = `${name} has the highest UCT, ${fmtNum(c.mean)} + ${fmtNum(c.explore)} = ${fmtNum(c.uct)}, so the loop tries ${name}.`;
  const ties = first.ties > 1 ? ` (${first.ties} moves tied; one was drawn at random.)` : '';
  const deeper = below.length ? ` Then ${below.length} level${below.length === 1 ? '' : 's'} down the tree: ${below.map((l) => moveName(l.chosen)).join(', ')}.` : '';
  return `Select: ${practice} ${why}${ties}${deeper}`;
}

function expandText(rec, n) {
  const e = rec.expansion;
  if (!e) return 'Expand: nothing to add.';
  const added = e.node !== null && e.move ? ` (${moveName(e.move)}, to ${cellText(e.cell, n)})` : '';
  return `Expand: ${e.what}${added}.`;
}

/** Cells sent as little-endian u32 bytes. */
export function cellsOf(bytes) {
  if (!bytes?.byteLength) return new Uint32Array(0);
  const v = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  return Uint32Array.from({ length: bytes.byteLength >> 2 }, (_, i) => v.getUint32(4 * i, true));
}

function rolloutText(rec, n) {
  const path = cellsOf(rec.path);
  const from = path.length ? `${cellText(path[path.length - 1], n)}` : 'the leaf';
  const steps = `${fmtInt(rec.rollout_steps)} step${rec.rollout_steps === 1 ? '' : 's'}`;
  let end;
  if (rec.detected) end = 'and detected the practice target';
  else if (rec.cut) end = 'and was cut short: the rest is charged from its reference walk';
  else if (rec.truncated) end = 'and reached its step cap without detecting it (a truncated rollout earns nothing)';
  else end = 'without detecting the practice target';
  const counts = rec.counts ? '' : ' This expansion rollout is not one of the decision’s loops.';
  return `Roll out: the walk from ${from} took ${steps} ${end}.${counts}`;
}

function backupText(rec, n) {
  const shown = rec.backup.slice(0, 3).map((b, i) => {
    const who = i === 0 && b.node === 0 ? `the root ${cellText(b.cell, n)}` : cellText(b.cell, n);
    const picked = b.picked ? ' (picked)' : '';
    return `${who}${picked} N ${fmtInt(b.visits[0])} → ${fmtInt(b.visits[1])}, Q/N ${fmtNum(b.value[0])} → ${fmtNum(b.value[1])}`;
  });
  const more = rec.backup.length > 3 ? `, and ${rec.backup.length - 3} more` : '';
  const passes = rec.others ? ` ${fmtInt(rec.others)} other cell${rec.others === 1 ? '' : 's'} the rollout passed through gained a visit too (pass-through visits).` : '';
  return `Back up: reward ${fmtNum(rec.reward)} goes up the path: ${shown.join('; ')}${more}.${passes}`;
}

const TEXT = { select: selectText, expand: expandText, rollout: rolloutText, backup: backupText };

/** The narration of `run`'s last phase, or '' when it was not stepped phase by phase. */
export function narration(run) {
  const rec = run.frame.phase;
  if (!rec?.phase) return '';
  return TEXT[rec.phase](rec, run.n);
}

/** Shows the phase strip and the narration for `run`. */
export function updateNarration(run) {
  const now = run.frame.phase?.phase ?? null;
  for (const el of $('phase-strip').children) {
    const on = el.dataset.phase === now;
    el.classList.toggle('now', on);
    if (on) el.setAttribute('aria-current', 'step');
    else el.removeAttribute('aria-current');
  }
  $('phase-strip').dataset.phase = now ?? '';
  setText('narration', now ? narration(run) : run.deliberates ? 'Press Step phase (p) to run the next loop one phase at a time, with each phase explained here.' : '');
}
