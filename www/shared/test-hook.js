// The page's test interface: `window.torusTest`, for the end-to-end tests
// and the browser benchmark (tests/e2e/). It only reads the page's state
// and forwards commands; nothing in the page depends on it.
//
//   ready()            resolves (to true when runs exist) once the newest reset has finished
//   state()            the controller's state: idle | running | paused | choosing | found | capped | error
//   speed()            the controller's speed: loops per frame, or 'max'
//   runs()             a snapshot per run: { label, config, searcher, deliberates, n, start,
//                      target, optimal, status, steps, revisits, pathLen, work, rolloutSteps, scores,
//                      intent, planning }
//   path(i = 0)        run i's path so far (cells, start first)
//   dispatch(cmd)      a controller command (see www/live/controller.js), e.g. { type: 'stepPhase' }
//   phase()            the last phase the first run did, select | expand | rollout | backup, or null
//                      (between loops, or not stepped phase by phase)
//   timeline()         the engine's point of the first run { move, loop, phase, end }, or null
//   seek(point)        seeks to { move, loop, phase } (a 'seek' command); resolves to { ok, error }
//                      once the page has drawn that point
//   back(unit)         one phase | loop | move back, as seek
//   offer()            the edit waiting for a choice (state choosing): { move, from, config }, or null
//   lineage(i = 0)     run i's branch points (the engine's [{ move, config }], oldest first)
//   tree(query, run)   run `run`'s tree of the decision (Race.tree: { shape, nodes: [{ id, parent,
//                      move, visits, value, mean, explore, uct, … }], total_nodes }; mean + explore =
//                      uct, the UCT split its parent's selection weighs, null at the root), or null
//                      for a searcher without one
//   narration()        the narration line's text
//   treeView(i = 1)    the tree panel: { shown, board: whose tree (0: A, 1: B, switched by the buttons
//                      #tree-board-0 and -1), nodes, rootVisits, drawn, hover, marked: [node indices],
//                      focus, cell: node i's cell, at: node i's client point or null }
//   treeFocus(focus)   shows 'all', 'best' or a node id's subtree (as a click on a node)
//   request(type, payload)  a raw search-worker request (benchLoops, usage, panicForTest, oomForTest)
//   engine             the page's wasm module (benchmark workloads)
//   resets()           how many resets the controller has had (a click that restarted the run adds one)
//   drawn(i = 0)       what the last frame drew on board i: { marks: [MARKS keys of www/live/marks.js],
//                      layers: [heat and hatched layer names], uploads (putImageData calls so far),
//                      at: [x, y] the searcher's point in cell units (a cell's centre is x + 0.5) }
//   legend()           what the legend names now: { marks: [data-mark], layers: [data-layer] }
//   watchFrames()      starts a fresh frameLog(): per drawn frame { ticket, ts, runs: [{ start,
//                      configStart, path0, position, status }], marks and at (board 0's: see drawn) }
//   batch.results()    the last batch's trial results; batch.usePool(k) a pool of k workers;
//                      batch.paired() a race's paired summary (the engine's summarizePaired), or null
//   view()             which view is shown: live | experiments; show(view) switches
//   experiments        the Experiments view:
//     state()            its state (name, trials, seed, preset, params, sweep, series); setState(s)
//     spec()             the engine spec of that state
//     run()              runs it (as the Run button); resolves to the result text, or null
//     cancel()           cancels a run (as the Cancel button)
//     status()           idle | running | done | cancelled | error | loaded
//     result()           the finished or loaded result's text, or null; shown() the drawn (maybe partial) result
//     lastRun()          { seconds, workers, units, name } of the last finished run
//     workers()          the pool size; usePool(k) a pool of k workers
//     load(text, name)   loads a results file's text (as the file input); resolves to true if loaded
//     exported(kind)     resolves to the text of a download: csv | trials-csv | paired-csv | json | svg (png: its size in bytes)
//     openPoint(index)   opens a point of the shown result in the live view (as a click)
//     config(index)      that point's config

import { experimentSpec } from './url-state.js';
import { treeViewState } from '../live/tree-panel.js';

/** Resolves to `done`'s answer once two animation frames have passed (the page has drawn it). */
async function shown(done) {
  const answer = await done;
  await new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)));
  return answer;
}

