// Named starting points of the page: engine parameters (as URL pairs) and
// view parameters, plus what to tell the user; and their buttons.

import { $, setText, fillSelect } from '../shared/ui.js';
import { readUrl } from '../shared/url-state.js';
import { LESSONS, lessonById } from './lessons.js';
import { reducedMotion } from './motion.js';

export const PRESETS = {
  default: { pairs: [], view: { speed: 10, race: '' }, note: '' },
  teaching: {
    pairs: [['n', '11'], ['sigma', '2'], ['loops', '40'], ['seed', '3'], ['start', '2,2'], ['keep_traces', '3']],
    view: { speed: 1, race: '' },
    note: 'Teaching view: one MCTS loop per frame. Each loop draws a practice target (◇) from the belief (the prior, or the posterior: the prior with searched cells removed), picks the neighbour with the highest UCT value, runs a random rollout from it until the rollout finds the practice target, then adds one visit to every cell the loop passed and credits each with 1/(its own steps to the practice target): the picked neighbour gets 1/τ. Pause and press ↑ to step a single loop.',
  },
};

/** Shows lesson `lesson`'s card beside the playback bar (undefined: hides it). */
function showLesson(lesson) {
  $('lesson-card').hidden = !lesson;
  $('lesson').value = lesson?.id ?? '';
  if (!lesson) return;
  setText('lesson-title', lesson.title);
  setText('lesson-text', lesson.text);
  setText('lesson-look', lesson.look);
  setText('lesson-claim', lesson.claim);
}

/**
 * Wires the lessons: the list beside the playback bar opens one (its
 * settings, layers and race through the one path for changes, and its
 * card); a link's `lesson` shows its card.
 */
function bindLessons({ engine, schema, live }) {
  fillSelect($('lesson'), [['', 'Lessons…'], ...LESSONS.map((l) => [l.id, l.title])]);
  const defaults = readUrl(engine, schema, '', live.races).view;
  $('lesson').addEventListener('change', (e) => {
    const lesson = lessonById(e.target.value);
    if (!lesson) return;
    const { config, view, messages } = readUrl(engine, schema, lesson.query, live.races);
    showLesson(lesson);
    live.change({ config, view: { ...defaults, ...view, lesson: lesson.id }, autoplay: view.autoplay && !reducedMotion(), note: messages.join('\n') });
  });
  $('lesson-close').addEventListener('click', () => {
    showLesson(undefined);
    live.change({ view: { lesson: '' }, restart: false });
  });
  showLesson(lessonById(live.view.lesson));
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
