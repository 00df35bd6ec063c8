// The configuration form, the playback bar and the keys. Choices and
// limits come from the engine's schema; values are shown as the engine
// writes them (the same text as the URL); every change goes back as text
// to onParam(key, raw), which the engine parses. Nothing here checks a value.

import { $, CHOICE_LABELS, fillSelect } from '../shared/ui.js';

/** Speeds on the slider, in loops per frame. */
const SPEEDS = [1, 2, 5, 10, 20, 50, 100, 200, 500, 1000, 2000, 5000, 20000, 'max'];

/** Control id → parameter key, for the inputs that edit one parameter. */
const PARAM_CONTROLS = ['n', 'prior', 'sigma', 'rv', 'start', 'searcher', 'variant', 'rollout', 'belief', 'loops', 'ms', 'c', 'mu', 'final', 'seed'];

export class Controls {
  /**
   * @param {object} o
   * @param {object} o.schema        the engine's schema
   * @param {object[]} o.races       race options (url-state.js raceOptions)
   * @param {(key, raw) => void} o.onParam      a parameter edited (raw text)
   * @param {(race) => void} o.onRace           the race opponent changed
   * @param {(speed) => void} o.onSpeed         loops per frame, or 'max'
   * @param {(action) => void} o.onPlayback     toggle | stepMove | stepLoop | restart | newSeed
   */
  constructor({ schema, races, onParam, onRace, onSpeed, onPlayback }) {
    this.params = new Map(schema.params.map((p) => [p.key, p]));
    const searchers = schema.searchers.map((s) => [s.name, s.label]);
    fillSelect($('searcher'), searchers);
    for (const key of Object.keys(CHOICE_LABELS)) {
      fillSelect($(key), this.params.get(key).choices.map((c) => [c, CHOICE_LABELS[key][c] ?? c]));
    }
    fillSelect($('race'), races.map((r) => [r.id, r.label]));
    // 'custom' is shown, never sent: it means no preset has all its values.
    fillSelect($('preset'), [['custom', 'custom (no preset)'], ...schema.presets.map((p) => [p.name, p.name])]);
    $('preset').title = schema.presets.map((p) => `${p.name}: ${p.help}`).join('\n');
    $('preset').addEventListener('change', (e) => {
      if (e.target.value !== 'custom') onParam('preset', e.target.value);
    });
    // Limits from the schema (the σ slider shows a narrower range, set in sync).
    for (const key of ['n', 'rv', 'loops', 'ms', 'c', 'mu']) {
      const p = this.params.get(key);
      $(key).min = p.key === 'ms' ? '0' : p.min;
      $(key).max = p.max;
      $(key).title = `${p.help}: ${p.allowed}`;
    }
    for (const key of PARAM_CONTROLS) {
      $(key).addEventListener('change', (e) => onParam(key, e.target.value));
    }
    $('sigma').addEventListener('input', (e) => {
      $('sigma-out').value = e.target.value;
    });
    $('budget').addEventListener('change', (e) => {
      const ms = Number(this.text?.get('ms') ?? 0);
      onParam('ms', e.target.value === 'ms' ? String(ms > 0 ? ms : 20) : '0');
    });
    $('race').addEventListener('change', (e) => onRace(e.target.value));
    $('speed').addEventListener('input', (e) => {
      const s = SPEEDS[Number(e.target.value)];
      $('speed-label').value = speedLabel(s);
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
      const action = { ' ': 'toggle', ArrowRight: 'stepMove', ArrowUp: 'stepLoop', r: 'restart', R: 'restart' }[e.key];
      if (!action) return;
      e.preventDefault();
      onPlayback(action);
    });
  }

  /**
   * Shows `config` (with its parameters as text, as the engine writes
   * them), the view parameters, which parameters apply, and the preset
   * whose values the config has (or null).
   */
  sync({ config, text, view, applicable, preset }) {
    this.text = text;
    $('preset').value = preset ?? 'custom';
    for (const key of PARAM_CONTROLS) {
      let v = text.get(key);
      if (key === 'ms' && v === '0') v = '';
      else if (key === 'c' && Number.isFinite(Number(v))) v = String(+Number(v).toFixed(6));
      $(key).value = v;
      $(key).disabled = !applicable.has(key);
    }
    const sigma = text.get('sigma');
    $('sigma').max = String(Math.max(5, config.n));
    $('sigma-out').value = sigma;
    $('sigma-row').hidden = !applicable.has('sigma');
    $('paint-tools').hidden = !applicable.has('paint');
    const timed = config.ms !== null;
    $('budget').value = timed ? 'ms' : 'loops';
    $('budget').disabled = !applicable.has('ms');
    $('loops-row').hidden = timed;
    $('ms-row').hidden = !timed;
    $('race').value = view.race;
    $('speed').value = speedIndex(view.speed);
    $('speed-label').value = speedLabel(view.speed);
  }

  /** Enables the loop button for runs that deliberate (or make a plan in slices: a slice a press). */
  setDeliberates(yes) {
    $('step-loop').disabled = !yes;
  }
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
