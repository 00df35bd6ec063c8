// The tree panel: fetches the decision's tree from the search worker when
// the run has changed (Race.treeColumns, cut by the panel's query: the
// visit threshold, the best line or a node in focus), has tree-view.js draw
// it, and links it with the lattice both ways: hovering or focusing a node
// draws its line of cells on the board; hovering a cell on the board marks
// the nodes that reach it. The words under it describe the node in focus
// with the engine's numbers (its UCT split where the engine reported one:
// the root's moves, and the moves the loop's selection weighed).

import { $, setText, fmtInt, fmtNum, showMessage } from '../shared/ui.js';
import { TreeView } from './tree-view.js';
import { cellText } from './panels/stats.js';
import { MOVE_NAMES } from './renderer.js';

/** The most nodes asked for: enough for a teaching tree, few enough to ship every change. */
const MAX_NODES = 4000;
/** While running, the tree is fetched at most this often (ms). */
const FETCH_MS = 250;
const MOVE_INDEX = { up: 0, right: 1, down: 2, left: 3 };

export class TreePanel {
  /**
   * @param {object} o
   * @param {object} o.controller  the playback state machine (its 'ask' command)
   * @param {object} o.boards      the boards (the line drawn on board 0, the hovered cell)
   * @param {Uint8Array} o.lut     the value ramp (a palette's 256×RGBA table)
   * @param {string} [o.focus]     a link's focus ('best' or a node id), applied to the first runs
   * @param {(focus) => void} [o.onFocus]  the focus changed ('all', 'best' or a node id)
   */
  constructor({ controller, boards, lut, focus = '', onFocus = () => {} }) {
    Object.assign(this, { controller, boards, onFocus });
    this.pending = focus === 'best' ? 'best' : focus ? Number(focus) : null;
    this.view = new TreeView($('tree-canvas'), lut);
    this.key = '';
    this.inflight = false;
    this.fetchedAt = 0;
    this.has = true; // the run has a tree (false: hide the panel)
    this.focus = undefined; // 'all', 'best' or a node id, from the first reset on
    this.run = null;
    drawRamp($('tree-ramp'), lut);
    $('tree-best').addEventListener('change', (e) => this.setFocus(e.target.checked ? 'best' : 'all'));
    $('tree-min').addEventListener('change', () => this.refetch());
    $('tree-all').addEventListener('click', () => this.setFocus('all'));
    this.bindPointer();
    boards.onHoverCell = (cell) => {
      if (!this.has) return;
      const k = this.view.markCell(cell);
      if (cell >= 0 && this.run) setText('tree-info', k ? `${k} node${k === 1 ? '' : 's'} of the tree reach ${cellText(cell, this.run.n)} (squares).` : `No node of the tree shown reaches ${cellText(cell, this.run.n)}.`);
      this.redraw();
    };
  }

  bindPointer() {
    const c = $('tree-canvas');
    c.addEventListener('pointermove', (e) => this.hoverNode(this.view.nodeAt(e.clientX, e.clientY)));
    c.addEventListener('pointerleave', () => document.activeElement !== c && this.hoverNode(-1));
    c.addEventListener('click', (e) => {
      const i = this.view.nodeAt(e.clientX, e.clientY);
      if (i > 0) this.setFocus(this.view.cols.id[i]);
    });
    c.addEventListener('focus', () => this.hoverNode(Math.max(0, this.view.hover)));
    c.addEventListener('blur', () => this.hoverNode(-1));
    // Keys on the focused tree: ↑ parent, ↓ first child, ←/→ siblings, Enter focus the subtree.
    c.addEventListener('keydown', (e) => {
      const next = this.keyTarget(e.key);
      if (next === undefined) return;
      e.preventDefault();
      e.stopPropagation();
      if (next === 'focus') this.setFocus(this.view.hover > 0 ? this.view.cols.id[this.view.hover] : 'all');
      else if (next >= 0) this.hoverNode(next);
    });
  }

  /** The node a key on the focused tree moves to, 'focus', or undefined for a key it does not take. */
  keyTarget(key) {
    const v = this.view;
    if (!v.layout) return undefined;
    const h = Math.max(0, v.hover);
    const L = v.layout;
    const siblings = (dir) => {
      const p = L.parent[h];
      if (p < 0) return h;
      const kids = [];
      for (let k = p + 1; k < L.end[p]; k = L.end[k]) kids.push(k);
      const at = kids.indexOf(h);
      return kids[Math.max(0, Math.min(kids.length - 1, at + dir))];
    };
    switch (key) {
      case 'ArrowUp': return L.parent[h] >= 0 ? L.parent[h] : h;
      case 'ArrowDown': return h + 1 < L.end[h] ? h + 1 : h;
      case 'ArrowLeft': return siblings(-1);
      case 'ArrowRight': return siblings(1);
      case 'Enter': return 'focus';
      default: return undefined;
    }
  }

  /** Shows node `i` (−1: none) in words, and its line of cells on the lattice. */
  hoverNode(i) {
    const v = this.view;
    v.hover = v.layout && i < v.layout.count ? i : -1;
    this.boards.treeLine = v.hover >= 0 ? v.cellsOf(v.hover) : null;
    setText('tree-info', v.hover >= 0 && this.run ? this.describe(v.hover) : (v.cols?.note ?? ''));
    this.redraw();
  }

