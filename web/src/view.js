// The 3-D view: points, bodies, segments, trails, the skeleton of joint trees, driven hoops and
// the ground of the scene JSON (src/io/report_scene.cpp), posed at any time by interpolating
// between frames; the camera frames everything drawn over the whole run.
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { bracket, interpolate } from './timeline.js';
import { Skeleton } from './skeleton.js';
import { Rings } from './rings.js';
import { Fit } from './framing.js';
import { visualObject } from './visuals.js';

const PALETTE = ['#d9534f', '#2f7ed8', '#f0ad4e', '#5cb85c', '#8e44ad', '#16a085'];
const BODY_COLOR = '#e8a33d';

function v3(a) {
  return new THREE.Vector3(a[0], a[1], a[2]);
}

// A helix of `turns` turns along the segment a-b (a spring), as line positions.
function coil(a, b, radius, turns, out) {
  const axis = new THREE.Vector3().subVectors(b, a);
  const len = axis.length() || 1e-9;
  axis.divideScalar(len);
  const u = new THREE.Vector3(1, 0, 0);
  if (Math.abs(u.dot(axis)) > 0.9) u.set(0, 1, 0);
  u.cross(axis).normalize();
  const w = new THREE.Vector3().crossVectors(axis, u);
  const n = out.length / 3;
  for (let k = 0; k < n; ++k) {
    const s = k / (n - 1);
    const end = k < 2 || k > n - 3;
    const phi = 2 * Math.PI * turns * s;
    const r = end ? 0 : radius;
    out[3 * k] = a.x + axis.x * len * s + r * (u.x * Math.cos(phi) + w.x * Math.sin(phi));
    out[3 * k + 1] = a.y + axis.y * len * s + r * (u.y * Math.cos(phi) + w.y * Math.sin(phi));
    out[3 * k + 2] = a.z + axis.z * len * s + r * (u.z * Math.cos(phi) + w.z * Math.sin(phi));
  }
}

