// Charts of an experiment's result with Observable Plot (vendored with d3
// into www/vendor by `make build`, loaded on first use as classic scripts:
// their UMD builds need no import map, which the page's CSP would refuse).
// Everything drawn is a statistic the engine computed (the result's points:
// quartiles, whiskers, means, CIs, capped counts, the lower bound,
// histograms); this module only places it.
//
//   box    box plots: the q1–q3 bar, a median tick, whisker rules, the mean
//          as a dot, capped counts above, each point's lower bound as a dashed tick
//   mean   means against x with their 95% interval bands (bars with one x
//          value), the lower bound dashed, published reference means as crosses
//   excess mean steps − optimal with 95% intervals (episodes measured in steps)
//   hist   (targets experiments) one heatmap of sampled targets per point
// The experiment's header names the chart that fits it first (its `chart`).
// Series are drawn in the engine's styles (seriesStyles: the CLI charts'
// colour-blind-safe colours, markers and dashes), so no two look alike.

import { scriptURL } from '../shared/trusted.js';
import { seriesStyles } from '../shared/engine.js';
import { provenance, provenanceLine } from '../shared/provenance.js';

/** Plot's class name for its elements; www/style.css styles them (see drawExperiment). */
const CLASS = 'exp-plot';
const PAPER = { background: '#ffffff', color: '#1b1f24', fontSize: '12px', fontFamily: 'system-ui, sans-serif' };
const BOUND_COLOR = '#6b7280';
const CAPPED_COLOR = '#c0262d';
const REFERENCE_COLOR = '#111111';

let plotReady = null;

function loadScript(src) {
  return new Promise((resolve, reject) => {
    const s = document.createElement('script');
    s.src = scriptURL(src);
    s.onload = resolve;
    s.onerror = () => reject(new Error(`could not load ${src} (run \`make build\`)`));
    document.head.append(s);
  });
}

/** Loads d3 and Plot once; resolves to the Plot namespace. */
export function loadPlot() {
  plotReady ??= (async () => {
    if (!globalThis.d3) await loadScript(new URL('../vendor/d3.min.js', import.meta.url).href);
    if (!globalThis.Plot) await loadScript(new URL('../vendor/plot.umd.min.js', import.meta.url).href);
    return globalThis.Plot;
  })();
  return plotReady;
}

/** Series i's style { colour, dash, marker } (the engine's, shared with the CLI's charts). */
function styleOf(i) {
  const all = seriesStyles();
  return all[i % all.length];
}

/** The colour and symbol scales of `series`, in the engine's styles. */
function seriesScales(series) {
  return {
    color: { domain: series, range: series.map((_, i) => styleOf(i).colour), legend: true },
    symbol: { domain: series, range: series.map((_, i) => styleOf(i).marker) },
  };
}

/** The header's chart → this module's mode. */
const HEADER_MODES = { box: 'box', line: 'mean', heatmap: 'hist' };

/** The chart modes that fit a result's experiment, the header's own first. */
export function chartModes(result) {
  const e = result.experiment;
  const modes = e.kind === 'targets' ? ['hist', 'box', 'mean'] : ['box', 'mean'];
  if (e.kind === 'episodes' && e.metric !== 'excess' && result.points.some((p) => p.excess_mean !== undefined)) modes.push('excess');
  if (result.paired?.length) modes.push('paired');
  const first = HEADER_MODES[e.chart];
  return first && modes.includes(first) ? [first, ...modes.filter((m) => m !== first)] : modes;
}

export const MODE_LABELS = { box: 'Box plots', mean: 'Means with 95% intervals', excess: 'Mean steps − optimal with 95% intervals', hist: 'Histograms of targets', paired: 'Paired differences with 95% intervals' };

/** The x axis's name in a sentence: its parameter key (its label can be long). */
export function xName(result) {
  return result.experiment.x.key ?? result.experiment.x.label;
}

