// A URDF link's <visual> geometry (issue 36 item 13), as the C++ side embeds it in a body's
// `visuals`: boxes, cylinders (along z), spheres and STL, OBJ or COLLADA meshes (base64), each
// placed by its origin in the link frame and coloured by its URDF material.
import * as THREE from 'three';
import { STLLoader } from 'three/examples/jsm/loaders/STLLoader.js';
import { OBJLoader } from 'three/examples/jsm/loaders/OBJLoader.js';
import { ColladaLoader } from 'three/examples/jsm/loaders/ColladaLoader.js';

export const VISUAL_COLOR = '#b8bcc4';

export function decodeBase64(text) {
  const s = atob(text);
  const out = new Uint8Array(s.length);
  for (let i = 0; i < s.length; ++i) out[i] = s.charCodeAt(i);
  return out;
}

function material(v) {
  const see = v.opacity !== undefined && v.opacity < 1 ? { transparent: true, opacity: v.opacity } : {};
  return new THREE.MeshStandardMaterial({ color: v.color ?? VISUAL_COLOR, roughness: 0.55, metalness: 0.1, ...see });
}

function mesh(v) {
  const data = decodeBase64(v.data);
  if (v.format === 'stl') return new THREE.Mesh(new STLLoader().parse(data.buffer), material(v));
  const text = new TextDecoder().decode(data);
  let object;
  if (v.format === 'obj') object = new OBJLoader().parse(text);
  else {
    // A URDF mesh is in its link's axes whatever the file's up axis: the loader's turn to y-up
    // (and its console warning about it) is undone.
    const warn = console.warn;
    console.warn = () => {};
    try {
      object = new ColladaLoader().parse(text, '').scene;
    } finally {
      console.warn = warn;
    }
    object.rotation.set(0, 0, 0);
  }
  if (v.color !== undefined || v.format === 'obj')
    object.traverse((o) => {
      if (o.isMesh) o.material = material(v);
    });
  return object;
}

// The visual `v` as an object in link coordinates.
export function visualObject(v) {
  let object;
  if (v.type === 'box') object = new THREE.Mesh(new THREE.BoxGeometry(v.size[0], v.size[1], v.size[2]), material(v));
  else if (v.type === 'sphere') object = new THREE.Mesh(new THREE.SphereGeometry(v.radius, 32, 20), material(v));
  else if (v.type === 'cylinder') {
    const geometry = new THREE.CylinderGeometry(v.radius, v.radius, v.length, 32);
    geometry.rotateX(Math.PI / 2); // three's cylinders run along y, URDF's along z
    object = new THREE.Mesh(geometry, material(v));
  } else {
    object = new THREE.Group();
    object.scale.set(v.scale[0], v.scale[1], v.scale[2]);
    object.add(mesh(v));
  }
  const placed = new THREE.Group();
  const r = v.rotation;
  const o = v.origin;
  placed.matrix.set(r[0], r[1], r[2], o[0], r[3], r[4], r[5], o[1], r[6], r[7], r[8], o[2], 0, 0, 0, 1);
  placed.matrixAutoUpdate = false;
  placed.add(object);
  return placed;
}
