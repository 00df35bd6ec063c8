// The configuration form, generated from the engine's schema: one control
// per parameter, by kind, labelled and grouped as the schema says (through
// shared/schema.js, the one reader of schema entries), advanced ones in a
// collapsed "More settings". Each control's id is its parameter's key.
// Values are shown as the engine writes them (the URL's text) and every
// change goes back as text to onParam(key, raw): nothing here checks a value.
// Controls of parameters that do not apply to the config are hidden.
//
// The grid edits a parameter only when asked (`pick`): a cell (the next
// click on a cell sets it, then the mode ends) or a painting (drag to
// paint), chosen with the toggle next to that control. Otherwise a click on
// the grid only inspects it (www/live/grid-input.js).

import { $, fillSelect } from '../shared/ui.js';
import { paramEntries, groupLabel } from '../shared/schema.js';

/** An integer range at most this wide gets a slider. */
const SLIDER_SPAN = 16;
/** Numbers a JS number input holds exactly. */
const EXACT = 2 ** 53;

export class ConfigForm {
  /**
   * @param {object} o
   * @param {object} o.schema                   the engine's schema
   * @param {(key, raw) => void} o.onParam      a parameter edited (raw text)
   * @param {(key) => void} o.onPaintClear      a painting's Clear button
   * @param {HTMLElement} [o.box]                where the fields go (#config-fields)
   * @param {HTMLSelectElement} [o.preset]       the preset select (#preset)
   */
  constructor({ schema, onParam, onPaintClear, box = $('config-fields'), preset = $('preset') }) {
    this.entries = paramEntries(schema);
    this.onParam = onParam;
    this.onPaintClear = onPaintClear;
    this.fields = new Map(); // key -> { entry, field, set(text), inputs }
    this.applicable = new Set();
    // The first cell parameter (the start): Shift+click on the grid sets it.
    this.startKey = this.entries.find((e) => e.kind === 'cell')?.key ?? null;
    this.pick = null;
    this.onPickChange = () => {}; // (kind of the grid's parameter, or null)
    this.build(schema, box);
    // 'custom' is shown, never sent: it means no preset has all its values.
    this.preset = preset;
    fillSelect(preset, [['custom', 'custom (no preset)'], ...schema.presets.map((p) => [p.name, p.name])]);
    preset.title = schema.presets.map((p) => `${p.name}: ${p.help}`).join('\n');
    preset.addEventListener('change', (e) => {
      if (e.target.value !== 'custom') onParam(schema.preset_key, e.target.value);
    });
  }

  build(schema, box) {
    const groups = new Map(); // "main:GROUP" or "more:GROUP" -> its fieldset
    const more = document.createElement('details');
    more.id = 'more-settings';
    more.className = 'more';
    const summary = document.createElement('summary');
    summary.textContent = 'More settings';
    more.append(summary);
    for (const entry of this.entries) {
      const id = `${entry.advanced ? 'more' : 'main'}:${entry.group}`;
      if (!groups.has(id)) {
        const set = document.createElement('fieldset');
        set.className = 'group config';
        set.dataset.group = entry.group;
        const legend = document.createElement('legend');
        legend.textContent = groupLabel(schema, entry.group);
        set.append(legend);
        groups.set(id, set);
        (entry.advanced ? more : box).append(set);
      }
      const f = this.control(entry);
      this.fields.set(entry.key, { entry, ...f });
      groups.get(id).append(f.field);
    }
    box.append(more);
    this.more = more;
    this.groups = [...groups.values()];
    // A group's name is shown only when there is more than one.
    const names = new Set(this.entries.map((e) => e.group));
    for (const set of this.groups) set.querySelector('legend').hidden = names.size < 2;
  }

