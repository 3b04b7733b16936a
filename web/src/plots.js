// Plots of the trajectory's columns (uPlot), chosen by group and series, with a cursor line at
// the animation time.
import uPlot from 'uplot';

const COLORS = ['#2f7ed8', '#d9534f', '#5cb85c', '#f0ad4e', '#8e44ad', '#16a085', '#34495e', '#c0392b'];
const ORDER = ['coordinates', 'rates', 'energy', 'multipliers', 'tensions', 'outputs', 'residuals'];
const MAX_SHOWN = 8;

/** Groups present in `series`, in display order, each with its series names (pure, tested). */
export function groups(series) {
  const by = new Map();
  for (const s of series) {
    if (!by.has(s.group)) by.set(s.group, []);
    by.get(s.group).push(s.name);
  }
  return ORDER.filter((g) => by.has(g)).map((g) => ({ group: g, names: by.get(g) }));
}

export class Plots {
  constructor(root, plots) {
    this.data = plots;
    this.root = root;
    this.groups = groups(plots.series);
    const bar = document.createElement('div');
    bar.className = 'plot-bar';
    this.select = document.createElement('select');
    this.select.id = 'plot-group';
    for (const { group, names } of this.groups) {
      const o = document.createElement('option');
      o.value = group;
      o.textContent = `${group} (${names.length})`;
      this.select.appendChild(o);
    }
    this.list = document.createElement('div');
    this.list.className = 'plot-series';
    bar.append(this.select, this.list);
    this.chartBox = document.createElement('div');
    this.chartBox.className = 'chart';
    root.append(bar, this.chartBox);
    this.select.addEventListener('change', () => this.showGroup(this.select.value));
    this.time = plots.t[0] ?? 0;
    if (this.groups.length) this.showGroup(this.groups[0].group);
    window.addEventListener('resize', () => this.chart && this.chart.setSize(this.size()));
  }

  showGroup(group) {
    const { names } = this.groups.find((g) => g.group === group);
    this.list.replaceChildren();
    const checked = new Set(names.slice(0, MAX_SHOWN));
    for (const name of names) {
      const label = document.createElement('label');
      const box = document.createElement('input');
      box.type = 'checkbox';
      box.checked = checked.has(name);
      box.value = name;
      box.addEventListener('change', () => this.draw(this.chosen()));
      label.append(box, ` ${name}`);
      this.list.appendChild(label);
    }
    this.draw(this.chosen());
  }

  chosen() {
    return [...this.list.querySelectorAll('input:checked')].map((b) => b.value);
  }

  size() {
    return { width: Math.max(320, this.chartBox.clientWidth || 800), height: 280 };
  }

  draw(names) {
    if (this.chart) this.chart.destroy();
    const byName = new Map(this.data.series.map((s) => [s.name, s.values]));
    const opts = {
      ...this.size(),
      scales: { x: { time: false } },
      axes: [{ label: 't [s]' }, {}],
      series: [{ label: 't' }, ...names.map((n, k) => ({ label: n, stroke: COLORS[k % COLORS.length], width: 1.5 }))],
      hooks: { draw: [(u) => this.cursor(u)] },
      legend: { live: true },
    };
    this.chart = new uPlot(opts, [this.data.t, ...names.map((n) => byName.get(n))], this.chartBox);
    this.chart.root.dataset.series = names.join(',');
  }

  // The animation time as a vertical line over the plot.
  cursor(u) {
    const x = u.valToPos(this.time, 'x', true);
    const ctx = u.ctx;
    ctx.save();
    ctx.strokeStyle = '#d9534f';
    ctx.lineWidth = 1.5 * (window.devicePixelRatio || 1);
    ctx.beginPath();
    ctx.moveTo(x, u.bbox.top);
    ctx.lineTo(x, u.bbox.top + u.bbox.height);
    ctx.stroke();
    ctx.restore();
  }

  setTime(t) {
    this.time = t;
    if (this.chart) this.chart.redraw(false, false);
  }
}
