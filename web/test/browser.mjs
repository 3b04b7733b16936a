// Browser test of the HTML report (ctest `report_browser`): for every example, simulate with
// --report, open the report in headless Chromium (playwright-core driving the system's
// /usr/bin/chromium) and check what a user sees: a first frame with a non-blank 3-D canvas,
// play advancing the slider, bodies moving between two screenshots, plots with the expected
// series, equations rendered by KaTeX without error nodes, and no console errors or warnings.
// Then a large generated run (200 moving points over 60 s): its size must stay under the bound of
// docs/model-language.md; its opening time is measured and printed, not asserted. Robot arms (the
// UR5 of examples/robots and a spatial R-R-P arm with a prismatic joint) are generated too, and
// every report with a skeleton is checked for connected links, with a hoop for the point on it,
// and every report for a camera that frames it all. Two reports are checked at a time.
//
// Usage: node browser.mjs LAGRANGE EXAMPLES_DIR OUT_DIR [NAME_FILTER]
// Prints "N passed, N failed" and exits non-zero when a check fails.
import { launch, openReport } from '../chromium.mjs';
import { execFile } from 'node:child_process';
import { promisify } from 'node:util';
import { mkdirSync, readdirSync, readFileSync, rmSync, statSync, writeFileSync } from 'node:fs';
import { basename, join, resolve } from 'node:path';

const [lagrange, examplesDir, outDir, filter = ''] = process.argv.slice(2);
if (!lagrange || !examplesDir || !outDir) {
  console.error('usage: node browser.mjs LAGRANGE EXAMPLES_DIR OUT_DIR [NAME_FILTER]');
  process.exit(2);
}
export const SIZE_BOUND = 12 * 1024 * 1024; // bytes; docs/model-language.md, "The report"
mkdirSync(outDir, { recursive: true });
const run = promisify(execFile);

function examples() {
  return readdirSync(examplesDir)
    .filter((f) => f.endsWith('.yaml') && f.includes(filter))
    .sort()
    .map((f) => join(examplesDir, f));
}

// Luminance variance and pixels of a screenshot of the 3-D view, decoded in a page of its own
// (reading the WebGL canvas back in the report itself would make Chromium warn about a stall).
let decoder = null;
async function viewPixels(page, path) {
  const png = await page.locator('#view canvas').screenshot(path ? { path } : {});
  return decoder.evaluate(async (b64) => {
    const img = new Image();
    img.src = `data:image/png;base64,${b64}`;
    await img.decode();
    const c = document.createElement('canvas');
    c.width = 160;
    c.height = 100;
    const ctx = c.getContext('2d');
    ctx.drawImage(img, 0, 0, c.width, c.height);
    const d = ctx.getImageData(0, 0, c.width, c.height).data;
    let sum = 0;
    let sum2 = 0;
    const lum = [];
    for (let i = 0; i < d.length; i += 4) {
      const y = 0.299 * d[i] + 0.587 * d[i + 1] + 0.114 * d[i + 2];
      lum.push(Math.round(y));
      sum += y;
      sum2 += y * y;
    }
    const n = lum.length;
    return { variance: sum2 / n - (sum / n) ** 2, lum };
  }, png.toString('base64'));
}

function differing(a, b) {
  let n = 0;
  for (let i = 0; i < a.length; ++i) if (Math.abs(a[i] - b[i]) > 24) ++n;
  return n;
}