const fmt = (v, d = 1) => (v === null || v === undefined ? '—' : Number.isInteger(v) ? String(v) : Number(v).toFixed(d));

/** The intervals of a result's point ({estimate, lo, hi, level, method}). */
const INTERVALS = ['mean', 'median', 'excess_mean'];

/**
 * A point with its intervals flattened as the CSV flattens them: field `f`
 * becomes `f` (the estimate), `f_lo` and `f_hi`.
 */
export function flatPoint(p) {
  const out = { ...p };
  for (const f of INTERVALS) {
    const i = p[f];
    if (i && typeof i === 'object') Object.assign(out, { [f]: i.estimate, [`${f}_lo`]: i.lo, [`${f}_hi`]: i.hi });
  }
  return out;
}

/** The tooltip text of a point (as the result has it, or flattened). */
export function pointSummary(result, point) {
  const e = result.experiment;
  const d = flatPoint(point);
  const lines = [
    e.x.values.length > 1 ? `${d.series}, ${xName(result)} = ${d.x}` : String(d.series),
    `mean ${fmt(d.mean)} [${fmt(d.mean_lo)}, ${fmt(d.mean_hi)}] (n = ${d.n})`,
    `median ${fmt(d.median)} [${fmt(d.median_lo)}, ${fmt(d.median_hi)}], quartiles ${fmt(d.q1)}–${fmt(d.q3)}`,
    `whiskers ${fmt(d.whisker_low)}–${fmt(d.whisker_high)}, range ${fmt(d.min)}–${fmt(d.max)}`,
  ];
  if (d.excess_mean !== undefined && e.metric !== 'excess') lines.push(`steps − optimal ${fmt(d.excess_mean)} [${fmt(d.excess_mean_lo)}, ${fmt(d.excess_mean_hi)}]`);
  if (d.capped) lines.push(`${d.capped} capped (kept at the cap)`);
  if (d.lower_bound !== null && d.lower_bound !== undefined) lines.push(`lower bound ${fmt(d.lower_bound, 2)}`);
  lines.push('click: open in the live view');
  return lines.join('\n');
}

/** Plot data: each point flattened, with its series label as `s` and its x text as `xs`. */
function pointData(result) {
  return result.points.map((p) => ({ ...flatPoint(p), s: String(p.series), xs: String(p.x) }));
}

/** For a log axis: values ≤ 0 (no steps) are drawn at half the smallest positive value. */
function logFloor(data, fields) {
  let min = Infinity;
  for (const d of data) for (const f of fields) if (d[f] > 0 && d[f] < min) min = d[f];
  return Number.isFinite(min) ? min / 2 : 0.5;
}

/** The points that have a lower bound (each point's own: series may differ in N, r_v or start). */
function boundData(data) {
  return data.filter((d) => d.lower_bound !== null && d.lower_bound !== undefined);
}

/** Published values, as [{ x, xs, y, label }] (the header's `references`, in the metric's units). */
function referenceData(result) {
  return (result.experiment.references ?? []).flatMap((r) => r.x.map((x, i) => ({ x, xs: String(x), y: r.y[i], label: r.label })));
}

/** Values for a log axis: ≤ 0 (no steps) is drawn at the axis floor. */
function yOf(log, floor) {
  return (f) => (d) => (d[f] === null || d[f] === undefined ? NaN : log ? Math.max(d[f], floor) : d[f]);
}

/** The layout of points: faceted by x value, series side by side (one x value: series only). */
function layout(result) {
  const e = result.experiment;
  const single = e.x.values.length === 1;
  return { single, fx: single ? {} : { fx: 'xs' } };
}

