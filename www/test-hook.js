// The page's test interface: `window.torusTest`, for the end-to-end tests
// and the browser benchmark (tests/e2e/). It only reads the page's state
// and forwards commands; nothing in the page depends on it.
//
//   ready()            resolves (to true when runs exist) once the newest reset has finished
//   state()            the controller's state: idle | running | paused | found | capped | error
//   speed()            the controller's speed: loops per frame, or 'max'
//   runs()             a snapshot per run: { label, config, searcher, deliberates, n, start,
//                      target, optimal, status, steps, pathLen, work, rolloutSteps }
//   path(i = 0)        run i's path so far (cells, start first)
//   dispatch(cmd)      a controller command (see www/controller.js)
//   request(type, payload)  a raw search-worker request (benchLoops, usage, panicForTest)
//   engine             the page's wasm module (benchmark workloads)
//   batch.results()    the last batch's trial results; batch.usePool(k) a pool of k workers

export function installTestHook({ controller, engine, batch }) {
  window.torusTest = {
    ready: () => controller.whenReady(),
    state: () => controller.state,
    speed: () => controller.speed,
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
        pathLen: r.pathLen,
        work: r.work(),
        rolloutSteps: r.rolloutSteps(),
      })),
    path: (i = 0) => controller.runs[i]?.path() ?? [],
    dispatch: (cmd) => controller.dispatch(cmd),
    request: (type, payload) => controller.dispatch({ type: 'request', request: type, payload }),
    engine,
    batch: {
      results: () => batch.results,
      usePool: (k) => batch.usePool(k),
    },
  };
}
