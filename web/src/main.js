// The lagrange report page: reads the JSON the C++ side embedded (#lagrange-data) and builds the
// 3-D view with its playback controls, the plots, the equations, the parameters and the run
// statistics. `window.lagrangeReport` lets the browser tests drive and inspect it.
import 'uplot/dist/uPlot.min.css';
import './style.css';
import { View } from './view.js';
import { Plots } from './plots.js';
import { renderEquations } from './equations.js';
import { advance } from './timeline.js';

function el(tag, props = {}, ...children) {
  const e = Object.assign(document.createElement(tag), props);
  e.append(...children);
  return e;
}

function number(x) {
  if (typeof x !== 'number') return String(x ?? '');
  if (x === 0 || (Math.abs(x) >= 1e-3 && Math.abs(x) < 1e6)) return String(+x.toPrecision(6));
  return x.toExponential(2);
}

function table(rows) {
  return el('table', {}, ...rows.map(([k, v]) => el('tr', {}, el('th', {}, k), el('td', { className: 'num' }, number(v)))));
}

function statistics(s) {
  const rows = [['status', s.status]];
  if (s.message) rows.push(['reason', s.message]);
  if (s.integrator) rows.push(['integrator', s.integrator]);
  rows.push(['coordinates', s.coordinates], ['constraints', s.constraints]);
  if (s.t_end !== undefined) rows.push(['time span [s]', `${number(s.t_start)} .. ${number(s.t_end)}`]);
  rows.push(['output samples', s.samples], ['steps', s.steps], ['rhs evaluations', s.rhs_evaluations], ['failed steps', s.failed_steps]);
  if (s.wall_seconds !== undefined) rows.push(['simulation wall time [s]', s.wall_seconds]);
  if (s.derive_seconds !== undefined) rows.push(['derive, compile [s]', `${number(s.derive_seconds)}, ${number(s.compile_seconds)}`]);
  if (s.energy_start !== undefined) {
    rows.push(['energy start, end', `${number(s.energy_start)}, ${number(s.energy_end)}`]);
    rows.push(['relative energy drift', s.energy_drift]);
  }
  if (s.max_constraint_residual !== undefined) rows.push(['worst constraint residual', s.max_constraint_residual]);
  if (s.rotation_drift !== undefined) rows.push(['worst rotation drift', s.rotation_drift]);
  return table(rows);
}

function main() {
  const timings = { start: performance.now() };
  const data = JSON.parse(document.getElementById('lagrange-data').textContent);
  const app = document.getElementById('app');
  const scene = data.scene;
  const t0 = scene.t[0];
  const t1 = scene.t[scene.t.length - 1];

  const viewBox = el('div', { id: 'view' });
  const play = el('button', { id: 'play', textContent: 'Pause' });
  const speed = el('select', { id: 'speed' }, ...[0.1, 0.25, 0.5, 1, 2, 4].map((v) => el('option', { value: v, textContent: `${v}×`, selected: v === 1 })));
  const slider = el('input', { id: 'time', type: 'range', min: 0, max: 1000, value: 0, step: 1 });
  const label = el('span', { className: 'time' });
  const plotBox = el('div', { id: 'plots' });
  const eqBox = el('div', { id: 'equations' });
  const params = data.parameters.map((p) => [p.name, p.value]);
  app.append(
    el('header', {}, el('h1', {}, data.name), el('span', { className: 'file' }, data.file)),
    el(
      'main',
      {},
      viewBox,
      el('div', { className: 'controls' }, play, speed, slider, label),
      el('div', { className: 'hint', textContent: 'drag: orbit · right-drag: pan · wheel: zoom · space: play/pause' }),
      ...(scene.notes ?? []).map((n) => el('div', { className: 'hint note', textContent: n })),
      el('h2', {}, 'Plots'),
      plotBox,
      el('div', { className: 'columns' }, el('div', {}, el('h2', {}, 'Parameters'), table(params)), el('div', {}, el('h2', {}, 'Run'), statistics(data.stats))),
      el('h2', {}, 'Equations of motion'),
      eqBox,
    ),
  );
  if (data.stats.status !== 'complete') label.classList.add('failed');

  timings.parsed = performance.now();
  const view = new View(viewBox, scene);
  timings.view = performance.now();
  const plots = new Plots(plotBox, data.plots);
  timings.plots = performance.now();
  // The equations after the first frame: the motion shows first.
  const equations = { ready: false };
  const typesetEquations = () =>
    renderEquations(eqBox, data.latex, () => {
      timings.equations = performance.now();
      equations.ready = true;
    });

  let t = t0;
  let playing = true;
  let last = null;
  const show = () => {
    view.pose(t);
    plots.setTime(t);
    slider.value = String(Math.round((1000 * (t - t0)) / ((t1 - t0) || 1)));
    label.textContent = `t = ${t.toFixed(2)} / ${number(t1)} s`;
  };
  const setPlaying = (on) => {
    playing = on;
    play.textContent = on ? 'Pause' : 'Play';
    last = null;
  };
  play.addEventListener('click', () => setPlaying(!playing));
  document.addEventListener('keydown', (e) => {
    if (e.code === 'Space' && e.target === document.body) {
      e.preventDefault();
      setPlaying(!playing);
    }
  });
  slider.addEventListener('input', () => {
    t = t0 + ((t1 - t0) * Number(slider.value)) / 1000;
    setPlaying(false);
    show();
  });
  const frames = { count: 0 };
  const tick = (now) => {
    if (playing && last !== null) t = advance(t, (now - last) / 1000, Number(speed.value), t0, t1);
    last = now;
    if (playing || frames.count === 0) show();
    if (frames.count === 0) {
      timings.firstFrame = performance.now();
      setTimeout(typesetEquations, 0);
    }
    frames.count++;
    requestAnimationFrame(tick);
  };
  show();
  window.lagrangeReport = {
    timings,
    frames,
    equations,
    time: () => t,
    playing: () => playing,
    play: () => setPlaying(true),
    pause: () => setPlaying(false),
    seek: (x) => {
      t = Math.min(t1, Math.max(t0, x));
      show();
    },
    view,
    plots,
  };
  requestAnimationFrame(tick);
}

main();