function boxPlot(Plot, result, width) {
  const e = result.experiment;
  const data = pointData(result);
  const log = e.y.log;
  const floor = log ? logFloor(data, ['whisker_low', 'q1', 'median', 'mean', 'min', 'lower_bound']) : 0;
  const y = yOf(log, floor);
  const { single, fx } = layout(result);
  const series = e.series;
  const bounds = boundData(data);
  const refs = referenceData(result);
  const marks = [
    Plot.ruleX(data, { ...fx, x: 's', y1: y('whisker_low'), y2: y('whisker_high'), stroke: 's' }),
    Plot.barY(data, { ...fx, x: 's', y1: y('q1'), y2: y('q3'), fill: 's', fillOpacity: 0.35, stroke: 's' }),
    Plot.tickY(data, { ...fx, x: 's', y: y('median'), stroke: 's', strokeWidth: 2.5 }),
    Plot.dot(data, { ...fx, x: 's', y: y('mean'), fill: 's', stroke: 's', r: 3.5, symbol: 's' }),
    Plot.text(data.filter((d) => d.capped > 0), { ...fx, x: 's', y: y('whisker_high'), text: (d) => String(d.capped), dy: -7, fontSize: 9, fill: CAPPED_COLOR }),
  ];
  if (bounds.length) marks.push(Plot.tickY(bounds, { ...fx, x: 's', y: y('lower_bound'), stroke: BOUND_COLOR, strokeWidth: 1.5, strokeDasharray: '4,2' }));
  if (refs.length) marks.push(Plot.dot(refs, { ...(single ? {} : { fx: 'xs' }), y: y('y'), symbol: 'times', r: 5, stroke: REFERENCE_COLOR, strokeWidth: 2 }));
  marks.push(Plot.tip(data, Plot.pointerX({ ...fx, x: 's', y: y('median'), title: (d) => pointSummary(result, d), fontSize: 11 })));
  return Plot.plot({
    width,
    height: 380,
    marginLeft: 56,
    marginBottom: single ? 50 : 36,
    style: PAPER,
    className: CLASS,
    ...(single ? {} : { fx: { domain: e.x.values, label: e.x.label, padding: 0.12 } }),
    x: single ? { domain: series, label: null, tickRotate: series.some((l) => l.length > 12) ? -15 : 0 } : { domain: series, axis: null, paddingInner: 0.15, paddingOuter: 0.1 },
    y: { label: e.y.label, type: log ? 'log' : 'linear', grid: true, nice: true },
    ...seriesScales(series),
    marks,
  });
}

/**
 * Means with 95% intervals: `f` names the mean and interval fields (mean,
 * mean_lo, mean_hi; or the excess ones). Against a numeric x, lines with
 * interval bands; otherwise dots with interval bars.
 */
/** The frame the means and the paired differences share. */
const MEANS_FRAME = { height: 380, marginLeft: 56, marginRight: 24, marginBottom: 40, style: PAPER, className: CLASS };

/** Their x scale: the labels as bands (one x value), else the x values, numeric or as points. */
function xScale(e, single, numeric, bands) {
  if (single) return { type: 'band', domain: bands, label: null, padding: 0.4 };
  if (numeric) return { label: e.x.label, type: e.x.log ? 'log' : 'linear', grid: true };
  return { label: e.x.label, type: 'point', domain: e.x.values, padding: 0.3 };
}

