// The LaTeX of `derive` splits into headed blocks (node --test web/test/).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { rows, splitLatex } from '../src/equations.js';

test('splitLatex keeps each align* block under its % heading', () => {
  const tex = [
    '% pendulum: 1 coordinates, 0 constraints',
    '% Energies',
    '\\begin{align*}',
    '  T &= \\frac{1}{2} m l^2 \\dot{\\theta}^2 \\\\',
    '  U &= -m g l \\cos\\theta \\\\',
    '\\end{align*}',
    '% Mass matrix M(q)',
    '\\begin{align*}',
    '  M_{11} &= m l^2 \\\\',
    '\\end{align*}',
    '% 1234 more characters of equations: lagrange derive --format latex',
  ].join('\n');
  const blocks = splitLatex(tex);
  assert.equal(blocks.length, 3);
  assert.equal(blocks[0].heading, 'Energies');
  assert.match(blocks[0].body, /T &= /);
  assert.match(blocks[0].body, /U &= /);
  assert.equal(blocks[1].heading, 'Mass matrix M(q)');
  assert.match(blocks[2].heading, /1234 more characters/);
  assert.equal(blocks[2].body, '');
});

test('splitLatex keeps a large model\'s verbatim block as text', () => {
  const tex = ['% big: large model, printed as plain text', '\\begin{verbatim}', 'Energies', '  e1 = x_dot^2', '% not a heading', '\\end{verbatim}'].join('\n');
  const blocks = splitLatex(tex);
  assert.equal(blocks.length, 1);
  assert.equal(blocks[0].verbatim, true);
  assert.equal(blocks[0].body, 'Energies\n  e1 = x_dot^2\n% not a heading');
  assert.match(blocks[0].heading, /large model/);
});

test('rows gives one equation per row of an align* body', () => {
  const body = ['  T &= \\frac{1}{2} m v^2 \\\\', '  U &= m g', '    h \\\\', '  L &= T - U'].join('\n');
  assert.deepEqual(rows(body), ['T = \\frac{1}{2} m v^2', 'U = m g h', 'L = T - U']);
});
