// The tree panel: fetches the decision's tree from the search worker when
// the run has changed (Race.treeColumns, cut by the panel's query: the
// visit threshold, the best line or a node in focus), has tree-view.js draw
// it, and links it with the lattice both ways: hovering or focusing a node
// draws its line of cells on the board; hovering a cell on the board marks
// the nodes that reach it. In a race, an A/B switch chooses whose tree it
// shows (board A's or B's), and the linking follows that board. The words under it describe the node in focus
// with the engine's numbers, its UCT split included (every node but the
// root: the terms its parent's selection weighs now, as the engine's tree
// export computes them with the selection's own function).

import { $, setText, fmtInt, fmtNum, showMessage } from '../shared/ui.js';
import { readTreeView, treeViewText } from '../shared/url-state.js';
import { TreeView } from './tree-view.js';
import { cellText } from './panels/stats.js';
import { MOVE_NAMES } from './renderer.js';

/** The most nodes asked for: enough for a teaching tree, few enough to ship every change. */
const MAX_NODES = 4000;
/** While running, the tree is fetched at most this often (ms). */
const FETCH_MS = 250;
const BOARDS = ['A', 'B'];

export class TreePanel {
  /**
   * @param {object} o
   * @param {object} o.controller  the playback state machine (its 'ask' command)
   * @param {object} o.boards      the boards (the line drawn on the board shown, the hovered cell)
   * @param {Uint8Array} o.lut     the value ramp (a palette's 256×RGBA table)
   * @param {string} [o.link]      a link's `tree=` text (board and focus), applied to the first runs
   * @param {(text) => void} [o.onLink]  the board or focus changed: the new `tree=` text
   */
  constructor({ controller, boards, lut, link = '', onLink = () => {} }) {
    Object.assign(this, { controller, boards, onLink });
    this.pending = readTreeView(link) ?? null;
    this.linked = this.pending ? treeViewText(this.pending) : ''; // the link's `tree=` text now
    this.view = new TreeView($('tree-canvas'), lut);
    this.key = '';
    this.inflight = false;
    this.fetchedAt = 0;
    this.has = [true, true]; // per board: its run has a tree (false once the engine said none)
    this.focus = undefined; // 'all', 'best' or a node id, from the first reset on
    this.board = 0; // whose tree is shown: 0 (A) or 1 (B, in a race)
    this.runs = [];
    this.run = null;
    drawRamp($('tree-ramp'), lut);
    $('tree-best').addEventListener('change', (e) => this.setFocus(e.target.checked ? 'best' : 'all'));
    $('tree-min').addEventListener('change', () => this.refetch());
    $('tree-all').addEventListener('click', () => this.setFocus('all'));
    BOARDS.forEach((_, k) => $(`tree-board-${k}`).addEventListener('click', () => this.setBoard(k)));
    this.bindPointer();
    boards.onHoverCell = (cell) => {
      if (!this.view.cols) return;
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
    if (split) s += Number.isFinite(split.explore) ? `. UCT = ${fmtNum(split.mean)} + ${fmtNum(split.explore)} = ${fmtNum(split.uct)}` : '. UCT = ∞: never tried, so its parent’s selection tries it first';
    if (cols.hidden[i]) s += `. ${cols.hidden[i]} child${cols.hidden[i] === 1 ? '' : 'ren'} not shown`;
    return `${s}.`;
  }

  /** The engine's UCT terms for node `i` (its parent's selection's now), or null at the root. */
  uctSplit(i) {
    const { cols } = this.view;
    if (i <= 0 || !cols.uct || Number.isNaN(cols.uct[i])) return null;
    return { mean: cols.mean[i], explore: cols.explore[i], uct: cols.uct[i] };
  }

  setFocus(focus) {
    this.showFocus(focus);
    this.link();
    this.refetch();
  }

  /** The link's `tree=` text follows the board and focus shown. */
  link() {
    this.linked = treeViewText({ board: this.board, focus: this.focus });
    this.onLink(this.linked);
  }

  /** Shows board `k`'s tree (0: A, 1: B); a node in focus was the other tree's, so the whole tree shows. */
  setBoard(k) {
    if (k === this.board || k >= this.runs.length) return;
    this.board = k;
    this.boards.treeBoard = k;
    this.forget();
    if (typeof this.focus === 'number') this.showFocus('all');
    this.showBoards();
    this.link();
    this.refetch();
  }

  /** The A/B switch: shown in a race, the board shown pressed, a board without a tree disabled. */
  showBoards() {
    const race = this.runs.length > 1;
    $('tree-board').hidden = !race;
    BOARDS.forEach((name, k) => {
      const b = $(`tree-board-${k}`);
      b.setAttribute('aria-pressed', String(k === this.board));
      b.disabled = race && !this.viewable(k);
      b.title = b.disabled ? `Board ${name}'s searcher keeps no search tree` : `Show board ${name}'s search tree`;
    });
  }

  /** True when board `k`'s run has a tree to show. */
  viewable(k) {
    return !!this.runs[k]?.deliberates && this.has[k];
  }

  /** Drops the tree shown and its links to the lattice. */
  forget() {
    this.view.setTree(null);
    this.view.hover = -1;
    this.view.markCell(-1);
    this.boards.treeLine = null;
    this.key = '';
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

  /** Fresh runs: forget the tree and the focus (a link's applies to the first runs); the board stays while there is a race. */
  reset(runs) {
    this.runs = runs;
    this.has = [true, true];
    const pending = this.pending;
    this.pending = null;
    this.showFocus(pending?.focus ?? 'all');
    this.board = pending?.board ?? this.board;
    if (this.board >= runs.length) {
      if (pending?.board) showMessage(`Tree view: tree=${treeViewText(pending)} shows board B's tree, but there is no race (vs=). Showing the tree of the only board.`);
      this.board = 0;
    }
    this.boards.treeBoard = this.board;
    // Fresh runs have a fresh tree: a focus on one of the old one's nodes goes (and leaves the link).
    if (treeViewText({ board: this.board, focus: this.focus }) !== this.linked) this.link();
    this.forget();
    this.showBoards();
    $('tree-panel').hidden = true;
  }

  /**
   * Draws the tree of the board chosen among `runs` (fetching it when that
   * run has changed) with the loop in flight; returns true while something
   * on it moves.
   */
  update(runs, { running, now, still }) {
    this.runs = runs;
    const run = runs[this.board];
    this.run = run;
    if (!runs.some((_, k) => this.viewable(k))) {
      $('tree-panel').hidden = true;
      return false;
    }
    if (!this.viewable(this.board)) {
      // The other board has a tree: the panel stays, with its switch.
      if (this.view.cols) this.forget();
      $('tree-panel').hidden = false;
      setText('tree-count', '');
      setText('tree-info', `Board ${BOARDS[this.board]}'s searcher keeps no search tree: switch to board ${BOARDS[1 - this.board]}.`);
      return this.view.draw({ phase: null, now, still });
    }
    const f = run.frame;
    const key = `${this.board}|${f.steps}|${f.work}|${JSON.stringify(f.point)}|${JSON.stringify(this.query())}`;
    if (key !== this.key && !this.inflight && (!running || now - this.fetchedAt >= FETCH_MS)) this.fetch(key);
    if ($('tree-panel').hidden) return false;
    return this.view.draw({ phase: f.phase ?? null, now, still });
  }

  async fetch(key) {
    this.inflight = true;
    this.fetchedAt = performance.now();
    const runs = this.controller.runs;
    const board = this.board;
    try {
      const answer = await this.controller.dispatch({ type: 'ask', request: 'treeColumns', payload: { run: board, query: this.query() } });
      if (runs !== this.controller.runs || board !== this.board) return;
      this.key = key;
      if (!answer.tree) {
        this.has[board] = false;
        this.showBoards();
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
      this.link();
    } finally {
      this.inflight = false;
      this.redraw();
    }
  }
}

/** What the tree view shows, for tests: whose tree (board 0 or 1), nodes laid out and drawn, the root's visits, the node in focus, the nodes marked, where node `i` is drawn (client px). */
export function treeViewState(panel, i = 1) {
  const v = panel.view;
  const rect = v.canvas.getBoundingClientRect();
  const k = rect.width / Math.max(1, v.canvas.width);
  const at = v.pos && i < (v.layout?.count ?? 0) && Number.isFinite(v.pos[2 * i]) ? [rect.left + v.pos[2 * i] * k, rect.top + v.pos[2 * i + 1] * k] : null;
  return { shown: !$('tree-panel').hidden, board: panel.board, nodes: v.layout?.count ?? 0, rootVisits: v.cols?.visits[0] ?? -1, drawn: v.drawnCount, hover: v.hover, marked: [...v.marked], focus: panel.focus, cell: v.cols?.cell[i] ?? -1, at };
}

/** The value ramp of the legend. */
function drawRamp(canvas, lut) {
  canvas.width = 256;
  canvas.height = 1;
  canvas.getContext('2d').putImageData(new ImageData(new Uint8ClampedArray(lut), 256, 1), 0, 0);
}