function meanPlot(Plot, result, width, f = { mean: 'mean', lo: 'mean_lo', hi: 'mean_hi', label: result.experiment.y.label, bounds: true }) {
  const e = result.experiment;
  const data = pointData(result);
  const { single } = layout(result);
  const numeric = e.x.numeric && !single;
  const xv = single ? (d) => d.s : numeric ? (d) => Number(d.x) : (d) => d.xs;
  const log = e.y.log && f.bounds;
  const floor = log ? logFloor(data, [f.lo, f.mean, 'lower_bound']) : 0;
  const y = yOf(log, floor);
  const bounds = f.bounds ? boundData(data) : [];
  const refs = f.bounds ? referenceData(result) : [];
  const series = e.series;
  const marks = [];
  if (!single) {
    marks.push(Plot.areaY(data, { x: xv, y1: y(f.lo), y2: y(f.hi), fill: 's', z: 's', fillOpacity: 0.15 }));
    // One line per series, in its dash (a dash pattern is not a channel).
    series.forEach((label, i) => {
      const dash = styleOf(i).dash;
      marks.push(Plot.lineY(data.filter((d) => d.s === label), { x: xv, y: y(f.mean), stroke: 's', strokeWidth: 1.8, ...(dash.length ? { strokeDasharray: dash.join(',') } : {}) }));
    });
  }
  marks.push(Plot.ruleX(data, { x: xv, y1: y(f.lo), y2: y(f.hi), stroke: 's', strokeOpacity: single ? 1 : 0.6, strokeWidth: single ? 2 : 1 }));
  marks.push(Plot.dot(data, { x: xv, y: y(f.mean), fill: 's', stroke: 's', symbol: 's', r: 3.5 }));
  if (bounds.length) {
    if (single) marks.push(Plot.tickY(bounds, { x: xv, y: y('lower_bound'), stroke: BOUND_COLOR, strokeWidth: 1.5, strokeDasharray: '4,2' }));
    else marks.push(Plot.lineY(bounds, { x: xv, y: y('lower_bound'), z: 's', stroke: BOUND_COLOR, strokeDasharray: '6,4' }));
    marks.push(Plot.text([bounds[bounds.length - 1]], { x: xv, y: y('lower_bound'), text: () => 'lower bound', dy: 10, textAnchor: 'end', fill: BOUND_COLOR, fontSize: 10 }));
  }
  if (refs.length) {
    const rx = numeric ? (d) => Number(d.x) : (d) => d.xs;
    marks.push(Plot.dot(refs, { x: rx, y: y('y'), symbol: 'times', r: 5, stroke: REFERENCE_COLOR, strokeWidth: 2 }));
    marks.push(Plot.text([refs[0]], { x: rx, y: y('y'), text: (d) => d.label, dx: 8, dy: -10, textAnchor: 'start', fontSize: 10, fill: REFERENCE_COLOR }));
  }
  marks.push(Plot.tip(data, Plot.pointer({ x: xv, y: y(f.mean), title: (d) => pointSummary(result, d), fontSize: 11 })));
  return Plot.plot({
    ...MEANS_FRAME,
    width,
    x: xScale(e, single, numeric, series),
    y: { label: f.label, type: log ? 'log' : 'linear', grid: true, nice: true },
    ...seriesScales(series),
    marks,
  });
}

function excessPlot(Plot, result, width) {
  // The bound is in the metric's units (steps), so it is not drawn here.
  return meanPlot(Plot, result, width, { mean: 'excess_mean', lo: 'excess_mean_lo', hi: 'excess_mean_hi', label: 'steps − optimal steps', bounds: false });
}

/** The engine's paired comparisons as plot data: `s` names the pair, `p` the series' point. */
function pairedData(result) {
  return (result.paired ?? [])
    .filter((c) => Number.isFinite(c.difference?.estimate))
    .map((c) => ({
      s: `${c.series} − ${c.reference}`,
      x: c.x,
      xs: String(c.x),
      d: c.difference.estimate,
      lo: c.difference.lo,
      hi: c.difference.hi,
      n: c.n,
      wins: c.wins,
      ties: c.ties,
      losses: c.losses,
      p: result.points[c.point],
    }));
}

/** The tooltip of a paired comparison. */
function pairedSummary(result, d) {
  const at = result.experiment.x.values.length > 1 ? ` at ${xName(result)} = ${d.xs}` : '';
  return `${d.s}${at}\npaired difference ${fmt(d.d)} [${fmt(d.lo)}, ${fmt(d.hi)}] over ${d.n} trials\nthe first took fewer in ${d.wins}, as many in ${d.ties}, more in ${d.losses}\nclick: open the first in the live view`;
}

