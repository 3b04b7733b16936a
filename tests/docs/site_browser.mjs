// The built manual in headless Chromium (issue 39): the start page and a tutorial open without
// console errors or warnings, and the search page lists the model-language page for "Baumgarte".
// usage: node site_browser.mjs HTML_DIR
import { launch } from '../../web/chromium.mjs';
import http from 'node:http';
import fs from 'node:fs';
import path from 'node:path';

const dir = process.argv[2];
if (!dir) {
  console.error('usage: node site_browser.mjs HTML_DIR');
  process.exit(2);
}
// Served from 127.0.0.1 as a reader's web server would (the search fetches pages, which a
// file:// page may not); nothing leaves the machine.
const types = { '.html': 'text/html', '.js': 'text/javascript', '.css': 'text/css',
  '.svg': 'image/svg+xml', '.png': 'image/png', '.json': 'application/json' };
const server = http.createServer((req, res) => {
  // The browser asks every server for /favicon.ico by itself; the manual has none.
  if (req.url === '/favicon.ico') { res.writeHead(204); res.end(); return; }
  const file = path.join(dir, decodeURIComponent(new URL(req.url, 'http://x').pathname));
  fs.readFile(file, (err, data) => {
    if (err) { res.writeHead(404); res.end(); return; }
    res.writeHead(200, { 'Content-Type': types[path.extname(file)] || 'application/octet-stream' });
    res.end(data);
  });
});
await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
const base = `http://127.0.0.1:${server.address().port}/`;
const browser = await launch();
const failures = [];
async function open(relative, check) {
  const messages = [];
  const page = await browser.newPage();
  page.on('console', (m) => {
    if (m.type() === 'error' || m.type() === 'warning') messages.push(`console ${m.type()}: ${m.text()}`);
  });
  page.on('pageerror', (e) => messages.push(`page error: ${e.message}`));
  page.on('requestfailed', (r) => messages.push(`request failed: ${r.url()}`));
  page.on('response', (r) => { if (r.status() >= 400 && !r.url().endsWith('/favicon.ico')) messages.push(`HTTP ${r.status()}: ${r.url()}`); });
  await page.goto(base + relative, { waitUntil: 'load' });
  if (check) await check(page, messages);
  await page.waitForTimeout(300);
  for (const m of messages) failures.push(`${relative}: ${m}`);
  await page.close();
}
await open('index.html');
await open('manual/tutorials/pendulum.html');
await open('search.html?q=Baumgarte', async (page, messages) => {
  try {
    await page.waitForSelector('ul.search li a[href*="model-language"]', { timeout: 20000 });
  } catch {
    messages.push('the search for Baumgarte does not list model-language');
  }
});
await browser.close();
server.close();
for (const f of failures) console.log('FAIL', f);
console.log(`opened 3 pages: ${failures.length} problems`);
process.exit(failures.length ? 1 : 0);
