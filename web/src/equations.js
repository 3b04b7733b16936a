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

export function renderEquations(root, tex) {
  for (const { heading, body } of splitLatex(tex)) {
    const h = document.createElement('h3');
    h.textContent = heading;
    root.appendChild(h);
    if (!body) continue;
    const div = document.createElement('div');
    div.className = 'equation';
    katex.render(`\\begin{aligned}${body.replace(/\\\\\s*$/, '')}\\end{aligned}`, div, {
      displayMode: true,
      throwOnError: false,
      output: 'mathml',
      maxSize: 50,
      maxExpand: 10000,
      strict: 'ignore',
    });
    root.appendChild(div);
  }
}