/** Each pair's mean difference (series − reference, trial by trial) with its interval, against 0. */
function pairedPlot(Plot, result, width) {
  const e = result.experiment;
  const data = pairedData(result);
  const pairs = [...new Set(data.map((d) => d.s))];
  const { single } = layout(result);
  const numeric = e.x.numeric && !single;
  const xv = single ? (d) => d.s : numeric ? (d) => Number(d.x) : (d) => d.xs;
  const marks = [Plot.ruleY([0], { stroke: BOUND_COLOR, strokeWidth: 1.5, strokeDasharray: '4,2' })];
  if (!single) {
    pairs.forEach((label, i) => {
      const dash = styleOf(i).dash;
      marks.push(Plot.lineY(data.filter((d) => d.s === label), { x: xv, y: 'd', stroke: 's', strokeWidth: 1.5, ...(dash.length ? { strokeDasharray: dash.join(',') } : {}) }));
    });
  }
  marks.push(Plot.ruleX(data.filter((d) => Number.isFinite(d.lo)), { x: xv, y1: 'lo', y2: 'hi', stroke: 's', strokeWidth: 2 }));
  marks.push(Plot.dot(data, { x: xv, y: 'd', fill: 's', stroke: 's', symbol: 's', r: 3.5 }));
  marks.push(Plot.tip(data, Plot.pointer({ x: xv, y: 'd', title: (d) => pairedSummary(result, d), fontSize: 11 })));
  return Plot.plot({
    ...MEANS_FRAME,
    width,
    x: xScale(e, single, numeric, pairs),
    y: { label: `${e.y.label}: first − second, trial by trial (0: no difference)`, grid: true, nice: true },
    ...seriesScales(pairs),
    marks,
  });
}

/** Side of a point's square histogram (its config's n, else √length). */
function histSide(p) {
  const len = p.histogram.length;
  const n = p.config?.n;
  if (Number.isInteger(n) && n * n === len) return n;
  const s = Math.round(Math.sqrt(len));
  return s * s === len ? s : 0;
}

/** Legend ticks for counts: 0 and the powers of ten up to the largest. */
function decades(cells) {
  let max = 0;
  for (const d of cells) if (d.c > max) max = d.c;
  const out = [0];
  for (let t = 1; t <= max; t *= 10) out.push(t);
  return out;
}

function histPlot(Plot, result, width) {
  const e = result.experiment;
  const pts = pointData(result).filter((p) => Array.isArray(p.histogram) && histSide(p) > 0);
  if (!pts.length) throw new Error('this result has no histograms');
  const n = histSide(pts[0]);
  const label = (p) => [e.series.length > 1 ? p.s : '', e.x.values.length > 1 ? `${xName(result)} = ${p.x}` : ''].filter(Boolean).join(', ') || p.s;
  const cells = [];
  for (const p of pts) {
    const side = histSide(p);
    const f = label(p);
    for (let i = 0; i < p.histogram.length; i++) cells.push({ f, i: (i % side) + 1, j: Math.floor(i / side) + 1, c: p.histogram[i], p });
  }
  const facets = pts.map(label);
  const cols = Math.min(facets.length, Math.max(1, Math.floor(width / 180)));
  const rows = Math.ceil(facets.length / cols);
  const side = Math.floor(width / cols);
  const ticks = [1, Math.ceil(n / 2), n];
  const fxOf = (d) => facets.indexOf(d.f) % cols;
  const fyOf = (d) => Math.floor(facets.indexOf(d.f) / cols);
  return Plot.plot({
    width,
    height: rows * side + 60,
    marginLeft: 44,
    marginTop: 30,
    style: PAPER,
    className: CLASS,
    fx: { axis: null, padding: 0.08 },
    fy: { axis: null, padding: 0.1 },
    x: { type: 'band', domain: Array.from({ length: n }, (_, k) => k + 1), ticks, label: 'x', padding: 0 },
    y: { type: 'band', domain: Array.from({ length: n }, (_, k) => k + 1), ticks, label: 'y', padding: 0 },
    // symlog: a delta prior's one full cell and a wide prior's few per cell both show.
    color: { type: 'symlog', scheme: 'magma', legend: true, label: 'targets per cell (symlog scale)', ticks: decades(cells) },
    marks: [
      Plot.cell(cells, { fx: fxOf, fy: fyOf, x: 'i', y: 'j', fill: 'c', inset: 0, shapeRendering: 'crispEdges' }),
      Plot.text(facets.map((f, k) => ({ f, k })), { fx: (d) => d.k % cols, fy: (d) => Math.floor(d.k / cols), frameAnchor: 'top', dy: -14, text: 'f', fontSize: 11 }),
      Plot.tip(cells, Plot.pointer({ fx: fxOf, fy: fyOf, x: 'i', y: 'j', title: (d) => `${d.f}\ncell (${d.i}, ${d.j}): ${d.c} targets\nclick: open in the live view` })),
    ],
  });
}

