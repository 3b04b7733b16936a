// Framing the camera (pure, tested in web/test/framing.test.mjs): how far from a box's centre a
// perspective camera looking back along `dir` must stand for the whole box to be in view.

const dot = (a, b) => a.x * b.x + a.y * b.y + a.z * b.z;
const cross = (a, b) => ({ x: a.y * b.z - a.z * b.y, y: a.z * b.x - a.x * b.z, z: a.x * b.y - a.y * b.x });
const unit = (a) => {
  const n = Math.sqrt(dot(a, a)) || 1;
  return { x: a.x / n, y: a.y / n, z: a.z / n };
};

/**
 * The distance D along the unit `dir` from `center` at which a camera with vertical field of
 * view `fovDeg`, `aspect` (width / height) and `up` sees every corner of `box` ({min, max}) with
 * a `margin` (fraction of the half-width) to spare. In the camera's axes (z = dir, x = up × z,
 * y = z × x) a corner c at depth D − c·z is in view when |c·x| ≤ tan(h/2)(D − c·z) and
 * |c·y| ≤ tan(v/2)(D − c·z).
 */
export function fitDistance(box, center, dir, up, fovDeg, aspect, margin = 0.06) {
  const z = unit(dir);
  let side = cross(up, z);
  if (dot(side, side) < 1e-12) side = cross(Math.abs(z.x) < 0.9 ? { x: 1, y: 0, z: 0 } : { x: 0, y: 1, z: 0 }, z);
  const x = unit(side);
  const y = cross(z, x);
  const tanV = Math.tan((fovDeg * Math.PI) / 360) * (1 - margin);
  const tanH = Math.tan((fovDeg * Math.PI) / 360) * aspect * (1 - margin);
  let d = 0;
  for (let k = 0; k < 8; ++k) {
    const c = {
      x: (k & 1 ? box.max.x : box.min.x) - center.x,
      y: (k & 2 ? box.max.y : box.min.y) - center.y,
      z: (k & 4 ? box.max.z : box.min.z) - center.z,
    };
    const depth = dot(c, z);
    d = Math.max(d, depth + Math.abs(dot(c, x)) / tanH, depth + Math.abs(dot(c, y)) / tanV);
  }
  return d;
}