async function checkReport(browser, html, csvHeader) {
  const messages = [];
  const failures = [];
  const expect = (ok, what) => ok || failures.push(what);
  const { page, seconds } = await openReport(browser, html, messages);
  // Only what the checks read: the whole run's data is megabytes to copy out of the page.
  const data = await page.evaluate(() => {
    const d = JSON.parse(document.getElementById('lagrange-data').textContent);
    const { t, skeleton, rings } = d.scene;
    return {
      scene: { t: [t[0], t[t.length - 1]], skeleton: !!skeleton, rings: !!rings },
      plots: { series: d.plots.series.map(({ name, group }) => ({ name, group })) },
      latex: d.latex,
    };
  });
  const t0 = data.scene.t[0];
  const t1 = data.scene.t[data.scene.t.length - 1];

  // The first frame, then the canvas is not blank.
  await page.evaluate((t) => { window.lagrangeReport.pause(); window.lagrangeReport.seek(t); }, t0);
  const shot = join(outDir, `${basename(html, '.html')}.png`);
  const first = await viewPixels(page, shot);
  expect(first.variance > 20, `3-D canvas looks blank (luminance variance ${first.variance.toFixed(1)})`);

  // Play advances the slider and the time.
  const before = await page.evaluate(() => [Number(document.getElementById('time').value), window.lagrangeReport.time()]);
  await page.click('#play');
  // until both have moved (at most 5 s; the expectations below say what did not)
  await page.waitForFunction(([slider, time]) => Number(document.getElementById('time').value) > slider && window.lagrangeReport.time() > time, before, { timeout: 5000 }).catch(() => {});
  const after = await page.evaluate(() => [Number(document.getElementById('time').value), window.lagrangeReport.time(), window.lagrangeReport.playing()]);
  expect(after[2] === true, 'the play button did not start playback');
  expect(after[1] > before[1] && after[0] > before[0], `play did not advance the slider (${before} -> ${after})`);
  await page.click('#play');

  // Bodies move: two screenshots at different times differ.
  let moved = 0;
  for (const f of [0.5, 0.25, 0.75, 1]) {
    await page.evaluate((t) => window.lagrangeReport.seek(t), t0 + f * (t1 - t0));
    const later = await viewPixels(page);
    moved = Math.max(moved, differing(first.lum, later.lum));
    if (moved > 10) break;
  }
  expect(moved > 10, `nothing moved between two screenshots (${moved} pixels differ)`);

  if (data.scene.skeleton) for (const problem of await checkSkeleton(page)) failures.push(problem);
  if (data.scene.rings) for (const problem of await checkRings(page)) failures.push(problem);
  for (const problem of await checkFraming(page)) failures.push(problem);

  // Plots: one chart with the first coordinates; every CSV column is offered somewhere.
  const plot = await page.evaluate(() => {
    const chart = document.querySelector('#plots .uplot');
    const labels = [...document.querySelectorAll('#plots .u-legend .u-series .u-label')].map((e) => e.textContent);
    const groups = [...document.querySelectorAll('#plot-group option')].map((o) => o.value);
    return { chart: !!chart, series: chart ? chart.dataset.series : '', labels, groups };
  });
  const coordinates = data.plots.series.filter((s) => s.group === 'coordinates').map((s) => s.name);
  const expected = coordinates.slice(0, 8);
  expect(plot.chart, 'no plot drawn');
  expect(plot.series === expected.join(','), `plot shows [${plot.series}], expected [${expected}]`);
  expect(expected.every((n) => plot.labels.includes(n)), `plot legend [${plot.labels}] lacks [${expected}]`);
  const offered = new Set(data.plots.series.map((s) => s.name));
  const missing = csvHeader.slice(1).filter((c) => !offered.has(c));
  expect(missing.length === 0, `CSV columns not offered as plots: ${missing.join(', ')}`);
  expect(plot.groups.includes('energy'), `no energy plot group (${plot.groups})`);

  // Equations rendered by KaTeX without error nodes.
  await page.waitForFunction(() => window.lagrangeReport.equations.ready, null, { timeout: 60000 });
  const tex = await page.evaluate(() => ({
    math: document.querySelectorAll('#equations .katex math').length,
    verbatim: document.querySelectorAll('#equations pre.verbatim').length,
    errors: [...document.querySelectorAll('#equations .katex-error')].map((e) => e.title || e.textContent).slice(0, 3),
    // sections too long to typeset at once are offered closed, typeset when opened
    closed: [...document.querySelectorAll('#equations details')].filter((d) => !d.open && d.querySelector('div')).length,
  }));
  // A large model's equations are text through named common subexpressions, as `derive` prints.
  if (data.latex.includes('\\begin{verbatim}')) expect(tex.verbatim > 0, 'no equations shown');
  else expect(tex.math > 0 || tex.closed > 0, 'no equations rendered or offered');
  expect(tex.errors.length === 0, `KaTeX error nodes: ${tex.errors.join(' | ')}`);

  expect(messages.length === 0, messages.slice(0, 5).join('\n'));
  await page.close();
  return { failures, seconds, shot };
}