/**
 * Draws `result` in `el` (replacing what was there) as `mode`.
 * onPoint(point) is called when a point is clicked. Resolves to the plot
 * element (a <figure> with the legend, or an <svg>).
 */
export async function drawExperiment(el, result, mode, { onPoint = () => {} } = {}) {
  const Plot = await loadPlot();
  const width = Math.max(360, Math.floor(el.clientWidth || 800));
  const draw = { box: boxPlot, mean: meanPlot, excess: excessPlot, hist: histPlot, paired: pairedPlot }[mode];
  if (!draw) throw new Error(`unknown chart ${JSON.stringify(mode)}`);
  const fig = draw(Plot, result, width);
  // Plot puts <style> elements in what it draws; the page's CSP (no inline
  // styles) would refuse them, so they come out before the chart goes in
  // (www/style.css has the same rules for .exp-plot), and go back into
  // exported SVG files, which are not under the page's CSP.
  fig.plotStyles = [...fig.querySelectorAll('style')].map((st) => {
    st.remove();
    return st.textContent;
  });
  // What standaloneSvg needs for its legend and caption.
  fig.result = result;
  fig.mode = mode;
  fig.addEventListener('click', () => {
    const v = fig.value;
    if (!v) return;
    onPoint(v.p ?? v);
  });
  el.replaceChildren(fig);
  return fig;
}

const SVG_NS = 'http://www.w3.org/2000/svg';

function svgEl(name, attrs, text) {
  const node = document.createElementNS(SVG_NS, name);
  for (const [k, v] of Object.entries(attrs)) node.setAttribute(k, String(v));
  if (text !== undefined) node.textContent = text;
  return node;
}

/** An SVG path of marker `name` (the engine's marker names, as Plot's symbols) of radius r at (0, 0), and whether it is filled. */
export function markerPath(name, r = 4.5) {
  const ring = (n, rr, inner = null) => {
    const k = inner === null ? n : 2 * n;
    return Array.from({ length: k }, (_, i) => {
      const a = -Math.PI / 2 + (2 * Math.PI * i) / k;
      const q = i % 2 === 1 && inner !== null ? inner : rr;
      return [q * Math.cos(a), q * Math.sin(a)];
    });
  };
  const poly = (pts) => `M${pts.map(([x, y]) => `${x.toFixed(2)},${y.toFixed(2)}`).join('L')}Z`;
  const lines = (segs) => segs.map(([a, b, c, d]) => `M${a.toFixed(2)},${b.toFixed(2)}L${c.toFixed(2)},${d.toFixed(2)}`).join('');
  switch (name) {
    case 'circle': return { d: `M${r},0A${r},${r} 0 1,1 ${-r},0A${r},${r} 0 1,1 ${r},0Z`, filled: true };
    case 'square': return { d: poly([[-0.9 * r, -0.9 * r], [0.9 * r, -0.9 * r], [0.9 * r, 0.9 * r], [-0.9 * r, 0.9 * r]]), filled: true };
    case 'triangle': return { d: poly(ring(3, 1.25 * r)), filled: true };
    case 'diamond': return { d: poly([[0, -1.3 * r], [1.3 * r, 0], [0, 1.3 * r], [-1.3 * r, 0]]), filled: true };
    case 'star': return { d: poly(ring(5, 1.35 * r, 0.6 * r)), filled: true };
    case 'hexagon': return { d: poly(ring(6, 1.1 * r)), filled: true };
    case 'times': return { d: lines([[-r, -r, r, r], [-r, r, r, -r]]), filled: false };
    case 'plus': return { d: lines([[-1.25 * r, 0, 1.25 * r, 0], [0, -1.25 * r, 0, 1.25 * r]]), filled: false };
    case 'wye': return { d: lines(ring(3, 1.3 * r).map(([x, y]) => [0, 0, x, -y])), filled: false };
    default: return { d: lines(ring(6, 1.25 * r).slice(0, 3).map(([x, y]) => [-x, -y, x, y])), filled: false };
  }
}

