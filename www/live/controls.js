// The page's own controls: the playback bar, the speed slider, the race
// opponent and the keys. The engine's parameters have their own form
// (live/config-form.js).

import { $, fillSelect } from '../shared/ui.js';

/** The keys (shown on the page, beside the playback buttons). */
const KEYS = { ' ': 'toggle', ArrowRight: 'stepMove', ArrowUp: 'stepLoop', r: 'restart', R: 'restart', n: 'newSeed', N: 'newSeed' };

/** Speeds on the slider, in loops per frame. */
const SPEEDS = [1, 2, 5, 10, 20, 50, 100, 200, 500, 1000, 2000, 5000, 20000, 'max'];

export class Controls {
  /**
   * @param {object} o
   * @param {object[]} o.races                  race options (url-state.js raceOptions)
   * @param {(race) => void} o.onRace           the race opponent changed
   * @param {(speed) => void} o.onSpeed         loops per frame, or 'max'
   * @param {(action) => void} o.onPlayback     toggle | stepMove | stepLoop | restart | newSeed
   */
  constructor({ races, onRace, onSpeed, onPlayback }) {
    fillSelect($('race'), races.map((r) => [r.id, r.label]));
    $('race').addEventListener('change', (e) => onRace(e.target.value));
    $('speed').addEventListener('input', (e) => {
      const s = SPEEDS[Number(e.target.value)];
      showSpeed(s);
      onSpeed(s);
    });
    for (const [id, action] of [['play', 'toggle'], ['step-move', 'stepMove'], ['step-loop', 'stepLoop'], ['reset', 'restart'], ['new-seed', 'newSeed']]) {
      $(id).addEventListener('click', () => onPlayback(action));
    }
    // Space on a focused button would also "click" it; keep one toggle.
    $('play').addEventListener('keydown', (e) => {
      if (e.key === ' ') e.stopPropagation();
    });
    document.addEventListener('keydown', (e) => {
      const t = e.target;
      if (e.ctrlKey || e.metaKey || e.altKey) return;
      if (t instanceof HTMLElement && t.closest('input, select, textarea, [contenteditable]')) return;
      const action = KEYS[e.key];
      if (!action) return;
      e.preventDefault();
      onPlayback(action);
    });
  }

  /** Shows the view parameters: the race opponent and the speed. */
  sync(view) {
    $('race').value = view.race;
    $('speed').value = speedIndex(view.speed);
    showSpeed(view.speed);
  }

  /** Enables the loop button for runs that deliberate (or make a plan in slices: a slice a press). */
  setDeliberates(yes) {
    $('step-loop').disabled = !yes;
  }
}

/** The speed as a screen reader says it ("10 loops/frame"), and beside the slider. */
function showSpeed(speed) {
  $('speed-label').value = speedLabel(speed);
  $('speed').setAttribute('aria-valuetext', speedLabel(speed));
}

function speedIndex(speed) {
  if (speed === 'max') return SPEEDS.length - 1;
  let best = 0;
  SPEEDS.forEach((s, i) => {
    if (s !== 'max' && Math.abs(Math.log(s) - Math.log(speed)) < Math.abs(Math.log(SPEEDS[best]) - Math.log(speed))) best = i;
  });
  return best;
}

function speedLabel(speed) {
  return speed === 'max' ? 'as fast as possible' : `${speed} loop${speed === 1 ? '' : 's'}/frame`;
}