// A joint tree drawn connected, at frames and between them: every bone starts where its parent's
// bone ends (1e-9 in world coordinates, as drawn by the meshes), every bone ends at its node's
// position of the scene, each prismatic joint's point lies on its rail (to the scene's rounding),
// and each link's body sits at its joint.
async function checkSkeleton(page) {
  return page.evaluate(() => {
    const r = window.lagrangeReport;
    const view = r.view;
    const sk = view.s.skeleton;
    const t = view.s.t;
    const problems = [];
    const near = (a, b, tol) => Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]) <= tol;
    const tol = 1e-9 * Math.max(1, view.s.extent);
    // the scene's numbers are rounded to 5 significant digits of the extent
    const rounding = 2e-4 * view.s.extent;
    const times = [0, 0.13, 0.5, 0.77, 1].map((f) => t[0] + f * (t[t.length - 1] - t[0]));
    times.push(t[Math.floor(t.length / 3)]);
    const joints = new Set(sk.axes.map((a) => a.node));
    for (const time of times) {
      r.seek(time);
      const drawn = view.skeleton.drawn();
      const node = (k) => [0, 1, 2].map((c) => view.skeleton.p[3 * k + c]);
      for (const b of drawn) {
        if (!near(b.to, node(b.b), tol) || !near(b.from, node(b.a), tol)) problems.push(`t = ${time}: bone ${b.a}-${b.b} is not drawn between its nodes`);
        if (b.rail) continue;
        const parent = drawn.find((p) => !p.rail && p.b === b.a);
        // the base is fixed to the world; a prismatic joint rides on its rail (checked below)
        const base = sk.nodes[b.a].kind === 'base';
        const onRail = sk.axes.some((a) => a.node === b.a && a.kind === 'prismatic');
        if (!base && !onRail && !parent) problems.push(`t = ${time}: bone ${b.a}-${b.b} hangs from no bone`);
        if (parent && !near(parent.to, b.from, tol)) problems.push(`t = ${time}: bone ${b.a}-${b.b} starts ${b.from} away from its parent's end ${parent.to}`);
      }
      // prismatic joints: the joint's point on the rail of the same link
      sk.axes.filter((a) => a.kind === 'prismatic').forEach((a) => {
        const rail = drawn.find((b) => b.rail && sk.nodes[b.a].name === sk.nodes[a.node].name);
        if (!rail) return problems.push(`joint ${a.name} has no rail`);
        const p = node(a.node);
        const d = [0, 1, 2].map((c) => rail.to[c] - rail.from[c]);
        const len = Math.hypot(...d);
        const s = [0, 1, 2].reduce((acc, c) => acc + (p[c] - rail.from[c]) * d[c], 0) / (len * len);
        const foot = [0, 1, 2].map((c) => rail.from[c] + s * d[c]);
        if (!(s >= -1e-6 && s <= 1 + 1e-6) || !near(foot, p, rounding)) problems.push(`t = ${time}: joint ${a.name} at ${p} is off its rail`);
      });
      if (!joints.size) problems.push('no joint axes drawn');
      // each body's frame at its link's joint node
      view.s.bodies.forEach((b, j) => {
        const k = sk.nodes.findIndex((n) => n.kind === 'joint' && n.name === b.name);
        if (k < 0) return;
        const m = view.bodyGroups[j].matrix.elements;
        if (!near([m[12], m[13], m[14]], node(k), tol)) problems.push(`t = ${time}: link ${b.name} drawn away from its joint`);
      });
    }
    return problems;
  });
}

