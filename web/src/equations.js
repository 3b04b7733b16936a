// The LaTeX of `lagrange derive --format latex` split into headed blocks and rendered by KaTeX.
import katex from 'katex';

/** [{heading, body, verbatim}] from `% heading` lines and align* blocks; a large model's
 * `verbatim` block (its equations through named common subexpressions) is kept as text (pure,
 * tested). */
export function splitLatex(tex) {
  const blocks = [];
  let heading = '';
  let body = null;
  let verbatim = false;
  for (const line of tex.split('\n')) {
    if (body === null && line.startsWith('%')) {
      heading = line.replace(/^%\s*/, '');
      if (/more characters of equations/.test(heading)) blocks.push({ heading, body: '', verbatim: false });
    } else if (body === null && (line.startsWith('\\begin{align*}') || line.startsWith('\\begin{verbatim}'))) {
      body = [];
      verbatim = line.startsWith('\\begin{verbatim}');
    } else if (body !== null && (line.startsWith('\\end{align*}') || line.startsWith('\\end{verbatim}'))) {
      blocks.push({ heading, body: body.join('\n'), verbatim });
      body = null;
    } else if (body !== null && (verbatim || !line.startsWith('%'))) {
      body.push(line);
    }
  }
  return blocks;
}

/** Characters of LaTeX typeset without asking; longer blocks, and blocks past this many, wait
 * until their section is opened (laying out very large MathML takes the browser seconds). */
export const EAGER_CHARS = 20000;

/** The rows of an align* body, one equation each, `&=` as `=` (pure, tested). */
export function rows(body) {
  const out = [];
  let row = '';
  for (const line of body.split('\n')) {
    row += (row ? ' ' : '') + line.trim();
    if (/\\\\\s*$/.test(row)) {
      out.push(row.replace(/\\\\\s*$/, '').replace('&=', '=').trim());
      row = '';
    }
  }
  if (row.trim()) out.push(row.replace('&=', '=').trim());
  return out.filter((r) => r.length > 0);
}

// Typesetting runs in slices between animation frames, one equation at a time, so that the
// view keeps playing while a long list of equations appears.
const queue = [];
let draining = null;
function drain(done) {
  const until = performance.now() + 12;
  while (queue.length && performance.now() < until) {
    const [el, tex] = queue.shift();
    katex.render(tex, el, { displayMode: true, throwOnError: false, output: 'mathml', maxSize: 50, maxExpand: 10000, strict: 'ignore' });
  }
  if (queue.length) setTimeout(() => drain(done), 0);
  else {
    draining = null;
    done();
  }
}
function typeset(div, body, done = () => {}) {
  for (const r of rows(body)) {
    const el = document.createElement('div');
    el.className = 'equation';
    div.appendChild(el);
    queue.push([el, r]);
  }
  if (!draining) draining = setTimeout(() => drain(done), 0);
}

/** Typesets the LaTeX of `derive` into `root`; `done` is called when the first equations are in. */
export function renderEquations(root, tex, done = () => {}) {
  let budget = EAGER_CHARS;
  for (const { heading, body, verbatim } of splitLatex(tex)) {
    const section = document.createElement('details');
    const summary = document.createElement('summary');
    summary.textContent = body ? `${heading} (${body.split('\n').length} lines)` : heading;
    section.appendChild(summary);
    root.appendChild(section);
    if (!body) continue;
    if (verbatim) {
      const pre = document.createElement('pre');
      pre.className = 'verbatim';
      pre.textContent = body;
      section.appendChild(pre);
      section.open = budget > 0;
      budget -= body.length;
      continue;
    }
    const div = document.createElement('div');
    section.appendChild(div);
    if (body.length <= budget) {
      budget -= body.length;
      typeset(div, body);
      section.open = true;
    } else {
      section.addEventListener('toggle', () => section.open && !div.firstChild && typeset(div, body));
    }
  }
  if (draining) {
    clearTimeout(draining);
    draining = setTimeout(() => drain(done), 0);
  } else done();
}