let measureCtx = null;
/** The width of `text` in px at `size` in the exports' font. */
function textWidth(text, size) {
  measureCtx ??= document.createElement('canvas').getContext('2d');
  measureCtx.font = `${size}px ${PAPER.fontFamily}`;
  return measureCtx.measureText(text).width;
}

/** `text` in lines no wider than `max` px at `size`, broken at spaces; a word longer than a line (a URL) fills each line it needs. */
function wrapLines(text, max, size) {
  const lines = [];
  let line = '';
  for (const word of String(text).split(' ')) {
    const joined = line ? `${line} ${word}` : word;
    if (textWidth(joined, size) <= max) {
      line = joined;
      continue;
    }
    if (textWidth(word, size) <= max) {
      lines.push(line);
      line = word;
      continue;
    }
    // Too long for any line: character by character from where the line is.
    let rest = line ? ' ' : '';
    for (const ch of word) {
      if (textWidth(line + rest + ch, size) > max && (line + rest).trim()) {
        lines.push(line + rest.trimEnd());
        line = '';
        rest = '';
      }
      rest += ch;
    }
    line += rest;
  }
  lines.push(line);
  return lines.filter((l, i) => l || i === 0);
}

/**
 * The caption of an exported chart: what ran (experiment, trials, seed,
 * preset), which build made the results and when, and this export's
 * provenance (the page's build, the date, the page's URL and the spec).
 */
export function exportCaption(result, mode, p = provenance()) {
  const e = result.experiment;
  const s = result.spec;
  const made = result.provenance ? provenanceLine(result.provenance) : 'made before results carried their provenance';
  return [
    `${e.name} · ${MODE_LABELS[mode] ?? mode} · ${s.trials} ${e.kind === 'targets' ? 'samples' : 'trials'} per point · seed ${s.seed} · preset ${s.preset ?? 'none'}`,
    `results: ${made}`,
    `exported: ${provenanceLine(p)}`,
    `page: ${p.command}`,
    `spec: ${JSON.stringify(s)}`,
  ];
}

/**
 * One standalone SVG of a drawn chart: a title, the legend (Plot draws it
 * as HTML beside the SVG; here it wraps onto as many rows as it needs,
 * each series with its colour and marker), the plot's SVG, and a caption
 * (exportCaption), on its background. The provenance is also kept as JSON
 * in <metadata>. Returns the SVG text.
 */
