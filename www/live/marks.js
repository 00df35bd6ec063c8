// The marks drawn over the heat layer: their colours, shapes and names,
// and the painters that draw them, used both by the renderer (on the board)
// and by the legend (its icons), so a legend icon is the mark itself.
//
// Every mark differs from every other by shape AND colour; the colours are
// told apart under deuteranopia, protanopia and tritanopia (the CVD test in
// tests/e2e/colors.test.mjs checks the pairwise distances). Each mark has a
// dark rim or halo, so it reads on any heat colour.
// Painters work in the context's current units: `px` is one device pixel.

/** Mark colours (sRGB hex), by the identity the CVD test compares. */
export const INK = {
  white: '#ffffff', // the searcher, its path, the decision arrows, the vision disc, the selected cell
  start: '#ff9f1c', // orange square
  target: '#ff4141', // red cross in a ring
  practice: '#c032f3', // violet diamond
  rollout: '#7fd4ff', // light-blue trail
  next: '#ffd602', // yellow: the planned path (dashed) and the chosen move's arrow
};

export const COLORS = {
  background: '#101418',
  grid: 'rgba(255,255,255,0.10)',
  frame: 'rgba(255,255,255,0.45)',
  path: '#f2f5f7',
  pathHalo: 'rgba(0,0,0,0.65)',
  rim: '#000000',
  fade: 'rgba(16,20,24,0.62)',
  hatch: 'rgba(255,255,255,0.55)',
};

/**
 * Every mark the board can draw, in legend order: its name for people and
 * what it means (the legend's tooltip). The renderer reports marks by these
 * keys; the test "every drawn mark has a legend entry" holds it to them.
 */
export const MARKS = {
  searcher: ['searcher', 'where the searcher stands (a halo keeps it visible at any N)'],
  path: ['path', 'the cells the searcher has walked'],
  shared: ['shared path', 'dashed: the moves this run kept from the run it branched from'],
  branch: ['branch point', 'the move where this run branched off with its new setting'],
  start: ['start', 'the cell the searcher started from'],
  target: ['target', 'the hidden target (shown once found, or with Reveal target)'],
  practice: ['practice target', 'the target the newest imagined search looked for'],
  rollout: ['rollout', 'an imagined search: a trail from its start (ring) to its end (dot), fading as it ages'],
  planned: ['planned path', 'the cells a planner means to walk next'],
  arrows: ['decision arrows', 'how often each neighbour was tried; the chosen one thick and yellow'],
  vision: ['vision disc', 'cells within the detection radius rᵥ'],
  searched: ['searched', 'hatched: cells within rᵥ of the path'],
  treeLine: ['tree line', 'the moves from the searcher to a node of the tree: the one in focus, or the loop’s selection (dotted, ending in a ring)'],
  selected: ['selected cell', 'the cell you clicked (its details are under the board)'],
};

const TAU = 2 * Math.PI;

/** Strokes the current path twice: a dark rim `rim` px wider, then `color`. */
function rimmed(ctx, color, width, px, rim = 2) {
  ctx.strokeStyle = COLORS.rim;
  ctx.lineWidth = (width + rim) * px;
  ctx.stroke();
  ctx.strokeStyle = color;
  ctx.lineWidth = width * px;
  ctx.stroke();
}

/** The searcher: a white disc with a dark rim inside a soft light halo. */
export function paintSearcher(ctx, x, y, r, px) {
  ctx.beginPath();
  ctx.arc(x, y, r + 4 * px, 0, TAU);
  ctx.fillStyle = 'rgba(255,255,255,0.28)';
  ctx.fill();
  ctx.beginPath();
  ctx.arc(x, y, r + 4 * px, 0, TAU);
  ctx.strokeStyle = 'rgba(0,0,0,0.55)';
  ctx.lineWidth = 1.5 * px;
  ctx.stroke();
  ctx.beginPath();
  ctx.arc(x, y, r, 0, TAU);
  ctx.fillStyle = INK.white;
  ctx.fill();
  ctx.strokeStyle = COLORS.rim;
  ctx.lineWidth = 1.5 * px;
  ctx.stroke();
}

/** The start: a square outline. */
export function paintStart(ctx, x, y, h, px) {
  ctx.beginPath();
  ctx.rect(x - h, y - h, 2 * h, 2 * h);
  rimmed(ctx, INK.start, 2, px);
}