export class View {
  constructor(container, scene) {
    this.s = scene;
    const np = scene.points.length;
    this.stride = 3 * np;
    this.renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: false });
    this.renderer.setPixelRatio(window.devicePixelRatio || 1);
    container.appendChild(this.renderer.domElement);
    this.container = container;
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color('#f7f7f4');
    this.scene.add(new THREE.HemisphereLight('#ffffff', '#888877', 2.2));
    const sun = new THREE.DirectionalLight('#ffffff', 1.6);
    this.up = v3(scene.up).normalize();
    sun.position.copy(this.up).multiplyScalar(3).add(new THREE.Vector3(1, 1, 1));
    this.scene.add(sun);
    this.build();
    this.camera = new THREE.PerspectiveCamera(40, 1, scene.extent * 1e-3, scene.extent * 100);
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.resize();
    this.resetCamera();
    window.addEventListener('resize', () => this.resize());
    this.controls.addEventListener('change', () => this.render());
  }

  build() {
    const s = this.s;
    const e = s.extent;
    this.tmp = new Float64Array(Math.max(12, 3 * s.points.length));
    this.pointMeshes = [];
    const sphere = new THREE.SphereGeometry(1, 24, 16);
    const cube = new THREE.BoxGeometry(1.4, 1.4, 1.4);
    s.points.forEach((p) => {
      if (p.kind === 'unused') {
        this.pointMeshes.push(null);
        return;
      }
      const fixed = p.kind === 'anchor' || p.kind === 'fixed';
      const color = p.color ?? (p.kind === 'particle' ? PALETTE[p.group % PALETTE.length] : fixed ? '#444444' : '#888888');
      const mesh = new THREE.Mesh(fixed ? cube : sphere, new THREE.MeshStandardMaterial({ color, roughness: 0.5 }));
      mesh.scale.setScalar(p.radius);
      mesh.name = p.name;
      this.scene.add(mesh);
      this.pointMeshes.push(mesh);
    });
    this.bodyGroups = s.bodies.map((b) => {
      const group = new THREE.Group();
      group.matrixAutoUpdate = false;
      group.name = b.name;
      this.scene.add(group);
      if (b.visuals) {
        // A URDF link as its <visual> elements draw it, in the link frame the pose places; a mesh
        // the loaders cannot read leaves the link to the inertia drawing below.
        try {
          const objects = b.visuals.map(visualObject);
          for (const o of objects) group.add(o);
          return group;
        } catch (e) {
          console.warn(`link ${b.name}: its visual could not be drawn (${e.message}); drawn from its inertia`);
        }
      }
      let geometry;
      if (b.shape === 'sphere') geometry = new THREE.SphereGeometry(b.size[0], 32, 20);
      else if (b.shape === 'capsule') {
        geometry = new THREE.CapsuleGeometry(b.size[0], Math.max(b.size[2] - 2 * b.size[0], 0), 8, 24);
        geometry.rotateX(Math.PI / 2); // along the body's link direction (the shape's z)
      } else if (b.shape === 'cylinder') {
        geometry = new THREE.CylinderGeometry(b.size[0], b.size[0], b.size[2], 32);
        geometry.rotateX(Math.PI / 2); // three's cylinders run along y, the body's along z
      } else geometry = new THREE.BoxGeometry(b.size[0], b.size[1], b.size[2]);
      // Over a skeleton the links are see-through, so that the joints inside them show.
      const see = s.skeleton ? { transparent: true, opacity: 0.35, depthWrite: false } : {};
      const mesh = new THREE.Mesh(geometry, new THREE.MeshStandardMaterial({ color: b.color ?? BODY_COLOR, roughness: 0.6, ...see }));
      const a = b.axes;
      const basis = new THREE.Matrix4().set(a[0], a[1], a[2], 0, a[3], a[4], a[5], 0, a[6], a[7], a[8], 0, 0, 0, 0, 1);
      mesh.quaternion.setFromRotationMatrix(basis);
      mesh.position.set(b.center[0], b.center[1], b.center[2]);
      const edges = new THREE.LineSegments(new THREE.EdgesGeometry(geometry, 30), new THREE.LineBasicMaterial({ color: '#5a4a30' }));
      mesh.add(edges);
      group.add(mesh);
      return group;
    });
    const rod = new THREE.CylinderGeometry(1, 1, 1, 12);
    this.segments = s.segments.map((g) => {
      if (g.kind === 'link') {
        const mesh = new THREE.Mesh(rod, new THREE.MeshStandardMaterial({ color: '#555a60', roughness: 0.4 }));
        mesh.userData.radius = 0.005 * e;
        this.scene.add(mesh);
        return { g, mesh };
      }
      const n = g.kind === 'spring' ? 160 : 2;
      const geometry = new THREE.BufferGeometry();
      geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(3 * n), 3));
      const material =
        g.kind === 'damper'
          ? new THREE.LineDashedMaterial({ color: '#7a4a9a', dashSize: 0.02 * e, gapSize: 0.01 * e })
          : new THREE.LineBasicMaterial({ color: g.kind === 'spring' ? '#2b7a4b' : '#999999' });
      const line = new THREE.Line(geometry, material);
      line.frustumCulled = false;
      this.scene.add(line);
      return { g, line, buf: new Float64Array(3 * n) };
    });
    // Trails: the whole path, drawn up to the current frame.
    const nf = s.t.length;
    this.trails = s.trail.map((i) => {
      const pos = new Float32Array(3 * nf);
      for (let f = 0; f < nf; ++f) for (let c = 0; c < 3; ++c) pos[3 * f + c] = s.positions[f * this.stride + 3 * i + c];
      const geometry = new THREE.BufferGeometry();
      geometry.setAttribute('position', new THREE.BufferAttribute(pos, 3));
      const color = s.points[i].color ?? PALETTE[s.points[i].group % PALETTE.length];
      const line = new THREE.Line(geometry, new THREE.LineBasicMaterial({ color, transparent: true, opacity: 0.7 }));
      line.frustumCulled = false;
      this.scene.add(line);
      return line;
    });
    if (s.skeleton) this.skeleton = new Skeleton(this.scene, s.skeleton, this.markerSize(), this.up);
    if (s.rings) this.rings = new Rings(this.scene, s.rings, 0.006 * e);
    this.addGround();
  }

  // The skeleton's markers scale with the tree itself at the first frame (a slider flung far
  // away must not fatten the joints), at most with the scene.
  markerSize() {
    const sk = this.s.skeleton;
    const box = new THREE.Box3();
    sk.nodes.forEach((n, k) => {
      if (n.kind !== 'rail') box.expandByPoint(new THREE.Vector3().fromArray(sk.positions, 3 * k));
    });
    const d = box.isEmpty() ? 0 : box.getSize(new THREE.Vector3()).length();
    return d > 1e-3 * this.s.extent ? Math.min(d, this.s.extent) : this.s.extent;
  }

  // Calls fn(x, y, z, r) with spheres that hold everything drawn over all frames: points with
  // their radius, the corners of bodies' shapes at their poses, the skeleton and the hoops.
  eachDrawn(fn) {
    const s = this.s;
    const p = new THREE.Vector3();
    const c = new THREE.Vector3();
    const nb = s.bodies.length;
    const rot = new THREE.Matrix4();
    const half = s.bodies.map((b) => (b.shape === 'box' ? b.size.map((x) => x / 2) : [b.size[0], b.size[1], b.shape === 'sphere' ? b.size[0] : b.size[2] / 2]));
    const axes = s.bodies.map((b) => new THREE.Matrix4().set(...b.axes.slice(0, 3), 0, ...b.axes.slice(3, 6), 0, ...b.axes.slice(6, 9), 0, 0, 0, 0, 1));
    for (let f = 0; f < s.t.length; ++f) {
      s.points.forEach((pt, i) => {
        const o = f * this.stride + 3 * i;
        if (pt.kind !== 'unused') fn(s.positions[o], s.positions[o + 1], s.positions[o + 2], pt.radius);
      });
      for (let j = 0; j < nb; ++j) {
        const r = s.poses;
        const o = (f * nb + j) * 12;
        rot.set(r[o + 3], r[o + 4], r[o + 5], r[o], r[o + 6], r[o + 7], r[o + 8], r[o + 1], r[o + 9], r[o + 10], r[o + 11], r[o + 2], 0, 0, 0, 1);
        c.fromArray(s.bodies[j].center);
        const h = half[j];
        for (let k = 0; k < 8; ++k) {
          p.set(k & 1 ? h[0] : -h[0], k & 2 ? h[1] : -h[1], k & 4 ? h[2] : -h[2]).applyMatrix4(axes[j]).add(c).applyMatrix4(rot);
          fn(p.x, p.y, p.z, 0);
        }
      }
      if (this.skeleton) this.skeleton.eachDrawn(f, fn);
      if (this.rings) this.rings.eachDrawn(f, fn);
    }
  }

  // The box around everything drawn over all frames.
  bounds() {
    const box = new THREE.Box3();
    this.eachDrawn((x, y, z, r) => {
      box.min.set(Math.min(box.min.x, x - r), Math.min(box.min.y, y - r), Math.min(box.min.z, z - r));
      box.max.set(Math.max(box.max.x, x + r), Math.max(box.max.y, y + r), Math.max(box.max.z, z + r));
    });
    if (box.isEmpty()) box.set(new THREE.Vector3(-1, -1, -1), new THREE.Vector3(1, 1, 1));
    return box;
  }

  // The ground: a grid square to gravity, just below everything drawn.
  addGround() {
    const s = this.s;
    const box = this.bounds();
    this.box = box;
    let low = Infinity;
    for (let k = 0; k < 8; ++k) {
      const c = new THREE.Vector3(k & 1 ? box.max.x : box.min.x, k & 2 ? box.max.y : box.min.y, k & 4 ? box.max.z : box.min.z);
      low = Math.min(low, c.dot(this.up));
    }
    const size = 2.5 * s.extent;
    const grid = new THREE.GridHelper(size, 20, '#b5b5aa', '#d9d9d0');
    grid.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), this.up);
    const center = box.getCenter(new THREE.Vector3());
    const along = center.dot(this.up);
    grid.position.copy(center).addScaledVector(this.up, low - 0.02 * s.extent - along);
    this.scene.add(grid);
  }

  resetCamera() {
    const s = this.s;
    const center = this.box.getCenter(new THREE.Vector3());
    let dir;
    if (s.normal) dir = v3(s.normal);
    else {
      // Three-quarter view: from a horizontal diagonal, a little above.
      const a = Math.abs(this.up.x) > 0.9 ? new THREE.Vector3(0, 1, 0) : new THREE.Vector3(1, 0, 0);
      const h1 = a.clone().addScaledVector(this.up, -a.dot(this.up)).normalize();
      const h2 = new THREE.Vector3().crossVectors(this.up, h1);
      dir = h1.multiplyScalar(0.8).addScaledVector(h2, -1.0).addScaledVector(this.up, 0.55).normalize();
    }
    this.camera.up.copy(this.up);
    const fit = new Fit(center, dir, this.up, this.camera.fov, this.camera.aspect);
    this.eachDrawn((x, y, z, r) => fit.add(x, y, z, r));
    const dist = fit.distance + 1e-9 * s.extent;
    this.camera.position.copy(center).addScaledVector(dir, dist);
    this.controls.target.copy(center);
    this.controls.update();
  }

  resize() {
    const w = this.container.clientWidth || 640;
    const h = this.container.clientHeight || 420;
    this.renderer.setSize(w, h);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.render();
  }

  pose(t) {
    const s = this.s;
    const { i, w } = bracket(s.t, t);
    const np = s.points.length;
    const p = interpolate(s.positions, this.stride, 0, 3 * np, i, w, this.tmp);
    for (let k = 0; k < np; ++k) if (this.pointMeshes[k]) this.pointMeshes[k].position.set(p[3 * k], p[3 * k + 1], p[3 * k + 2]);
    const nb = s.bodies.length;
    const m = new Float64Array(12);
    const qa = new THREE.Quaternion();
    const qb = new THREE.Quaternion();
    const rot = new THREE.Matrix4();
    for (let j = 0; j < nb; ++j) {
      interpolate(s.poses, 12 * nb, 12 * j, 3, i, w, m);
      const a = (i * nb + j) * 12;
      const b = (Math.min(i + 1, s.t.length - 1) * nb + j) * 12;
      const r = s.poses;
      rot.set(r[a + 3], r[a + 4], r[a + 5], 0, r[a + 6], r[a + 7], r[a + 8], 0, r[a + 9], r[a + 10], r[a + 11], 0, 0, 0, 0, 1);
      qa.setFromRotationMatrix(rot);
      rot.set(r[b + 3], r[b + 4], r[b + 5], 0, r[b + 6], r[b + 7], r[b + 8], 0, r[b + 9], r[b + 10], r[b + 11], 0, 0, 0, 0, 1);
      qb.setFromRotationMatrix(rot);
      qa.slerp(qb, w);
      this.bodyGroups[j].matrix.compose(new THREE.Vector3(m[0], m[1], m[2]), qa, new THREE.Vector3(1, 1, 1));
      this.bodyGroups[j].matrixWorldNeedsUpdate = true;
    }
    const a = new THREE.Vector3();
    const b = new THREE.Vector3();
    const yAxis = new THREE.Vector3(0, 1, 0);
    for (const seg of this.segments) {
      a.fromArray(p, 3 * seg.g.a);
      b.fromArray(p, 3 * seg.g.b);
      if (seg.mesh) {
        const d = new THREE.Vector3().subVectors(b, a);
        const len = d.length();
        seg.mesh.position.addVectors(a, b).multiplyScalar(0.5);
        seg.mesh.quaternion.setFromUnitVectors(yAxis, len > 0 ? d.divideScalar(len) : yAxis);
        seg.mesh.scale.set(seg.mesh.userData.radius, len, seg.mesh.userData.radius);
        continue;
      }
      if (seg.g.kind === 'spring') coil(a, b, 0.025 * s.extent, 12, seg.buf);
      else seg.buf.set([a.x, a.y, a.z, b.x, b.y, b.z]);
      seg.line.geometry.attributes.position.array.set(seg.buf);
      seg.line.geometry.attributes.position.needsUpdate = true;
      if (seg.g.kind === 'damper') seg.line.computeLineDistances();
    }
    if (this.skeleton) this.skeleton.pose(i, w);
    if (this.rings) this.rings.pose(i, w);
    for (const trail of this.trails) trail.geometry.setDrawRange(0, i + 1 + (w > 0 ? 1 : 0));
    this.render();
  }

  render() {
    this.renderer.render(this.scene, this.camera);
  }
}
