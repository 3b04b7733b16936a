// The LaTeX of `lagrange derive --format latex` split into headed blocks and rendered by KaTeX.
import katex from 'katex';

/** [{heading, body}] from `% heading` lines and align* blocks (pure, tested). */
export function splitLatex(tex) {
  const blocks = [];
  let heading = '';
  let body = null;
  for (const line of tex.split('\n')) {
    if (body === null && line.startsWith('%')) {
      heading = line.replace(/^%\s*/, '');
      if (/more characters of equations/.test(heading)) blocks.push({ heading, body: '' });
    } else if (line.startsWith('\\begin{align*}')) {
      body = [];
    } else if (line.startsWith('\\end{align*}')) {
      blocks.push({ heading, body: body.join('\n') });
      body = null;
    } else if (body !== null && !line.startsWith('%')) {
      body.push(line);
    }
  }
  return blocks;
}

/** Characters of LaTeX typeset at once; longer blocks, and blocks past this many, wait until
 * their section is opened (laying out very large MathML takes the browser seconds). */
export const EAGER_CHARS = 20000;

function typeset(div, body) {
  katex.render(`\\begin{aligned}${body.replace(/\\\\\s*$/, '')}\\end{aligned}`, div, {
    displayMode: true,
    throwOnError: false,
    output: 'mathml',
    maxSize: 50,
    maxExpand: 10000,
    strict: 'ignore',
  });
}

export function renderEquations(root, tex) {
  let budget = EAGER_CHARS;
  for (const { heading, body } of splitLatex(tex)) {
    const section = document.createElement('details');
    const summary = document.createElement('summary');
    summary.textContent = body ? `${heading} (${body.split('\n').length} lines)` : heading;
    section.appendChild(summary);
    root.appendChild(section);
    if (!body) continue;
    const div = document.createElement('div');
    div.className = 'equation';
    section.appendChild(div);
    const eager = body.length <= budget;
    if (eager) {
      budget -= body.length;
      typeset(div, body);
      section.open = true;
    } else {
      section.addEventListener('toggle', () => section.open && !div.firstChild && typeset(div, body));
    }
  }
}
