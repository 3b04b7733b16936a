// Browser test of URDF <visual> geometry in the report (issue 36 item 13; ctest
// `report_urdf_visuals`): simulate tests/io/urdf_visuals/visual_arm.urdf with --report, open it
// in headless Chromium and check that each link is drawn by its visuals (no inertia box), and
// that the STL mesh's vertices sit where the link's pose and the visual's origin, rotation and
// scale put them, at several frames of the motion; and the COLLADA plate on the fixed base where
// its origin puts it, in its own z-up axes. No console errors or warnings.
//
// Usage: node urdf_visuals.mjs LAGRANGE URDF OUT_DIR
import { launch, openReport } from '../chromium.mjs';
import { execFile } from 'node:child_process';
import { promisify } from 'node:util';
import { mkdirSync } from 'node:fs';
import { join } from 'node:path';
import assert from 'node:assert/strict';

const [lagrange, urdf, outDir] = process.argv.slice(2);
if (!lagrange || !urdf || !outDir) {
  console.error('usage: node urdf_visuals.mjs LAGRANGE URDF OUT_DIR');
  process.exit(2);
}
mkdirSync(outDir, { recursive: true });
const html = join(outDir, 'visual_arm.html');
await promisify(execFile)(lagrange, ['simulate', urdf, '--initial', 'shoulder=0.5', '--initial', 'elbow=-0.4', '--t-end', '3', '-o', join(outDir, 'visual_arm.csv'), '--report', html]);

// row-major 3×3 times a vector
const mul = (R, v) => [0, 1, 2].map((r) => R[3 * r] * v[0] + R[3 * r + 1] * v[1] + R[3 * r + 2] * v[2]);
const add = (a, b) => a.map((x, k) => x + b[k]);

const browser = await launch();
const messages = [];
let failures = 0;
try {
  const { page } = await openReport(browser, html, messages);
  const scene = await page.evaluate(() => JSON.parse(document.getElementById('lagrange-data').textContent).scene);
  const nb = scene.bodies.length;
  assert.deepEqual(scene.bodies.map((b) => b.name), ['base', 'upper', 'tool']);
  assert.equal(scene.notes, undefined, 'every mesh was found');
  // Each link is drawn by its visuals alone.
  const children = await page.evaluate(() => window.lagrangeReport.view.bodyGroups.map((g) => g.children.length));
  assert.deepEqual(children, scene.bodies.map((b) => b.visuals.length));
  const tool = scene.bodies.findIndex((b) => b.name === 'tool');
  const visual = scene.bodies[tool].visuals[0];
  assert.equal(visual.type, 'mesh');
  const nf = scene.t.length;
  const frames = [0, Math.floor(nf / 3), Math.floor((2 * nf) / 3), nf - 1];
  let moved = 0;
  let first = null;
  for (const f of frames) {
    await page.evaluate((t) => {
      window.lagrangeReport.pause();
      window.lagrangeReport.seek(t);
    }, scene.t[f]);
    // The STL's vertices in the world, as three.js drew them.
    const drawn = await page.evaluate((j) => {
      const group = window.lagrangeReport.view.bodyGroups[j];
      group.updateMatrixWorld(true);
      let mesh = null;
      group.traverse((o) => {
        if (o.isMesh) mesh = o;
      });
      const p = mesh.geometry.attributes.position;
      const out = [];
      for (let i = 0; i < p.count; ++i) {
        const v = { x: p.getX(i), y: p.getY(i), z: p.getZ(i) };
        const e = mesh.matrixWorld.elements; // column-major
        out.push([0, 1, 2].map((r) => e[r] * v.x + e[4 + r] * v.y + e[8 + r] * v.z + e[12 + r]));
      }
      return { local: Array.from(p.array), world: out, visible: mesh.visible };
    }, tool);
    assert.equal(drawn.world.length, 12, 'four triangles of the tetrahedron');
    assert.ok(drawn.visible);
    // Where the link's pose (the scene's, at this frame) puts them.
    const pose = scene.poses.slice((f * nb + tool) * 12, (f * nb + tool) * 12 + 12);
    const R = pose.slice(3, 12);
    for (let i = 0; i < drawn.world.length; ++i) {
      const v = drawn.local.slice(3 * i, 3 * i + 3).map((x, k) => x * visual.scale[k]);
      const expected = add(pose.slice(0, 3), mul(R, add(visual.origin, mul(visual.rotation, v))));
      for (let k = 0; k < 3; ++k) assert.ok(Math.abs(drawn.world[i][k] - expected[k]) < 2e-4, `frame ${f} vertex ${i}: drawn ${drawn.world[i]}, expected ${expected}`);
    }
    if (first === null) first = drawn.world[1];
    else moved = Math.max(moved, Math.hypot(...drawn.world[1].map((x, k) => x - first[k])));
  }
  assert.ok(moved > 0.05, `the mesh moves with its link (${moved})`);
  // The COLLADA plate: 4 corners (±0.1, ±0.1, 0) in the base frame, 0.05 below its origin.
  const base = scene.bodies.findIndex((b) => b.name === 'base');
  assert.equal(scene.bodies[base].visuals[1].format, 'dae');
  const corners = await page.evaluate((j) => {
    const group = window.lagrangeReport.view.bodyGroups[j];
    group.updateMatrixWorld(true);
    const meshes = [];
    group.traverse((o) => {
      if (o.isMesh) meshes.push(o);
    });
    const plate = meshes[meshes.length - 1];
    const p = plate.geometry.attributes.position;
    const out = [];
    for (let i = 0; i < p.count; ++i) {
      const e = plate.matrixWorld.elements;
      const v = [p.getX(i), p.getY(i), p.getZ(i)];
      out.push([0, 1, 2].map((r) => e[r] * v[0] + e[4 + r] * v[1] + e[8 + r] * v[2] + e[12 + r]));
    }
    return out;
  }, base);
  assert.equal(corners.length, 6, 'two triangles');
  for (const c of corners) {
    assert.ok(Math.abs(Math.abs(c[0]) - 0.1) < 1e-6 && Math.abs(Math.abs(c[1]) - 0.1) < 1e-6, `corner ${c}`);
    assert.ok(Math.abs(c[2] + 0.05) < 1e-6, `corner ${c} at z = -0.05`);
  }
  assert.deepEqual(messages, []);
  console.log(`urdf visuals: the mesh follows its link at ${frames.length} frames`);
} catch (e) {
  failures++;
  console.error(e.message);
  for (const m of messages) console.error(m);
} finally {
  await browser.close();
}
process.exit(failures ? 1 : 0);
