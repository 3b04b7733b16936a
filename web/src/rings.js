// Driven hoops in the 3-D view (scene.rings, src/io/report_driven.cpp): the closed curve a
// driven point rides on, sampled by the C++ side at every frame, drawn as a ring of rods that
// turns with its drive.
import * as THREE from 'three';
import { interpolate } from './timeline.js';

const Y = new THREE.Vector3(0, 1, 0);

export class Rings {
  constructor(scene, rings, radius) {
    this.r = rings;
    this.n = rings.samples;
    this.stride = 3 * this.n * rings.points.length;
    this.p = new Float64Array(this.stride);
    this.radius = radius;
    const rod = new THREE.CylinderGeometry(1, 1, 1, 8);
    const material = new THREE.MeshStandardMaterial({ color: '#6c7a89', roughness: 0.4, metalness: 0.2 });
    this.rods = [];
    for (let k = 0; k < this.stride / 3; ++k) {
      const mesh = new THREE.Mesh(rod, material);
      scene.add(mesh);
      this.rods.push(mesh);
    }
  }

  /** Poses the rings between frames i and i + 1 (weight w). */
  pose(i, w) {
    interpolate(this.r.positions, this.stride, 0, this.stride, i, w, this.p);
    const a = new THREE.Vector3();
    const b = new THREE.Vector3();
    const n = this.n;
    this.rods.forEach((mesh, k) => {
      const ring = Math.floor(k / n);
      const next = ring * n + ((k + 1) % n);
      a.fromArray(this.p, 3 * k);
      b.fromArray(this.p, 3 * next);
      const d = new THREE.Vector3().subVectors(b, a);
      const len = d.length();
      mesh.position.addVectors(a, b).multiplyScalar(0.5);
      mesh.quaternion.setFromUnitVectors(Y, len > 0 ? d.divideScalar(len) : Y);
      mesh.scale.set(this.radius, len, this.radius);
    });
  }

  /** Calls fn(x, y, z, r) with spheres that hold the rings drawn at frame f. */
  eachDrawn(f, fn) {
    const p = this.r.positions;
    for (let k = f * this.stride; k < (f + 1) * this.stride; k += 3) fn(p[k], p[k + 1], p[k + 2], this.radius);
  }
}
