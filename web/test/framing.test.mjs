// Unit tests of the camera's framing (web/src/framing.js): the fitted distance puts every corner
// of the box inside the view, the farthest one on its edge.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { Fit, fitDistance } from '../src/framing.js';

// Normalised screen coordinates of p seen from `eye` looking at `target` (up, fov, aspect).
function project(p, eye, target, up, fovDeg, aspect) {
  const sub = (a, b) => ({ x: a.x - b.x, y: a.y - b.y, z: a.z - b.z });
  const dot = (a, b) => a.x * b.x + a.y * b.y + a.z * b.z;
  const cross = (a, b) => ({ x: a.y * b.z - a.z * b.y, y: a.z * b.x - a.x * b.z, z: a.x * b.y - a.y * b.x });
  const unit = (a) => {
    const n = Math.sqrt(dot(a, a));
    return { x: a.x / n, y: a.y / n, z: a.z / n };
  };
  const z = unit(sub(eye, target));
  const x = unit(cross(up, z));
  const y = cross(z, x);
  const d = sub(p, eye);
  const depth = -dot(d, z);
  const t = Math.tan((fovDeg * Math.PI) / 360);
  return [dot(d, x) / (depth * t * aspect), dot(d, y) / (depth * t)];
}

test('a unit cube seen along an axis with a 90° view needs the distance 1 from its centre', () => {
  const box = { min: { x: -0.5, y: -0.5, z: -0.5 }, max: { x: 0.5, y: 0.5, z: 0.5 } };
  const d = fitDistance(box, { x: 0, y: 0, z: 0 }, { x: 0, y: 0, z: 1 }, { x: 0, y: 1, z: 0 }, 90, 1, 0);
  assert.ok(Math.abs(d - 1) < 1e-15, `distance ${d}`);
});

test('every corner of a long, off-centre box is in view from a three-quarter direction, one on the edge', () => {
  const box = { min: { x: -3, y: 0.2, z: -0.1 }, max: { x: 40, y: 2.5, z: 1.7 } };
  const center = { x: 18.5, y: 1.35, z: 0.8 };
  const dir = { x: 0.8 / 1.4, y: -1 / 1.4, z: 0.55 / 1.4 };
  const up = { x: 0, y: 0, z: 1 };
  for (const aspect of [0.5, 1, 2.2]) {
    const d = fitDistance(box, center, dir, up, 40, aspect, 0);
    const n = Math.hypot(dir.x, dir.y, dir.z);
    const eye = { x: center.x + (d * dir.x) / n, y: center.y + (d * dir.y) / n, z: center.z + (d * dir.z) / n };
    let widest = 0;
    for (let k = 0; k < 8; ++k) {
      const c = { x: k & 1 ? box.max.x : box.min.x, y: k & 2 ? box.max.y : box.min.y, z: k & 4 ? box.max.z : box.min.z };
      const [sx, sy] = project(c, eye, center, up, 40, aspect);
      widest = Math.max(widest, Math.abs(sx), Math.abs(sy));
    }
    assert.ok(Math.abs(widest - 1) < 1e-12, `aspect ${aspect}: widest corner at ${widest}`);
  }
});

test('a sphere fitted alone touches the edge of the view (the side plane is tangent to it)', () => {
  // camera on +z looking at the origin, 90° square view: a sphere of radius r at (a, 0, 0)
  // touches the side plane x = depth when (a + r√2) = D (half-angle 45°, sec = √2).
  const fit = new Fit({ x: 0, y: 0, z: 0 }, { x: 0, y: 0, z: 1 }, { x: 0, y: 1, z: 0 }, 90, 1, 0);
  fit.add(2, 0, 0, 0.5);
  assert.ok(Math.abs(fit.distance - (2 + 0.5 * Math.SQRT2)) < 1e-12, `distance ${fit.distance}`);
  // the side plane x + z = D lies r from the centre (2, 0, 0): |2 - D| / √2 = r
  const D = fit.distance;
  assert.ok(Math.abs(Math.abs(2 - D) / Math.SQRT2 - 0.5) < 1e-12);
});