/** The target: a cross in a ring. */
export function paintTarget(ctx, x, y, h, px) {
  ctx.beginPath();
  ctx.moveTo(x - h, y - h);
  ctx.lineTo(x + h, y + h);
  ctx.moveTo(x + h, y - h);
  ctx.lineTo(x - h, y + h);
  ctx.moveTo(x + 1.3 * h, y);
  ctx.arc(x, y, 1.3 * h, 0, TAU);
  rimmed(ctx, INK.target, 2.2, px);
}

/** A ring around the target, `t` in [0, 1) of a found pulse (grows and fades). */
export function paintPulse(ctx, x, y, h, t, px) {
  ctx.beginPath();
  ctx.arc(x, y, h * (1.3 + 3.5 * t), 0, TAU);
  ctx.globalAlpha = 1 - t;
  rimmed(ctx, INK.target, 2.5, px);
  ctx.globalAlpha = 1;
}

/** The branch point: a filled triangle pointing up, rimmed. */
export function paintBranch(ctx, x, y, h, px) {
  ctx.beginPath();
  ctx.moveTo(x, y - 1.15 * h);
  ctx.lineTo(x + h, y + 0.75 * h);
  ctx.lineTo(x - h, y + 0.75 * h);
  ctx.closePath();
  ctx.fillStyle = INK.white;
  ctx.fill();
  ctx.strokeStyle = COLORS.rim;
  ctx.lineWidth = 1.5 * px;
  ctx.stroke();
}

/** The dashes over a shared path (the path is drawn under them). */
export const SHARED_DASH = 'rgba(16,20,24,0.9)';

/** The practice target: a diamond outline. */
export function paintPractice(ctx, x, y, h, px) {
  ctx.beginPath();
  ctx.moveTo(x, y - h);
  ctx.lineTo(x + h, y);
  ctx.lineTo(x, y + h);
  ctx.lineTo(x - h, y);
  ctx.closePath();
  rimmed(ctx, INK.practice, 1.8, px);
}

/** A rollout's start (a ring) or end (a filled dot). */
export function paintTrailEnd(ctx, x, y, r, px, end) {
  ctx.beginPath();
  ctx.arc(x, y, r, 0, TAU);
  if (end) {
    ctx.fillStyle = INK.rollout;
    ctx.fill();
    ctx.strokeStyle = COLORS.rim;
    ctx.lineWidth = px;
    ctx.stroke();
  } else rimmed(ctx, INK.rollout, 1.5, px, 1.5);
}

/** The vision disc: a dashed circle of radius `r`. */
export function paintVision(ctx, x, y, r, px) {
  ctx.beginPath();
  ctx.arc(x, y, r, 0, TAU);
  ctx.setLineDash([3 * px, 3 * px]);
  ctx.strokeStyle = 'rgba(255,255,255,0.6)';
  ctx.lineWidth = px;
  ctx.stroke();
  ctx.setLineDash([]);
}

/** The selected cell: four corner brackets around a cell of half-size `h`. */
export function paintSelected(ctx, x, y, h, px) {
  const k = h * 0.45;
  ctx.beginPath();
  for (const [sx, sy] of [[-1, -1], [1, -1], [1, 1], [-1, 1]]) {
    ctx.moveTo(x + sx * h, y + sy * (h - k));
    ctx.lineTo(x + sx * h, y + sy * h);
    ctx.lineTo(x + sx * (h - k), y + sy * h);
  }
  rimmed(ctx, INK.white, 1.5, px);
}

/** A decision arrow from (x0, y0) to (x1, y1); the chosen move's is thick and yellow. */
export function paintArrow(ctx, x0, y0, x1, y1, chosen, px) {
  const head = 7 * px;
  const ang = Math.atan2(y1 - y0, x1 - x0);
  ctx.beginPath();
  ctx.moveTo(x0, y0);
  ctx.lineTo(x1, y1);
  ctx.moveTo(x1 - head * Math.cos(ang - 0.5), y1 - head * Math.sin(ang - 0.5));
  ctx.lineTo(x1, y1);
  ctx.lineTo(x1 - head * Math.cos(ang + 0.5), y1 - head * Math.sin(ang + 0.5));
  rimmed(ctx, chosen ? INK.next : INK.white, chosen ? 3.5 : 2, px);
}

