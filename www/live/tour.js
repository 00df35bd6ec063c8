// The first-visit tour: five short steps, each pointing at the thing it
// names (a ring around it, the card beside it). It shows once, when the
// run has made a few moves (or at once if it waits for Play), pauses the
// run while it is open and resumes it after; Skip, Esc or the last step
// close it, and localStorage remembers that it was seen. The Tour button
// opens it again.

import { $, setText } from '../shared/ui.js';

export const TOUR_KEY = 'torus-search.tour';
/** The tour opens once the run has made this many moves (so there is a path and trails to point at). */
const OPEN_AFTER_MOVES = 4;

const STEPS = [
  ['This is the searcher', 'The white disc with a halo. It moves one cell per step, hunting a hidden target. The edges wrap around: leaving on the right, it comes back on the left.', 'searcher'],
  ['Where the target may be', 'The colours show the prior: where the target was likely hidden. One click here shows its belief (what is left after searching) or how often its imagined searches passed each cell.', '#heat-switch'],
  ['Its imagined searches', 'Before each step, Monte Carlo Tree Search imagines many searches for practice targets (◇) drawn from its belief. Each light-blue trail is one of them, from its ring to its dot.', '#legend [data-mark="rollout"]'],
  ['Its next step', 'The arrows around the searcher show how often each neighbour was tried; it steps where the imagined searches went best (the thick yellow arrow).', 'searcher'],
  ['You drive', 'Play, pause, step one imagined search (Step loop) or one real move. The Teaching view shows a small lattice slowly; the legend names everything drawn.', '.playback'],
];

function seen() {
  try {
    return localStorage.getItem(TOUR_KEY) === 'seen';
  } catch {
    return false;
  }
}

function remember() {
  try {
    localStorage.setItem(TOUR_KEY, 'seen');
  } catch {
    /* storage refused: the tour shows again next time */
  }
}

export class Tour {
  /**
   * @param {object} o
   * @param {object} o.controller  the playback state machine
   * @param {object} o.boards      the Boards (where the searcher is drawn)
   */
  constructor({ controller, boards }) {
    Object.assign(this, { controller, boards });
    this.step = -1;
    this.resume = false;
    this.done = false; // opened once (or not needed)
    this.card = $('tour');
    this.spot = $('tour-spot');
    $('tour-next').addEventListener('click', () => this.go(this.step + 1));
    $('tour-back').addEventListener('click', () => this.go(this.step - 1));
    $('tour-skip').addEventListener('click', () => this.close());
    $('tour-open').addEventListener('click', () => this.open());
    document.addEventListener('keydown', (e) => {
      if (e.key === 'Escape' && this.step >= 0) this.close();
    });
    addEventListener('resize', () => this.place());
    addEventListener('scroll', () => this.place(), true);
    controller.on('frame', ({ state, runs }) => {
      if (this.step >= 0) this.place();
      else if (!this.done && runs.length && (state !== 'running' || runs[0].frame.steps >= OPEN_AFTER_MOVES)) {
        this.done = true;
        if (!seen()) this.open();
      }
    });
  }

  open() {
    this.done = true;
    if (this.controller.state === 'running') {
      this.controller.dispatch({ type: 'pause' });
      this.resume = true;
    }
    this.card.hidden = false;
    this.go(0);
    $('tour-next').focus();
  }

  close() {
    this.step = -1;
    this.card.hidden = true;
    this.spot.hidden = true;
    remember();
    if (this.resume) this.controller.dispatch({ type: 'play' });
    this.resume = false;
  }

  go(step) {
    if (step >= STEPS.length) return this.close();
    this.step = Math.max(0, step);
    const [title, text] = STEPS[this.step];
    setText('tour-count', `${this.step + 1} of ${STEPS.length}`);
    setText('tour-title', title);
    setText('tour-text', text);
    $('tour-back').disabled = this.step === 0;
    setText('tour-next', this.step === STEPS.length - 1 ? 'Done' : 'Next');
    this.anchorEl()?.scrollIntoView({ block: 'nearest' });
    this.place();
    return undefined;
  }

  /** The element the step names (null for the searcher, a point on the board). */
  anchorEl() {
    const target = STEPS[this.step][2];
    if (target === 'searcher') return $('view-0');
    return document.querySelector(target) ?? $('legend');
  }

  /** The rectangle the step points at, in client px. */
  anchorRect() {
    const run = this.controller.runs[0];
    if (STEPS[this.step][2] === 'searcher' && run) {
      const [x, y] = this.boards.searcherPoint(run, 0);
      return { left: x - 22, top: y - 22, right: x + 22, bottom: y + 22, width: 44, height: 44 };
    }
    return this.anchorEl().getBoundingClientRect();
  }

  /** Rings the anchor and puts the card beside it (below or above it on a narrow screen). */
  place() {
    if (this.step < 0) return;
    const a = this.anchorRect();
    Object.assign(this.spot.style, { left: `${a.left - 4}px`, top: `${a.top - 4}px`, width: `${a.width + 8}px`, height: `${a.height + 8}px` });
    this.spot.hidden = false;
    const card = this.card.getBoundingClientRect();
    const [vw, vh] = [innerWidth, innerHeight];
    const gap = 14;
    let side;
    let left;
    let top;
    if (vw >= 700 && a.right + gap + card.width <= vw) [side, left, top] = ['right', a.right + gap, (a.top + a.bottom - card.height) / 2];
    else if (vw >= 700 && a.left - gap - card.width >= 0) [side, left, top] = ['left', a.left - gap - card.width, (a.top + a.bottom - card.height) / 2];
    else if (a.bottom + gap + card.height <= vh) [side, left, top] = ['below', (a.left + a.right - card.width) / 2, a.bottom + gap];
    else [side, left, top] = ['above', (a.left + a.right - card.width) / 2, a.top - gap - card.height];
    left = Math.max(8, Math.min(vw - card.width - 8, left));
    top = Math.max(8, Math.min(vh - card.height - 8, top));
    this.card.dataset.side = side;
    // The card's pointer aims at the anchor's centre.
    const tip = side === 'right' || side === 'left' ? (a.top + a.bottom) / 2 - top : (a.left + a.right) / 2 - left;
    this.card.style.setProperty('--tip', `${Math.max(14, Math.min((side === 'right' || side === 'left' ? card.height : card.width) - 14, tip))}px`);
    Object.assign(this.card.style, { left: `${left}px`, top: `${top}px` });
  }
}