  /** A node in words: its moves from the root, N, Q/N, picks, and its UCT split where the engine gave it. */
  describe(i) {
    const { cols, layout } = this.view;
    const line = [];
    for (let k = i; layout.parent[k] >= 0; k = layout.parent[k]) line.push(MOVE_NAMES[cols.move[k]]);
    const where = line.length ? `${line.reverse().join(' → ')} (depth ${cols.depth[i]})` : 'The root (the searcher’s cell)';
    const q = cols.value[i];
    let s = `${where}, cell ${cellText(cols.cell[i], this.run.n)}: N = ${fmtInt(cols.visits[i])}, Q/N = ${Number.isFinite(q) ? fmtNum(q) : '– (unvisited)'}`;
    if (cols.picks[i] >= 0) s += `, picked ${fmtInt(cols.picks[i])} times this decision`;
    const split = this.uctSplit(i);
    if (split) s += `. UCT = ${fmtNum(split.mean)} + ${fmtNum(split.explore)} = ${fmtNum(split.uct)}`;
    if (cols.hidden[i]) s += `. ${cols.hidden[i]} child${cols.hidden[i] === 1 ? '' : 'ren'} not shown`;
    return `${s}.`;
  }

  /** The engine's UCT terms for node `i`: a root child's from the decision, else a candidate the loop's selection weighed. */
  uctSplit(i) {
    const { cols, layout } = this.view;
    const f = this.run.frame;
    if (layout.parent[i] === 0 && f.decision) return f.decision.children[cols.move[i]];
    for (const level of f.phase?.select ?? []) {
      for (const c of level.candidates) if (c.node === cols.id[i] && c.valid) return c;
    }
    return null;
  }

  setFocus(focus) {
    this.showFocus(focus);
    this.onFocus(focus);
    this.refetch();
  }

  showFocus(focus) {
    this.focus = focus;
    $('tree-best').checked = focus === 'best';
    $('tree-all').hidden = typeof focus !== 'number';
  }

  refetch() {
    this.key = '';
    this.redraw();
  }

  redraw() {
    this.controller.dispatch({ type: 'animate' });
  }

  query() {
    const min = Math.max(0, Math.floor(Number($('tree-min').value) || 0));
    return { max_nodes: MAX_NODES, min_visits: min, focus: this.focus };
  }

  /** Fresh runs: forget the tree and the focus. */
  reset() {
    this.has = true;
    const was = this.focus;
    this.showFocus(this.pending ?? 'all');
    this.pending = null;
    // Fresh runs have a fresh tree: a focus on one of the old one's nodes goes (and leaves the link).
    if (was !== undefined && was !== this.focus && this.focus === 'all') this.onFocus('all');
    this.view.setTree(null);
    this.view.hover = -1;
    this.boards.treeLine = null;
    this.key = '';
    $('tree-panel').hidden = true;
  }

  /**
   * Draws run `run`'s tree (fetching it when the run has changed) with the
   * loop in flight; returns true while something on it moves.
   */
  update(run, { running, now, still }) {
    this.run = run;
    if (!this.has || !run.deliberates) {
      $('tree-panel').hidden = true;
      return false;
    }
    const f = run.frame;
    const key = `${f.steps}|${f.work}|${JSON.stringify(f.point)}|${JSON.stringify(this.query())}`;
    if (key !== this.key && !this.inflight && (!running || now - this.fetchedAt >= FETCH_MS)) this.fetch(key);
    if ($('tree-panel').hidden) return false;
    return this.view.draw({ phase: f.phase ?? null, now, still });
  }

  async fetch(key) {
    this.inflight = true;
    this.fetchedAt = performance.now();
    const runs = this.controller.runs;
    try {
      const answer = await this.controller.dispatch({ type: 'ask', request: 'treeColumns', payload: { run: 0, query: this.query() } });
      if (runs !== this.controller.runs) return;
      this.key = key;
      if (!answer.tree) {
        this.has = false;
        $('tree-panel').hidden = true;
        return;
      }
      $('tree-panel').hidden = false;
      this.view.setTree(answer.tree);
      // The tables' star (depth 1) needs a short canvas, a tree a tall one.
      $('tree-canvas').classList.toggle('shallow', this.view.layout.maxDepth <= 1);
      setText('tree-lo', fmtNum(this.view.range[0], 3));
      setText('tree-hi', fmtNum(this.view.range[1], 3));
      setText('tree-count', `${fmtInt(answer.tree.id.length)} of ${fmtInt(answer.tree.total_nodes)} nodes shown`);
      if (this.view.hover >= 0) this.hoverNode(this.view.hover);
      else setText('tree-info', answer.tree.note);
    } catch (err) {
      // A trapped engine is the controller's to report (its message stays);
      // the tree waits for the restart.
      if (err.trap || this.controller.state === 'error') return;
      // A focus on a node that went with a real move: say so, show the whole tree.
      showMessage(`Tree view: ${err.message}. Showing the whole tree.`);
      this.showFocus('all');
      this.onFocus('all');
    } finally {
      this.inflight = false;
      this.redraw();
    }
  }
}

/** What the tree view shows, for tests: nodes laid out and drawn, the node in focus, the nodes marked, where node `i` is drawn (client px). */
export function treeViewState(panel, i = 1) {
  const v = panel.view;
  const rect = v.canvas.getBoundingClientRect();
  const k = rect.width / Math.max(1, v.canvas.width);
  const at = v.pos && i < (v.layout?.count ?? 0) && Number.isFinite(v.pos[2 * i]) ? [rect.left + v.pos[2 * i] * k, rect.top + v.pos[2 * i + 1] * k] : null;
  return { shown: !$('tree-panel').hidden, nodes: v.layout?.count ?? 0, drawn: v.drawnCount, hover: v.hover, marked: [...v.marked], focus: panel.focus, cell: v.cols?.cell[i] ?? -1, at };
}

/** The value ramp of the legend. */
function drawRamp(canvas, lut) {
  canvas.width = 256;
  canvas.height = 1;
  canvas.getContext('2d').putImageData(new ImageData(new Uint8ClampedArray(lut), 256, 1), 0, 0);
}