/** A hatch pattern tile (diagonal lines) for the searched cells, `size` px square. */
export function hatchTile(size) {
  const c = document.createElement('canvas');
  c.width = c.height = size;
  const ctx = c.getContext('2d');
  ctx.strokeStyle = COLORS.hatch;
  ctx.lineWidth = Math.max(1, size / 6);
  ctx.beginPath();
  for (const o of [-size, 0, size]) {
    ctx.moveTo(o, size);
    ctx.lineTo(o + size, 0);
  }
  ctx.stroke();
  return c;
}

/** The legend's icon of mark `key`, drawn into a small canvas (w × h CSS px at `dpr`). */
export function paintIcon(canvas, key, dpr = 1) {
  const w = 28;
  const h = 16;
  canvas.width = w * dpr;
  canvas.height = h * dpr;
  canvas.style.width = `${w}px`;
  canvas.style.height = `${h}px`;
  const ctx = canvas.getContext('2d');
  ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
  ctx.fillStyle = COLORS.background;
  ctx.fillRect(0, 0, w, h);
  ctx.lineCap = 'round';
  ctx.lineJoin = 'round';
  ICONS[key](ctx, w, h);
}

const line = (ctx, color, width, dash = []) => {
  ctx.beginPath();
  ctx.moveTo(4, 8);
  ctx.lineTo(24, 8);
  ctx.setLineDash(dash);
  rimmed(ctx, color, width, 1);
  ctx.setLineDash([]);
};

const ICONS = {
  searcher: (ctx) => paintSearcher(ctx, 14, 8, 3.5, 1),
  path: (ctx) => line(ctx, COLORS.path, 2.5),
  shared: (ctx) => {
    line(ctx, COLORS.path, 3);
    ctx.beginPath();
    ctx.moveTo(4, 8);
    ctx.lineTo(24, 8);
    ctx.setLineDash([3, 3]);
    ctx.strokeStyle = SHARED_DASH;
    ctx.lineWidth = 1.6;
    ctx.stroke();
    ctx.setLineDash([]);
  },
  branch: (ctx) => paintBranch(ctx, 14, 8, 5, 1),
  start: (ctx) => paintStart(ctx, 14, 8, 4.5, 1),
  target: (ctx) => paintTarget(ctx, 14, 8, 3.5, 1),
  practice: (ctx) => paintPractice(ctx, 14, 8, 5, 1),
  rollout: (ctx) => {
    for (let i = 0; i < 4; i++) {
      ctx.beginPath();
      ctx.moveTo(6 + 4 * i, 8);
      ctx.lineTo(10 + 4 * i, 8);
      ctx.globalAlpha = 0.25 + 0.25 * i;
      ctx.strokeStyle = INK.rollout;
      ctx.lineWidth = 2;
      ctx.stroke();
    }
    ctx.globalAlpha = 1;
    paintTrailEnd(ctx, 5, 8, 2.5, 1, false);
    paintTrailEnd(ctx, 23, 8, 2.5, 1, true);
  },
  planned: (ctx) => line(ctx, INK.next, 2, [4, 3]),
  arrows: (ctx) => {
    paintArrow(ctx, 3, 8, 12, 8, false, 0.8);
    paintArrow(ctx, 15, 8, 25, 8, true, 0.8);
  },
  vision: (ctx) => paintVision(ctx, 14, 8, 6.5, 1),
  searched: (ctx, w, h) => {
    ctx.fillStyle = ctx.createPattern(hatchTile(6), 'repeat');
    ctx.fillRect(2, 2, w - 4, h - 4);
  },
  treeLine: (ctx) => {
    ctx.beginPath();
    ctx.moveTo(3, 8);
    ctx.lineTo(17, 8);
    ctx.setLineDash([1.5, 3]);
    rimmed(ctx, INK.white, 2.5, 1, 2.5);
    ctx.setLineDash([]);
    ctx.beginPath();
    ctx.arc(21.5, 8, 4, 0, TAU);
    rimmed(ctx, INK.white, 1.8, 1, 2.5);
  },
  selected: (ctx) => paintSelected(ctx, 14, 8, 6, 1),
};