// A driven point rides on its drawn hoop at every frame: within the sag of the hoop's chords
// (and the scene's rounding) of the polygon the rods draw.
async function checkRings(page) {
  return page.evaluate(() => {
    const r = window.lagrangeReport;
    const view = r.view;
    const rings = view.rings;
    const t = view.s.t;
    const problems = [];
    const n = rings.n;
    for (let f = 0; f < t.length; f += Math.max(1, Math.floor(t.length / 10))) {
      r.seek(t[f]);
      view.s.rings.points.forEach((point, ring) => {
        const p = view.pointMeshes[point].position;
        let best = Infinity;
        let size = 0;
        for (let k = 0; k < n; ++k) {
          const mesh = rings.rods[ring * n + k];
          mesh.updateMatrixWorld();
          const a = p.clone().set(0, -0.5, 0).applyMatrix4(mesh.matrixWorld);
          const b = p.clone().set(0, 0.5, 0).applyMatrix4(mesh.matrixWorld);
          const d = b.clone().sub(a);
          const s = Math.min(1, Math.max(0, p.clone().sub(a).dot(d) / d.lengthSq()));
          best = Math.min(best, a.addScaledVector(d, s).distanceTo(p));
          size = Math.max(size, d.length());
        }
        // a chord of length c on a circle sags c^2 / (8 R), R ~ n c / (2 pi)
        const sag = (size * Math.PI) / (4 * n);
        if (best > sag + 2e-4 * view.s.extent) problems.push(`t = ${t[f]}: point ${point} is ${best} off its hoop`);
      });
    }
    return problems;
  });
}

// The camera as reset frames the whole run: every vertex of every mesh drawn (points, bodies,
// skeleton), at every frame, projects inside the view.
async function checkFraming(page) {
  return page.evaluate(() => {
    const r = window.lagrangeReport;
    const view = r.view;
    view.resetCamera();
    const camera = view.camera;
    camera.updateMatrixWorld();
    const t = view.s.t;
    const step = Math.max(1, Math.floor(t.length / 12));
    let worst = 0;
    let where = '';
    for (let f = 0; f < t.length; f += step) {
      r.seek(t[f]);
      view.scene.updateMatrixWorld(true);
      view.scene.traverse((o) => {
        if (!o.isMesh || !o.visible) return;
        const pos = o.geometry.attributes.position;
        const v = o.position.clone();
        for (let k = 0; k < pos.count; ++k) {
          v.fromBufferAttribute(pos, k).applyMatrix4(o.matrixWorld).project(camera);
          const off = Math.max(Math.abs(v.x), Math.abs(v.y));
          if (off > worst) {
            worst = off;
            where = `${o.name || o.type} at t = ${t[f]}`;
          }
        }
      });
    }
    return worst <= 1 ? [] : [`the camera misses part of the run: ${where} at ${worst.toFixed(3)} of the half-width`];
  });
}

// Robot arms for the skeleton's checks: the UR5 of examples/robots from a bent pose, and the
// spatial R-R-P arm of issue 20 (revolute about z, revolute about y, a prismatic slider).
function armModels() {
  const ur5 = join(outDir, 'arm_ur5.yaml');
  writeFileSync(ur5, [
    'name: ur5 arm',
    `urdf: {file: ${resolve(examplesDir, 'robots', 'ur5.urdf')}, initial: {shoulder_lift_joint: -1.2, elbow_joint: 1.0, wrist_1_joint: -0.5}, rate: {shoulder_pan_joint: 0.8}}`,
    'gravity: [0, 0, -9.81]',
    'simulate: {t_end: 1.5, output_step: 0.01}',
  ].join('\n') + '\n');
  const rrp = join(outDir, 'arm_rrp.yaml');
  writeFileSync(rrp, [
    'name: rrp arm',
    'parameters: {g: 9.81, m1: 3.0, m2: 2.0, m3: 1.2, h1: 0.4, h2: 0.3, L2: 0.5, c2: 0.25, e3: 0.05}',
    'links:',
    '  base:   {joint: {name: q1, type: revolute, axis: [0, 0, 1], origin: {xyz: [0, 0, h1]}, initial: 0.2, rate: 0.5},',
    '           mass: m1, com: [0, 0, 0.1], inertia: [0.03, 0.03, 0.02]}',
    '  upper:  {parent: base, joint: {name: q2, type: revolute, axis: [0, 1, 0], origin: {xyz: [0, 0, h2]}, initial: -0.4, rate: 0.1},',
    '           mass: m2, com: [c2, 0, 0], inertia: [0.004, 0.045, 0.046]}',
    '  slider: {parent: upper, joint: {name: d3, type: prismatic, axis: [1, 0, 0], origin: {xyz: [L2, e3, 0]}, initial: 0.1, rate: -0.2},',
    '           mass: m3, com: [0.1, 0, 0.02], inertia: [[0.002, 0.0003, 0.0001], [0.0003, 0.011, 0.0002], [0.0001, 0.0002, 0.012]]}',
    'gravity: [0, 0, -g]',
    'simulate: {t_end: 0.6, output_step: 0.005}',
  ].join('\n') + '\n');
  return [ur5, rrp];
}

