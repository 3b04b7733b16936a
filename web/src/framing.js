// Framing the camera (pure, tested in web/test/framing.test.mjs): how far from a centre a
// perspective camera looking back along `dir` must stand for every drawn sphere to be in view.

const dot = (a, b) => a.x * b.x + a.y * b.y + a.z * b.z;
const cross = (a, b) => ({ x: a.y * b.z - a.z * b.y, y: a.z * b.x - a.x * b.z, z: a.x * b.y - a.y * b.x });
const unit = (a) => {
  const n = Math.sqrt(dot(a, a)) || 1;
  return { x: a.x / n, y: a.y / n, z: a.z / n };
};

/**
 * The distance D along the unit `dir` from `center` at which a camera with vertical field of
 * view `fovDeg`, `aspect` (width / height) and `up` sees every sphere added. In the camera's
 * axes (z = dir, x = up × z, y = z × x) a sphere at c (from the centre) of radius r, at depth
 * D − c·z, is inside the side planes of half-angle a when |c·x| cos a + r ≤ (D − c·z) sin a,
 * i.e. D ≥ c·z + (|c·x| + r / cos a) / tan a, and likewise for y with the vertical half-angle.
 * `margin` shrinks the angles' tangents (a fraction of the half-width left free).
 */
export class Fit {
  constructor(center, dir, up, fovDeg, aspect, margin = 0.06) {
    this.c = center;
    this.z = unit(dir);
    let side = cross(up, this.z);
    if (dot(side, side) < 1e-12) side = cross(Math.abs(this.z.x) < 0.9 ? { x: 1, y: 0, z: 0 } : { x: 0, y: 1, z: 0 }, this.z);
    this.x = unit(side);
    this.y = cross(this.z, this.x);
    const t = Math.tan((fovDeg * Math.PI) / 360);
    this.tanV = t * (1 - margin);
    this.tanH = t * aspect * (1 - margin);
    this.secV = Math.sqrt(1 + this.tanV * this.tanV);
    this.secH = Math.sqrt(1 + this.tanH * this.tanH);
    this.distance = 0;
  }

  /** Takes in the sphere at (px, py, pz) of radius r (0: a point). */
  add(px, py, pz, r = 0) {
    const c = { x: px - this.c.x, y: py - this.c.y, z: pz - this.c.z };
    const depth = dot(c, this.z);
    const h = depth + (Math.abs(dot(c, this.x)) + r * this.secH) / this.tanH;
    const v = depth + (Math.abs(dot(c, this.y)) + r * this.secV) / this.tanV;
    if (h > this.distance || v > this.distance) this.distance = Math.max(h, v);
  }
}

/** The distance of Fit for the eight corners of `box` ({min, max}). */
export function fitDistance(box, center, dir, up, fovDeg, aspect, margin = 0.06) {
  const fit = new Fit(center, dir, up, fovDeg, aspect, margin);
  for (let k = 0; k < 8; ++k) fit.add(k & 1 ? box.max.x : box.min.x, k & 2 ? box.max.y : box.min.y, k & 4 ? box.max.z : box.min.z);
  return fit.distance;
}