  /** A field for one parameter: { field, set(text), inputs }. */
  control(entry) {
    const field = document.createElement('div');
    field.className = 'field';
    field.id = `field-${entry.key}`;
    field.dataset.param = entry.key;
    field.dataset.kind = entry.kind;
    const label = document.createElement('label');
    label.htmlFor = entry.key;
    label.textContent = entry.label;
    const help = document.createElement('small');
    help.className = 'help';
    help.id = `${entry.key}-help`;
    help.textContent = entry.help;
    help.title = `${entry.help} (${entry.allowed})`;
    const make = BUILDERS[entry.kind] ?? textInput;
    const built = make(entry, this);
    built.main.id = entry.key;
    built.main.setAttribute('aria-describedby', help.id);
    if (entry.kind === 'bool') {
      label.prepend(built.main, ' ');
      field.classList.add('check');
      field.append(label, help);
    } else field.append(label, built.node ?? built.main, help);
    if (built.wide) field.classList.add('wide');
    return { field, set: built.set, inputs: built.inputs ?? [built.main] };
  }

  /** Toggles the grid's parameter: `key`, or none when it is already `key`. */
  setPick(key) {
    this.pick = this.pick === key ? null : key;
    this.showPick();
  }

  /** Ends the grid's edit mode. */
  clearPick() {
    this.pick = null;
    this.showPick();
  }

  showPick() {
    for (const { entry, field } of this.fields.values()) {
      const b = field.querySelector('.pick');
      if (b) b.setAttribute('aria-pressed', String(entry.key === this.pick));
    }
    this.onPickChange(this.pickKind());
  }

  /** The kind of the grid's parameter (null when the grid edits nothing). */
  pickKind() {
    return this.pick ? this.fields.get(this.pick).entry.kind : null;
  }

  /** A painting's brush: { radius, erase }. */
  brush(key) {
    const f = this.fields.get(key).field;
    return { radius: Number(f.querySelector('.brush').value), erase: f.querySelector('.erase').checked };
  }

  /**
   * Shows a config: `text` its parameters as the engine writes them,
   * `applicable` the keys that affect its run, `preset` the preset whose
   * values it has (or null).
   */
  sync({ text, applicable, preset }) {
    const was = this.applicable;
    this.applicable = applicable;
    this.preset.value = preset ?? 'custom';
    for (const [key, { field, set, inputs, entry }] of this.fields) {
      const on = applicable.has(key);
      field.hidden = !on;
      for (const el of inputs) el.disabled = !on;
      set(text.get(key) ?? '');
      // A painting that comes into use is edited on the grid at once.
      if (on && !was.has(key) && entry.kind === 'paint' && was.size) this.pick = key;
    }
    if (this.pick && !applicable.has(this.pick)) this.pick = null;
    this.showPick();
    for (const set of this.groups) set.hidden = ![...set.querySelectorAll('.field')].some((f) => !f.hidden);
    this.more.hidden = ![...this.more.querySelectorAll('.field')].some((f) => !f.hidden);
  }
}

/** Sends `raw` for `entry` from an element's change. */
function onChange(el, entry, form, raw = () => el.value) {
  el.addEventListener('change', () => form.onParam(entry.key, raw()));
}

function textInput(entry, form, { numeric = false } = {}) {
  const el = document.createElement('input');
  el.type = 'text';
  if (numeric) el.inputMode = entry.kind === 'int' ? 'numeric' : 'decimal';
  onChange(el, entry, form);
  return { main: el, set: (t) => (el.value = t) };
}

function numberInput(entry, form) {
  const min = Number(entry.min);
  const max = Number(entry.max);
  // A text box for values a number input cannot hold (inf, 64-bit seeds).
  if (!Number.isFinite(max) || Math.abs(max) > EXACT) return textInput(entry, form, { numeric: true });
  const int = entry.kind === 'int';
  if (int && max - min <= SLIDER_SPAN) return slider(entry, form);
  const el = document.createElement('input');
  el.type = 'number';
  Object.assign(el, { min: entry.min, max: entry.max, step: int ? '1' : 'any' });
  onChange(el, entry, form);
  return { main: el, set: (t) => (el.value = t) };
}