// A large run: 20 pendulums with 10 points along each rod, 200 moving points, 60 s.
function largeModel() {
  const n = 20;
  const lines = ['name: two hundred points', 'parameters: {g: 9.81, m: 1.0, l: 1.0}', 'coordinates:'];
  for (let k = 0; k < n; ++k) lines.push(`  th${k}: {initial: ${(0.3 + 0.05 * k).toFixed(2)}, rate: 0.0}`);
  lines.push('points:');
  for (let k = 0; k < n; ++k)
    for (let j = 1; j <= 10; ++j) lines.push(`  p${k}_${j}: [${k * 0.3} + ${j / 10}*l*sin(th${k}), -${j / 10}*l*cos(th${k}), ${(k * 0.2).toFixed(1)}]`);
  lines.push('particles:');
  for (let k = 0; k < n; ++k) lines.push(`  p${k}_10: m`);
  lines.push('gravity: [0, -g, 0]', 'simulate: {t_end: 60, output_step: 0.01}');
  const file = join(outDir, 'two_hundred_points.yaml');
  writeFileSync(file, lines.join('\n') + '\n');
  return file;
}

// Simulates a model, checks its report and prints what it found (at once, so that the lines of
// two models checked side by side do not interleave); true when it passed.
async function checkModel(browser, model) {
  const name = basename(model, '.yaml');
  const html = resolve(join(outDir, `${name}.html`));
  const csv = join(outDir, `${name}.csv`);
  const lines = [];
  let result;
  try {
    const started = Date.now();
    await run(resolve(lagrange), ['simulate', model, '-q', '-o', csv, '--report', html]);
    const simulated = (Date.now() - started) / 1000;
    const header = readFileSync(csv, 'utf8').split('\n', 1)[0].split(',');
    result = await checkReport(browser, html, header);
    const size = statSync(html).size;
    if (name === 'two_hundred_points') {
      if (size > SIZE_BOUND) result.failures.push(`report of ${size} bytes exceeds the bound of ${SIZE_BOUND}`);
      lines.push(`large run: 200 moving points over 60 s: report ${(size / 1048576).toFixed(2)} MB (bound ${SIZE_BOUND / 1048576} MB), opened in ${result.seconds.toFixed(2)} s, simulated and written in ${simulated.toFixed(2)} s`);
    }
    rmSync(csv, { force: true });
    rmSync(`${csv}.json`, { force: true });
    lines.push(`${result.failures.length ? 'FAIL' : 'ok  '} ${name}: ${(size / 1024).toFixed(0)} kB, first frame after ${result.seconds.toFixed(2)} s`);
  } catch (e) {
    result = { failures: [String(e.stderr ?? '') + String(e.message ?? e)] };
    lines.push(`FAIL ${name}`);
  }
  for (const f of result.failures) lines.push(`    ${f}`);
  console.log(lines.join('\n'));
  return result.failures.length === 0;
}

const browser = await launch();
decoder = await browser.newPage();
let passed = 0;
let failed = 0;
try {
  const queue = examples();
  for (const arm of armModels()) if (basename(arm).includes(filter)) queue.push(arm);
  // Two reports at a time (much of a check is waiting for the page); the large run alone after
  // them, so that its opening time is its own.
  const worker = async () => {
    while (queue.length) (await checkModel(browser, queue.shift())) ? ++passed : ++failed;
  };
  await Promise.all([worker(), worker()]);
  if (!filter || 'two_hundred_points'.includes(filter)) (await checkModel(browser, largeModel())) ? ++passed : ++failed;
} finally {
  await browser.close();
}
console.log(`${passed} passed, ${failed} failed`);
process.exit(failed ? 1 : 0);
