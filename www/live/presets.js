// Named starting points of the page: engine parameters (as URL pairs) and
// view parameters, plus what to tell the user; and their buttons.

import { $, setText, fillSelect } from '../shared/ui.js';
import { readUrl } from '../shared/url-state.js';
import { LESSONS, lessonById, lessonAt, lessonSteps, lessonValue } from './lessons.js';
import { reducedMotion } from './motion.js';

export const PRESETS = {
  default: { pairs: [], view: { speed: 10, race: '' }, note: '' },
  teaching: {
    pairs: [['n', '11'], ['sigma', '2'], ['loops', '40'], ['seed', '3'], ['start', '2,2'], ['keep_traces', '3']],
    view: { speed: 1, race: '' },
    note: 'Teaching view: one MCTS loop per frame. Each loop draws a practice target (◇) from the belief (the prior, or the posterior: the prior with searched cells removed), picks the neighbour with the highest UCT value, runs a random rollout from it until the rollout finds the practice target, then adds one visit to every cell the loop passed and credits each with 1/(its own steps to the practice target): the picked neighbour gets 1/τ. Pause and press ↑ to step a single loop.',
  },
};

/**
 * Shows the card of `at` (`{ lesson, step }`; undefined hides it) beside the
 * playback bar, with a button per step when the lesson has steps (`open(step)` opens one).
 */
function showLesson(at, open) {
  const lesson = at?.lesson;
  $('lesson-card').hidden = !lesson;
  $('lesson').value = lesson?.id ?? '';
  if (!lesson) return;
  setText('lesson-title', lesson.title);
  setText('lesson-text', lesson.text);
  setText('lesson-look', lesson.look);
  setText('lesson-claim', lesson.claim);
  const steps = lessonSteps(lesson);
  const bar = $('lesson-steps');
  bar.hidden = steps.length < 2;
  bar.replaceChildren(...(steps.length < 2 ? [] : steps.map((st, i) => {
    const b = document.createElement('button');
    b.type = 'button';
    b.textContent = `${i + 1}. ${st.label}`;
    b.setAttribute('aria-pressed', String(i === at.step));
    b.addEventListener('click', () => open({ lesson, step: i }));
    return b;
  })));
}

/**
 * Wires the lessons: the list beside the playback bar opens one, a step
 * button one of its steps (its settings, layers and race through the one
 * path for changes, and its card); a link's `lesson` shows its card.
 */
function bindLessons({ engine, schema, live }) {
  fillSelect($('lesson'), [['', 'Lessons…'], ...LESSONS.map((l) => [l.id, l.title])]);
  const defaults = readUrl(engine, schema, '', live.races).view;
  const open = (at) => {
    const { config, view, messages } = readUrl(engine, schema, lessonSteps(at.lesson)[at.step].query, live.races);
    showLesson(at, open);
    live.change({ config, view: { ...defaults, ...view, lesson: lessonValue(at.lesson, at.step) }, autoplay: view.autoplay && !reducedMotion(), note: messages.join('\n') });
  };
  $('lesson').addEventListener('change', (e) => {
    const lesson = lessonById(e.target.value);
    if (lesson) open({ lesson, step: 0 });
  });
  $('lesson-close').addEventListener('click', () => {
    showLesson(undefined, open);
    live.change({ view: { lesson: '' }, restart: false });
  });
  showLesson(lessonAt(live.view.lesson), open);
}

/** Wires the Teaching view and Default demo buttons: each starts its preset, playing; and the lessons. */
export function bindPresets({ engine, schema, live, viewState }) {
  bindLessons({ engine, schema, live });
  const start = (name) => {
    const p = PRESETS[name];
    if (name === 'teaching') {
      viewState.teaching();
      live.controller.dispatch({ type: 'view', view: viewState.frameView() });
    }
    live.change({ config: engine.parseParams(p.pairs).config, view: p.view, autoplay: true, note: p.note });
  };
  $('teaching').addEventListener('click', () => start('teaching'));
  $('defaults').addEventListener('click', () => start('default'));
}
