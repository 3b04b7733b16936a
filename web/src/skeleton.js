// The kinematic skeleton of a joint tree in the 3-D view (scene.skeleton, src/io/report_skeleton.cpp):
// bones from joint to joint, a cylinder along each revolute joint's axis, a rail along each
// prismatic joint over its travel with a collar where the link is, and a base plate at the world.
// Every position comes from the C++ side; this only draws them.
import * as THREE from 'three';
import { interpolate } from './timeline.js';

const BONE = '#3b4652';
const REVOLUTE = '#2f7ed8';
const PRISMATIC = '#8e44ad';
const Y = new THREE.Vector3(0, 1, 0);

// Places a unit cylinder (three's, along y) from a to b with radius r.
function span(mesh, a, b, r) {
  const d = new THREE.Vector3().subVectors(b, a);
  const len = d.length();
  mesh.position.addVectors(a, b).multiplyScalar(0.5);
  mesh.quaternion.setFromUnitVectors(Y, len > 0 ? d.divideScalar(len) : Y);
  mesh.scale.set(r, len, r);
}

export class Skeleton {
  /** `size`: the length the markers are scaled to; `up`: against gravity (the base plate's normal). */
  constructor(scene, sk, size, up) {
    this.sk = sk;
    this.nn = sk.nodes.length;
    this.na = sk.axes.length;
    this.size = size;
    this.up = up;
    this.p = new Float64Array(3 * this.nn);
    this.a = new Float64Array(3 * this.na);
    const rod = new THREE.CylinderGeometry(1, 1, 1, 16);
    const material = (color) => new THREE.MeshStandardMaterial({ color, roughness: 0.45 });
    const add = (mesh) => {
      scene.add(mesh);
      return mesh;
    };
    const bone = material(BONE);
    this.bones = sk.bones.map(([a, b]) => ({ a, b, mesh: add(new THREE.Mesh(rod, bone)), r: 0.012 * size }));
    const rail = material(PRISMATIC);
    this.rails = sk.rails.map(([a, b]) => ({ a, b, mesh: add(new THREE.Mesh(rod, rail)), r: 0.007 * size }));
    // Joint axes: a short cylinder on the axis (revolute) or a collar around the rail (prismatic),
    // with a thin line through it that shows the direction.
    this.axes = sk.axes.map((x) => {
      const prismatic = x.kind === 'prismatic';
      return {
        node: x.node,
        body: add(new THREE.Mesh(rod, material(prismatic ? PRISMATIC : REVOLUTE))),
        line: add(new THREE.Mesh(rod, material(BONE))),
        r: (prismatic ? 0.024 : 0.03) * size,
        half: (prismatic ? 0.03 : 0.045) * size,
        reach: 0.1 * size,
      };
    });
    const ball = new THREE.SphereGeometry(1, 16, 12);
    this.balls = [];
    sk.nodes.forEach((n, k) => {
      if (n.kind !== 'joint' && n.kind !== 'com' && n.kind !== 'anchor') return;
      const mesh = add(new THREE.Mesh(ball, material(n.kind === 'com' ? '#e8a33d' : BONE)));
      mesh.scale.setScalar((n.kind === 'com' ? 0.018 : 0.016) * size);
      this.balls.push({ node: k, mesh });
    });
    // The base: a plate square to `up` at the world's origin, under the root joints.
    const base = sk.nodes.findIndex((n) => n.kind === 'base');
    this.plate = new THREE.Mesh(new THREE.CylinderGeometry(0.12 * size, 0.12 * size, 0.02 * size, 40), material('#555555'));
    this.plate.quaternion.setFromUnitVectors(Y, up);
    this.base = base;
    add(this.plate);
  }

  /** Node k's position at the last pose. */
  node(k) {
    return new THREE.Vector3(this.p[3 * k], this.p[3 * k + 1], this.p[3 * k + 2]);
  }

  /** Poses the skeleton between frames i and i + 1 (weight w). */
  pose(i, w) {
    const sk = this.sk;
    interpolate(sk.positions, 3 * this.nn, 0, 3 * this.nn, i, w, this.p);
    interpolate(sk.directions, 3 * this.na, 0, 3 * this.na, i, w, this.a);
    for (const s of [...this.bones, ...this.rails]) span(s.mesh, this.node(s.a), this.node(s.b), s.r);
    this.axes.forEach((x, k) => {
      const c = this.node(x.node);
      const d = new THREE.Vector3(this.a[3 * k], this.a[3 * k + 1], this.a[3 * k + 2]).normalize();
      span(x.body, c.clone().addScaledVector(d, -x.half), c.clone().addScaledVector(d, x.half), x.r);
      span(x.line, c.clone().addScaledVector(d, -x.reach), c.clone().addScaledVector(d, x.reach), 0.004 * this.size);
    });
    for (const b of this.balls) b.mesh.position.copy(this.node(b.node));
    if (this.base >= 0) this.plate.position.copy(this.node(this.base)).addScaledVector(this.up, -0.01 * this.size);
  }

  /** Where the drawn bones and rails end, in world coordinates: [{a, b, from, to}] (for the tests). */
  drawn() {
    const ends = [];
    for (const s of [...this.bones, ...this.rails]) {
      s.mesh.updateMatrixWorld();
      const from = new THREE.Vector3(0, -0.5, 0).applyMatrix4(s.mesh.matrixWorld);
      const to = new THREE.Vector3(0, 0.5, 0).applyMatrix4(s.mesh.matrixWorld);
      ends.push({ a: s.a, b: s.b, rail: this.rails.includes(s), from: from.toArray(), to: to.toArray() });
    }
    return ends;
  }

  /** Calls fn(x, y, z, r) with spheres that hold everything drawn at frame f. */
  eachDrawn(f, fn) {
    const m = 0.12 * this.size; // the plate's radius and the axes' reach, the largest markers
    const p = this.sk.positions;
    for (let k = 3 * this.nn * f; k < 3 * this.nn * (f + 1); k += 3) fn(p[k], p[k + 1], p[k + 2], m);
  }
}
