// The share panel's side of the live view: the link and file name of the
// run, its boards for a PNG, its episode for a file, and replaying an
// imported episode (through the one config path), checked move for move
// once it ends. A restart abandons the check.

import { readUrl } from '../shared/url-state.js';
import { showMessage } from '../shared/ui.js';
import { bindShare, replayVerdict } from './share.js';

/**
 * @param {object} o
 * @param {object} o.engine, o.schema, o.races   the wasm module, its schema, the race options
 * @param {object} o.controller, o.live, o.boards   the state machine, the LiveState, the boards
 * @param {() => string} o.link                  the page's link, up to date
 */
export function bindReplay({ engine, schema, races, controller, live, boards, link }) {
  let replay = null; // { path, speed, timed } while an imported episode replays
  live.onRestart(() => {
    replay = null;
  });
  controller.on('state', (s) => {
    if (!replay || (s !== 'found' && s !== 'capped')) return;
    const { path: want, speed, timed } = replay;
    replay = null;
    live.change({ view: { speed }, restart: false });
    const { same, message } = replayVerdict(controller.runs[0].path(), want, timed);
    showMessage(message);
    document.body.dataset.replay = same ? 'match' : 'differ';
  });
  bindShare({
    link,
    name: () => `torus-${live.config.searcher}-n${live.config.n}-seed${live.config.seed}`,
    canvases: () => boards.canvases(controller.runs.length),
    episode: async () => {
      const runs = await controller.dispatch({ type: 'export' });
      return runs && { engineVersion: engine.version(), query: live.query({ full: true }), runs };
    },
    replay: async (query, path) => {
      const got = readUrl(engine, schema, query, races);
      if (got.messages.length) throw new Error(got.messages.join(' '));
      const ready = live.change({ config: got.config, view: got.view, autoplay: true });
      controller.dispatch({ type: 'speed', speed: 'max' });
      // Set after the restart clears it, before the replay can end.
      replay = { path, speed: got.view.speed, timed: got.config.ms !== null };
      showMessage(`Replaying the imported episode (seed ${got.config.seed}, ${path.length - 1} steps)…`);
      await ready;
    },
  });
}
