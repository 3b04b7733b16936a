// Unit tests of the report front-end's pure parts (node --test web/test/).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { advance, bracket, interpolate } from '../src/timeline.js';

test('bracket finds the frames around a time and the weight between them', () => {
  const t = [0, 0.5, 1, 2];
  assert.deepEqual(bracket(t, 0.75), { i: 1, w: 0.5 });
  assert.deepEqual(bracket(t, 1.5), { i: 2, w: 0.5 });
  assert.deepEqual(bracket(t, 0), { i: 0, w: 0 });
  assert.deepEqual(bracket(t, -3), { i: 0, w: 0 });
  assert.deepEqual(bracket(t, 9), { i: 2, w: 1 });
  assert.deepEqual(bracket([4], 9), { i: 0, w: 0 });
});

test('interpolate blends one block of two frames linearly', () => {
  // two frames of stride 4: [a0 a1 | b0 b1] at offset 2
  const flat = [9, 9, 0, 10, 9, 9, 2, 20];
  assert.deepEqual(interpolate(flat, 4, 2, 2, 0, 0.25, [0, 0]), [0.5, 12.5]);
  // the last frame interpolates with itself
  assert.deepEqual(interpolate(flat, 4, 2, 2, 1, 0.5, [0, 0]), [2, 20]);
});

test('advance plays in real time times the speed and wraps at the end', () => {
  assert.equal(advance(1, 0.5, 2, 0, 10), 2);
  assert.ok(Math.abs(advance(9.5, 1, 1, 0, 10) - 0.5) < 1e-12);
  assert.equal(advance(3, 1, 1, 5, 5), 5);
});
