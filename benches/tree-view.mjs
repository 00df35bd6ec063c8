#!/usr/bin/env node
// The tree view's cost per frame at 10^5 nodes, in headless Chromium: the
// page's own modules (www/live/tree-layout.js, tree-view.js) on a tree the
// engine grew (a `tree` decision of 10^5 loops at N = 40 on a uniform
// prior, as benches/teach-node.mjs), exported whole as columns. Times the
// layout (once per tree) and a frame's drawing (every frame), at the tree
// panel's size at 1440×900 with device pixel ratios 1 and 2. Timed here,
// never in tests. Needs `make build` (www/pkg). Prints one JSON object.
// Usage: node benches/tree-view.mjs
import { ROOT, launchBrowser, openPage, startServer } from '../tests/e2e/harness.mjs';

const server = await startServer(ROOT);
const out = {};
try {
  for (const dpr of [1, 2]) {
    const browser = await launchBrowser({ viewport: { width: 1440, height: 900 }, deviceScaleFactor: dpr });
    try {
      const { page } = await openPage(browser.context, `${server.url}?autoplay=0`);
      await page.waitForFunction(() => window.torusTest?.runs().length, null, { timeout: 60_000 });
      out[`dpr_${dpr}`] = await page.evaluate(async () => {
        const { layoutTree } = await import('/www/live/tree-layout.js');
        const { TreeView } = await import('/www/live/tree-view.js');
        const engine = window.torusTest.engine;
        const race = new engine.Race([{ prior: 'uniform', loops: 100000, variant: 'tree', tree_nodes: 100016 }]);
        race.advance(99999);
        const cols = race.treeColumns(0, { max_nodes: 1 << 20 });
        race.free();
        const canvas = document.getElementById('tree-canvas');
        document.getElementById('tree-panel').hidden = false;
        const view = new TreeView(canvas, engine.paletteLut('viridis'));
        const time = (f, k) => {
          const ms = [];
          for (let i = 0; i < k; i++) {
            const t = performance.now();
            f();
            ms.push(performance.now() - t);
          }
          ms.sort((a, b) => a - b);
          return { mean: ms.reduce((a, b) => a + b, 0) / k, median: ms[k >> 1], p95: ms[Math.floor(0.95 * (k - 1))], max: ms[k - 1] };
        };
        const layout = time(() => layoutTree(cols), 10);
        view.setTree(cols);
        // A frame with the loop's selection path, the pulse and a node in focus drawn over the tree.
        view.hover = Math.min(cols.id.length - 1, 5000);
        // Reading a pixel back makes the canvas rasterise the frame inside the timing.
        const draw = time(() => {
          view.draw({ phase: null, now: 0, still: true });
          view.ctx.getImageData(0, 0, 1, 1);
        }, 60);
        return { nodes: cols.id.length, max_depth: view.layout.maxDepth, canvas_px: [canvas.width, canvas.height], drawn_nodes: view.drawnCount, layout_ms: layout, draw_ms: draw };
      });
    } finally {
      await browser.close();
    }
  }
} finally {
  await server.close();
}
console.log(JSON.stringify(out, null, 2));