export function standaloneSvg(fig, title) {
  const plotSvg = fig.tagName.toLowerCase() === 'svg' ? fig : fig.querySelector(':scope > svg:not([class$="-ramp"])') ?? fig.querySelector('svg:last-of-type');
  const w = Number(plotSvg.getAttribute('width'));
  const h = Number(plotSvg.getAttribute('height'));
  const legend = [];
  const color = typeof fig.scale === 'function' ? fig.scale('color') : null;
  // Series i is drawn in the engine's style i: its colour and marker.
  if (color && color.type === 'ordinal') color.domain.forEach((d, i) => legend.push([String(d), styleOf(i).colour, styleOf(i).marker]));
  const ramp = fig.tagName.toLowerCase() === 'figure' ? fig.querySelector('svg[class$="-ramp"]') : null;
  // Legend items in rows: a row ends before an item would cross the right edge.
  const rows = [[]];
  let x = 10;
  for (const item of legend) {
    const iw = 30 + textWidth(item[0], 12);
    if (x + iw > w - 10 && rows.at(-1).length) {
      rows.push([]);
      x = 10;
    }
    rows.at(-1).push({ item, x });
    x += iw;
  }
  const top = 28;
  const legendH = legend.length ? 20 * rows.length + 4 : ramp ? Number(ramp.getAttribute('height')) + 6 : 0;
  const p = provenance();
  const caption = fig.result ? exportCaption(fig.result, fig.mode, p).flatMap((l) => wrapLines(l, w - 20, 11)) : [];
  const total = top + legendH + h + (caption.length ? 8 + 15 * caption.length : 0);
  const out = svgEl('svg', { xmlns: SVG_NS, width: w, height: total, viewBox: `0 0 ${w} ${total}`, 'font-family': PAPER.fontFamily, 'font-size': 12 });
  out.append(svgEl('metadata', { id: 'torus-search-provenance' }, JSON.stringify({ export: p, results: fig.result?.provenance ?? null, spec: fig.result?.spec ?? null })));
  if (fig.plotStyles?.length) out.append(svgEl('style', {}, fig.plotStyles.join('\n')));
  out.append(svgEl('rect', { width: '100%', height: '100%', fill: PAPER.background }));
  out.append(svgEl('text', { x: 10, y: 19, 'font-size': 14, 'font-weight': 600, fill: PAPER.color }, title));
  rows.forEach((row, r) => {
    for (const { item: [label, fill, marker], x: ix } of row) {
      const y = top + 4 + 20 * r;
      out.append(svgEl('rect', { x: ix, y, width: 16, height: 12, fill, 'fill-opacity': 0.35, stroke: fill }));
      if (marker) {
        const m = markerPath(marker, 3.5);
        out.append(svgEl('path', { d: m.d, transform: `translate(${ix + 8},${y + 6})`, fill: m.filled ? fill : 'none', stroke: m.filled ? '#333' : fill, 'stroke-width': m.filled ? 0.6 : 1.6 }));
      }
      out.append(svgEl('text', { x: ix + 20, y: y + 10, fill: PAPER.color }, label));
    }
  });
  if (!legend.length && ramp) {
    const r = ramp.cloneNode(true);
    r.setAttribute('x', 10);
    r.setAttribute('y', top);
    out.append(r);
  }
  const body = plotSvg.cloneNode(true);
  body.setAttribute('x', 0);
  body.setAttribute('y', top + legendH);
  out.append(body);
  caption.forEach((line, i) => out.append(svgEl('text', { x: 10, y: top + legendH + h + 18 + 15 * i, 'font-size': 11, fill: '#4b5563' }, line)));
  return new XMLSerializer().serializeToString(out);
}

/** Renders SVG text to a PNG blob at `scale` (the page's CSP allows blob: images for this). */
export function svgToPng(svgText, scale = 2) {
  return new Promise((resolve, reject) => {
    const url = URL.createObjectURL(new Blob([svgText], { type: 'image/svg+xml' }));
    const img = new Image();
    img.onload = () => {
      try {
        const canvas = document.createElement('canvas');
        canvas.width = Math.ceil(img.width * scale);
        canvas.height = Math.ceil(img.height * scale);
        const ctx = canvas.getContext('2d');
        ctx.scale(scale, scale);
        ctx.drawImage(img, 0, 0);
        canvas.toBlob((blob) => (blob ? resolve(blob) : reject(new Error('the browser made no PNG'))), 'image/png');
      } catch (err) {
        reject(err);
      } finally {
        URL.revokeObjectURL(url);
      }
    };
    img.onerror = () => {
      URL.revokeObjectURL(url);
      reject(new Error('the chart could not be rendered as an image'));
    };
    img.src = url;
  });
}
