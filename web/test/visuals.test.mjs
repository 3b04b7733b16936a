// Unit tests of the URDF visuals (web/src/visuals.js): shapes, placement by origin and rpy
// matrix, colours, and meshes decoded from base64.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import * as THREE from 'three';
import { decodeBase64, visualObject, VISUAL_COLOR } from '../src/visuals.js';

const identity = [1, 0, 0, 0, 1, 0, 0, 0, 1];
const meshOf = (object) => {
  let mesh = null;
  object.updateMatrixWorld(true);
  object.traverse((o) => {
    if (o.isMesh) mesh = o;
  });
  return mesh;
};
const worldOf = (mesh, v) => new THREE.Vector3(...v).applyMatrix4(mesh.matrixWorld).toArray();
// geometry is float32
const close = (a, b) => a.forEach((x, k) => assert.ok(Math.abs(x - b[k]) < 1e-6, `${a} != ${b}`));

test('base64 decodes to the bytes it encodes', () => {
  assert.deepEqual(Array.from(decodeBase64('AAEC/w==')), [0, 1, 2, 255]);
  assert.deepEqual(new TextDecoder().decode(decodeBase64('bGFncmFuZ2U=')), 'lagrange');
});

test('a box is placed by its origin and rotation, in its URDF colour', () => {
  // rpy (0, 0, pi/2): x → y
  const object = visualObject({ type: 'box', size: [0.4, 0.2, 0.1], origin: [1, 2, 3], rotation: [0, -1, 0, 1, 0, 0, 0, 0, 1], color: '#ff0000', opacity: 0.5 });
  const mesh = meshOf(object);
  close(worldOf(mesh, [0.2, 0, 0]), [1, 2.2, 3]); // the box's +x face centre, turned onto +y
  mesh.geometry.computeBoundingBox();
  close(mesh.geometry.boundingBox.max.toArray(), [0.2, 0.1, 0.05]);
  assert.equal(mesh.material.color.getHexString(), 'ff0000');
  assert.ok(mesh.material.transparent && mesh.material.opacity === 0.5);
});

test('a cylinder runs along z, as in URDF; no colour gives the default', () => {
  const mesh = meshOf(visualObject({ type: 'cylinder', radius: 0.1, length: 2, origin: [0, 0, 0], rotation: identity }));
  mesh.geometry.computeBoundingBox();
  close(mesh.geometry.boundingBox.max.toArray(), [0.1, 0.1, 1]);
  assert.equal(`#${mesh.material.color.getHexString()}`, VISUAL_COLOR);
  assert.ok(!mesh.material.transparent);
});

test('an OBJ mesh is decoded, scaled and placed', () => {
  const obj = 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n';
  const data = Buffer.from(obj).toString('base64');
  const object = visualObject({ type: 'mesh', format: 'obj', data, scale: [2, 3, 4], origin: [0, 0, 1], rotation: identity });
  const mesh = meshOf(object);
  assert.equal(mesh.geometry.attributes.position.count, 3);
  close(worldOf(mesh, [1, 0, 0]), [2, 0, 1]);
  close(worldOf(mesh, [0, 1, 0]), [0, 3, 1]);
});
