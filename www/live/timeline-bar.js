// The timeline under the board: a scrubber over the moves the run has
// reached, buttons back a move, a loop or a phase, to the start and to the
// furthest point, and where the board stands (move, loop, phase). The
// engine keeps the snapshots and replays to any point (src/run/timeline.rs);
// this module only sends the points asked for and shows the engine's.

import { $, setText, fmtInt } from '../shared/ui.js';
import { PHASES } from './panels/narrate.js';

const PHASE_NAMES = Object.fromEntries(PHASES);

/** A timeline point in words: "move 3, loop 12, Roll out". */
export function pointText(p) {
  if (!p) return 'move 0';
  const phase = p.phase ? `, ${PHASE_NAMES[p.phase] ?? p.phase}` : '';
  return `move ${fmtInt(p.move)}, loop ${fmtInt(p.loop)}${phase}`;
}

export class TimelineBar {
  /** @param {(action: string, arg?: object) => void} onTravel  'start' | 'end' | 'backMove' | 'backLoop' | 'backPhase' | 'seek' { move } */
  constructor(onTravel) {
    for (const [id, action] of [['tl-start', 'start'], ['tl-end', 'end'], ['back-move', 'backMove'], ['back-loop', 'backLoop'], ['back-phase', 'backPhase']]) {
      $(id).addEventListener('click', () => onTravel(action));
    }
    // Seek once the thumb settles (a drag sends one seek per position it rests on).
    let pending = null;
    $('scrub').addEventListener('input', (e) => {
      clearTimeout(pending);
      const move = Number(e.target.value);
      pending = setTimeout(() => onTravel('seek', { move }), 120);
    });
    this.shown = '';
  }

  /** Shows the engine's timeline `{ move, loop, phase, end }` (null before the first frame). */
  update(timeline, deliberates) {
    const end = timeline?.end ?? { move: 0, loop: 0, phase: null };
    const scrub = $('scrub');
    const max = String(end.move);
    if (scrub.max !== max) scrub.max = max;
    if (document.activeElement !== scrub) scrub.value = String(timeline?.move ?? 0);
    const text = pointText(timeline);
    const reached = `To the furthest point reached: ${pointText(end)} (End)`;
    if (text !== this.shown || reached !== this.reached) {
      this.shown = text;
      this.reached = reached;
      setText('tl-point', text);
      scrub.setAttribute('aria-valuetext', text);
      $('tl-end').title = reached;
      $('tl-end').setAttribute('aria-label', reached);
    }
    $('back-loop').disabled = !deliberates;
    $('back-phase').disabled = !deliberates;
  }
}
