// The tree view's layout: a tidy layout of the engine's tree columns
// (nodes in preorder with their parent, depth and exported leaves below;
// Race.treeColumns), computed once per tree and read every frame. A node
// spans its leaves' share of the width and sits at the middle of its span,
// one row per depth. `end[i]` is the preorder index after node i's subtree,
// so a drawing skips a subtree too narrow to see in one step (lazy: the cost
// of a frame follows the pixels, not the nodes). Pure: no DOM.

/**
 * @param {object} cols  the engine's columns: parent (Int32Array, −1 at the root), depth, leaves
 *                       (Uint32Array), one entry per node in preorder
 * @returns {{ count, x: Float64Array (0..1 across), span: Float64Array (share of the width),
 *            end: Uint32Array, parent: Int32Array (preorder index, −1 at the root),
 *            at: Int32Array (engine id → preorder index, −1 when not exported), depth, maxDepth }}
 */
export function layoutTree(cols) {
  const count = cols.parent.length;
  const { parent, at } = parentIndices(cols);
  const x = new Float64Array(count);
  const span = new Float64Array(count);
  const end = new Uint32Array(count);
  const next = new Float64Array(count); // where a node's next child's span starts
  const total = Math.max(1, count ? cols.leaves[0] : 1);
  let maxDepth = 0;
  for (let i = 0; i < count; i++) {
    const p = parent[i];
    const w = cols.leaves[i] / total;
    const from = p < 0 ? 0 : next[p];
    if (p >= 0) next[p] += w;
    span[i] = w;
    x[i] = from + w / 2;
    next[i] = from;
    if (cols.depth[i] > maxDepth) maxDepth = cols.depth[i];
  }
  // Subtree ends, from the back: a node's subtree ends where its last
  // descendant's does (preorder keeps a subtree contiguous).
  for (let i = count - 1; i >= 0; i--) {
    if (end[i] === 0) end[i] = i + 1;
    const p = parent[i];
    if (p >= 0 && end[i] > end[p]) end[p] = end[i];
  }
  return { count, x, span, end, parent, at, depth: cols.depth, maxDepth };
}

/** Each node's parent as a preorder index (−1 at the root); the columns name parents by engine id. */
function parentIndices(cols) {
  const count = cols.id.length;
  let maxId = 0;
  for (let i = 0; i < count; i++) if (cols.id[i] > maxId) maxId = cols.id[i];
  const at = new Int32Array(maxId + 1).fill(-1);
  for (let i = 0; i < count; i++) at[cols.id[i]] = i;
  const parent = new Int32Array(count);
  for (let i = 0; i < count; i++) parent[i] = cols.parent[i] < 0 ? -1 : at[cols.parent[i]];
  return { parent, at };
}

/** The preorder indices of node `i`'s line from the root (root first), from a layout. */
export function lineOf(layout, i) {
  const line = [];
  for (let k = i; k >= 0; k = layout.parent[k]) line.push(k);
  return line.reverse();
}
