// Charts with uPlot (vendored into www/vendor by `make build`): steps taken
// against running time, one series per run, plus each run's optimal steps as
// a dashed line once it is known.

import uPlot from '../vendor/uPlot.esm.js';

const SERIES_COLORS = ['#ffd166', '#7fd4ff'];

export class StepsChart {
  /** @param {HTMLElement} el container */
  constructor(el) {
    this.el = el;
    this.plot = null;
    this.labels = [];
    this.data = [[]];
    this.optimal = [];
    this.lastT = -Infinity;
    this.lastUpdate = 0;
    this.ro = new ResizeObserver(() => this.resize());
    this.ro.observe(el);
  }

  width() {
    return Math.max(200, Math.floor(this.el.clientWidth || 300));
  }

  /** Starts a new chart for runs with these labels. */
  reset(labels) {
    this.labels = labels;
    this.data = [[], ...labels.map(() => [])];
    this.optimal = labels.map(() => null);
    this.lastT = -Infinity;
    if (this.plot) this.plot.destroy();
    const series = [{ label: 'time (s)' }];
    labels.forEach((label, i) => {
      series.push({ label, stroke: SERIES_COLORS[i % 2], width: 2, points: { show: false } });
    });
    labels.forEach((label, i) => {
      series.push({ label: `optimal (${i === 0 ? 'main' : 'race'})`, stroke: SERIES_COLORS[i % 2], width: 1, dash: [4, 4], points: { show: false } });
    });
    const axis = { stroke: '#93a1ae', grid: { stroke: 'rgba(255,255,255,0.07)' }, ticks: { stroke: 'rgba(255,255,255,0.15)' } };
    this.plot = new uPlot(
      {
        width: this.width(),
        height: 170,
        scales: { x: { time: false } },
        axes: [
          { ...axis, label: 'running time (s)', labelSize: 18, size: 34 },
          { ...axis, label: 'steps', labelSize: 18, size: 48 },
        ],
        series,
        legend: { live: false },
        cursor: { drag: { x: false, y: false } },
      },
      this.fullData(),
      this.el,
    );
  }

  fullData() {
    const x = this.data[0];
    const opt = this.optimal.map((o) => x.map(() => o));
    return [...this.data, ...opt];
  }

  /** Records steps at running time t (seconds); redraws at most 5 times a second. */
  push(t, steps, optimal, force = false) {
    if (!this.plot) return;
    optimal.forEach((o, i) => {
      this.optimal[i] = o;
    });
    if (t - this.lastT >= 0.05 || force) {
      this.data[0].push(t);
      steps.forEach((s, i) => this.data[i + 1].push(s));
      this.lastT = t;
      // Bound the history: thin out every other point when it grows long.
      if (this.data[0].length > 4000) this.data = this.data.map((arr) => arr.filter((_, j) => j % 2 === 0));
    }
    const now = performance.now();
    if (force || now - this.lastUpdate > 200) {
      this.lastUpdate = now;
      this.plot.setData(this.fullData());
    }
  }

  resize() {
    if (this.plot) this.plot.setSize({ width: this.width(), height: 170 });
  }
}
