// The page's own controls: the playback bar, the speed slider, the race
// opponent and the keys. The engine's parameters have their own form
// (live/config-form.js).

import { $, fillSelect } from '../shared/ui.js';
import { PHASE_SPEEDS } from '../shared/url-state.js';

/** The keys (shown on the page, beside the playback buttons). */
const KEYS = {
  ' ': 'toggle', ArrowRight: 'stepMove', ArrowUp: 'stepLoop', p: 'stepPhase', P: 'stepPhase', r: 'restart', R: 'restart', n: 'newSeed', N: 'newSeed',
  ArrowLeft: 'backMove', Home: 'start', End: 'end',
};
/** With Ctrl (or ⌘): loops; with Shift: phases. */
const CTRL_KEYS = { ArrowRight: 'stepLoop', ArrowLeft: 'backLoop' };
const SHIFT_KEYS = { ArrowRight: 'stepPhase', ArrowLeft: 'backPhase' };

/** Speeds on the slider: one phase every 2, 1 or 0.5 s, then loops per frame. */
export const SPEEDS = [...PHASE_SPEEDS, 1, 2, 5, 10, 20, 50, 100, 200, 500, 1000, 2000, 5000, 20000, 'max'];

/** The action of a key press, or undefined. */
function keyAction(e) {
  if (e.altKey) return undefined;
  if (e.ctrlKey || e.metaKey) return CTRL_KEYS[e.key];
  if (e.shiftKey && SHIFT_KEYS[e.key]) return SHIFT_KEYS[e.key];
  return KEYS[e.key];
}

export class Controls {
  /**
   * @param {object} o
   * @param {object[]} o.races                  race options (url-state.js raceOptions)
   * @param {(view) => void} o.onRace           the race opponent changed: { race } or { vs }
   * @param {(speed) => void} o.onSpeed         loops per frame, or 'max'
   * @param {(action) => void} o.onPlayback     toggle | stepMove | stepLoop | stepPhase | restart | newSeed
   *                                            | backMove | backLoop | backPhase | start | end
   */
  constructor({ races, onRace, onSpeed, onPlayback }) {
    fillSelect($('race'), races.map((r) => [r.id, r.label]));
    $('race').addEventListener('change', (e) => onRace({ race: e.target.value }));
    $('vs').addEventListener('change', (e) => onRace({ vs: e.target.value.trim().replace(/\s+/g, ' ') }));
    $('speed').addEventListener('input', (e) => {
      const s = SPEEDS[Number(e.target.value)];
      showSpeed(s);
      onSpeed(s);
    });
    for (const [id, action] of [['play', 'toggle'], ['step-move', 'stepMove'], ['step-loop', 'stepLoop'], ['step-phase', 'stepPhase'], ['reset', 'restart'], ['new-seed', 'newSeed']]) {
      $(id).addEventListener('click', () => onPlayback(action));
    }
    // Space on a focused button would also "click" it; keep one toggle.
    $('play').addEventListener('keydown', (e) => {
      if (e.key === ' ') e.stopPropagation();
    });
    document.addEventListener('keydown', (e) => {
      const t = e.target;
      if (t instanceof HTMLElement && t.closest('input, select, textarea, [contenteditable]')) return;
      const action = keyAction(e);
      if (!action) return;
      e.preventDefault();
      onPlayback(action);
    });
  }

  /** Shows the view parameters: the race opponent and the speed. */
  sync(view) {
    $('race').value = view.race;
    $('vs').value = view.vs ?? '';
    $('speed').value = speedIndex(view.speed);
    showSpeed(view.speed);
  }

  /** Enables the loop button for runs that deliberate (or make a plan in slices: a slice a press). */
  setDeliberates(yes) {
    $('step-loop').disabled = !yes;
    $('step-phase').disabled = !yes;
  }
}

/** The speed as a screen reader says it ("10 loops/frame"), and beside the slider. */
function showSpeed(speed) {
  $('speed-label').value = speedLabel(speed);
  $('speed').setAttribute('aria-valuetext', speedLabel(speed));
}

function speedIndex(speed) {
  if (typeof speed === 'string') return Math.max(0, SPEEDS.indexOf(speed));
  let best = SPEEDS.indexOf(1);
  SPEEDS.forEach((s, i) => {
    if (typeof s === 'number' && Math.abs(Math.log(s) - Math.log(speed)) < Math.abs(Math.log(SPEEDS[best]) - Math.log(speed))) best = i;
  });
  return best;
}

function speedLabel(speed) {
  if (speed === 'max') return 'as fast as possible';
  if (typeof speed === 'string') return `one phase every ${speed.slice(0, -1)} s`;
  return `${speed} loop${speed === 1 ? '' : 's'}/frame`;
}