function slider(entry, form) {
  const wrap = document.createElement('span');
  wrap.className = 'slider';
  const el = document.createElement('input');
  el.type = 'range';
  Object.assign(el, { min: entry.min, max: entry.max, step: '1' });
  const out = document.createElement('output');
  el.addEventListener('input', () => (out.value = el.value));
  onChange(el, entry, form);
  wrap.append(el, out);
  return { main: el, node: wrap, set: (t) => (el.value = out.value = t) };
}

/** optfloat: a number, 0 (or empty) for none. */
function optNumber(entry, form) {
  const el = document.createElement('input');
  el.type = 'number';
  Object.assign(el, { min: '0', max: entry.max, step: 'any', placeholder: 'none (0)' });
  onChange(el, entry, form, () => el.value.trim() || '0');
  return { main: el, set: (t) => (el.value = Number(t) === 0 ? '' : t) };
}

function choice(entry, form) {
  const el = document.createElement('select');
  fillSelect(el, entry.choices.map((c) => [c, entry.choiceLabel(c)]));
  onChange(el, entry, form);
  return { main: el, set: (t) => (el.value = t) };
}

function bool(entry, form) {
  const el = document.createElement('input');
  el.type = 'checkbox';
  onChange(el, entry, form, () => (el.checked ? '1' : '0'));
  return { main: el, set: (t) => (el.checked = ['1', 'true', 'yes', 'on'].includes(t)) };
}

/** A toggle: the grid edits this parameter while it is pressed. */
function pickButton(entry, form, text) {
  const b = document.createElement('button');
  b.type = 'button';
  b.className = 'pick';
  b.textContent = text;
  b.setAttribute('aria-pressed', 'false');
  b.addEventListener('click', () => form.setPick(entry.key));
  return b;
}

/** cell and optcell: x,y (optcell: empty for none), or a click on the grid. */
function cell(entry, form) {
  const wrap = document.createElement('span');
  wrap.className = 'with-pick';
  const el = document.createElement('input');
  el.type = 'text';
  el.inputMode = 'numeric';
  el.pattern = entry.kind === 'optcell' ? '(\\d+,\\d+)?' : '\\d+,\\d+';
  if (entry.kind === 'optcell') el.placeholder = 'none';
  onChange(el, entry, form, () => el.value.trim());
  const pick = pickButton(entry, form, 'Pick on grid');
  pick.id = `${entry.key}-pick`;
  pick.title = `Then click a cell of the lattice to set ${entry.label}`;
  pick.setAttribute('aria-label', `${entry.label}: pick on the grid`);
  wrap.append(el, pick);
  return { main: el, node: wrap, inputs: [el, pick], set: (t) => (el.value = t) };
}

/** paint: the painting is edited on the grid; a brush, an eraser and Clear. */
function paint(entry, form) {
  const wrap = document.createElement('span');
  wrap.className = 'paint-tools';
  const toggle = pickButton(entry, form, 'Paint on the grid');
  toggle.setAttribute('aria-label', `${entry.label}: paint on the grid`);
  const brush = Object.assign(document.createElement('input'), { type: 'range', min: '0', max: '10', step: '1', value: '2', className: 'brush', id: `${entry.key}-brush` });
  const erase = Object.assign(document.createElement('input'), { type: 'checkbox', className: 'erase', id: `${entry.key}-erase` });
  const clear = Object.assign(document.createElement('button'), { type: 'button', textContent: 'Clear', id: `${entry.key}-clear` });
  clear.addEventListener('click', () => form.onPaintClear(entry.key));
  const labelled = (text, input) => {
    const l = document.createElement('label');
    l.append(`${text} `, input);
    return l;
  };
  const eraseLabel = document.createElement('label');
  eraseLabel.append(erase, ' Erase');
  wrap.append(toggle, labelled('Brush', brush), eraseLabel, clear);
  return { main: toggle, node: wrap, inputs: [toggle, brush, erase, clear], wide: true, set: () => {} };
}

const BUILDERS = {
  int: numberInput,
  float: numberInput,
  optfloat: optNumber,
  choice,
  bool,
  cell,
  optcell: cell,
  paint,
};
