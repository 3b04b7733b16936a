// Headless Chromium for the report's tests and screenshots: playwright-core driving the system's
// Debian `chromium` (no browser downloads). Each launch has a fresh profile: playwright makes a
// new temporary --user-data-dir itself (and refuses one passed as an argument).
import { chromium } from 'playwright-core';
import { pathToFileURL } from 'node:url';

export async function launch() {
  return chromium.launch({
    executablePath: '/usr/bin/chromium',
    args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
      '--disable-background-networking', '--disable-component-update', '--disable-sync',
      '--enable-unsafe-swiftshader'],
  });
}

// Chromium's software WebGL (SwiftShader under --disable-gpu) reads every frame back for the
// software compositor and says so as a console warning of its GL driver, whatever the page does
// (also on an empty three.js scene). That one message is the browser's, not the report's.
const SOFTWARE_GL_NOTICE = /^\[\.WebGL-0x[0-9a-f]+\]GL Driver Message \(OpenGL, Performance, GL_CLOSE_PATH_NV, High\): GPU stall due to ReadPixels( \(this message will no longer repeat\))?$/;

/** Opens a report and waits for its first frame (`seconds` after navigation began); console errors and warnings go to `messages`. */
export async function openReport(browser, html, messages = []) {
  const page = await browser.newPage({ viewport: { width: 1100, height: 900 } });
  page.on('console', (m) => {
    if ((m.type() === 'error' || m.type() === 'warning') && !SOFTWARE_GL_NOTICE.test(m.text())) messages.push(`console ${m.type()}: ${m.text()}`);
  });
  page.on('pageerror', (e) => messages.push(`page error: ${e.message}`));
  await page.goto(pathToFileURL(html).href, { waitUntil: 'commit' });
  await page.waitForFunction(() => window.lagrangeReport && window.lagrangeReport.frames.count >= 1, null, { timeout: 30000 });
  // Seconds from the start of navigation to the first frame drawn, by the page's own clock.
  const seconds = (await page.evaluate(() => window.lagrangeReport.timings.firstFrame)) / 1000;
  return { page, seconds };
}