export function installTestHook({ controller, engine, batch, experiments, showView, boards, tree }) {
  // What each drawn frame showed, once a test asks (bounded, so a long soak
  // does not grow it): the reset ticket, and per run its configured start,
  // the first path cell and the position.
  let frameLog = null;
  controller.on('frame', ({ runs }) => {
    if (!frameLog) return;
    if (frameLog.length >= 10_000) frameLog.shift();
    frameLog.push({
      ticket: controller.resets,
      ts: performance.now(),
      marks: boards.drawnMarks(0),
      at: boards.renderers[0].at,
      runs: runs.map((r) => ({ start: r.start, configStart: r.config.start.join(','), path0: r.pathLen ? r.pathView()[0] : -1, position: r.frame.position, status: r.status() })),
    });
  });
  window.torusTest = {
    watchFrames: () => {
      frameLog = [];
    },
    frameLog: () => frameLog ?? [],
    ready: () => controller.whenReady(),
    state: () => controller.state,
    speed: () => controller.speed,
    fps: () => controller.meter.fps,
    runs: () =>
      controller.runs.map((r) => ({
        label: r.label,
        config: r.config,
        searcher: r.searcher,
        deliberates: r.deliberates,
        n: r.n,
        start: r.start,
        target: r.target,
        optimal: r.optimal,
        status: r.status(),
        steps: r.frame.steps,
        revisits: r.frame.revisits,
        pathLen: r.pathLen,
        work: r.work(),
        rolloutSteps: r.rolloutSteps(),
        scores: r.frame.scores ?? null,
        intent: r.intent ? Array.from(r.intent) : [],
        planning: r.frame.planning ?? null,
      })),
    path: (i = 0) => controller.runs[i]?.path() ?? [],
    dispatch: (cmd) => controller.dispatch(cmd),
    phase: () => controller.runs[0]?.frame.point?.phase ?? null,
    timeline: () => (controller.timeline ? structuredClone(controller.timeline) : null),
    seek: (point) => shown(controller.dispatch({ type: 'seek', point })),
    back: (unit) => shown(controller.dispatch({ type: 'back', unit })),
    offer: () => (controller.offer ? structuredClone(controller.offer) : null),
    lineage: (i = 0) => structuredClone(controller.runs[i]?.lineage ?? []),
    tree: async (query = {}, run = 0) => (await controller.dispatch({ type: 'request', request: 'tree', payload: { run, query } }))?.tree ?? null,
    narration: () => document.getElementById('narration').textContent,
    treeView: (i = 1) => treeViewState(tree, i),
    treeFocus: (focus) => tree.setFocus(focus),
    request: (type, payload) => controller.dispatch({ type: 'request', request: type, payload }),
    engine,
    resets: () => controller.resets,
    drawn: (i = 0) => ({ marks: boards.drawnMarks(i), layers: [...boards.renderers[i].drawnLayers], uploads: boards.renderers[i].uploads, at: boards.renderers[i].at }),
    legend: () => ({
      marks: [...document.querySelectorAll('#legend [data-mark]')].map((e) => e.dataset.mark),
      layers: [...document.querySelectorAll('#legend [data-layer]')].filter((e) => !e.hidden).map((e) => e.dataset.layer),
    }),
    batch: {
      results: () => batch.results,
      paired: () => batch.paired,
      usePool: (k) => batch.usePool(k),
      killWorker: (i) => batch.pool?.killWorker(i) ?? false,
      replaced: () => batch.pool?.replaced ?? 0,
    },
    view: () => document.body.dataset.view,
    show: (view) => showView(view),
    experiments: {
      state: () => structuredClone(experiments.state),
      setState: (s) => experiments.setState(s),
      spec: () => experimentSpec(experiments.state),
      run: () => experiments.run(),
      cancel: () => experiments.cancel(),
      status: () => document.body.dataset.experiment,
      result: () => experiments.result?.text ?? null,
      shown: () => experiments.shown,
      lastRun: () => experiments.lastRun,
      workers: () => experiments.runner.workers,
      usePool: (k) => experiments.runner.usePool(k),
      killWorker: (i) => experiments.runner.pool.killWorker(i),
      replaced: () => experiments.runner.pool.replaced,
      load: (text, name) => experiments.loadText(text, name),
      exported: async (kind) => {
        const blob = await experiments.exported(kind);
        return kind === 'png' ? blob.size : blob.text();
      },
      openPoint: (index) => experiments.openPoint(index),
      config: (index) => experiments.shown?.points.find((p) => p.index === index)?.config ?? null,
    },
  };
}
