// README screenshots from real reports: node screenshots.mjs OUT_DIR REPORT.html[@FRACTION]...
// writes OUT_DIR/<name>.png of each report's 3-D view at FRACTION of its run (default 0.3).
import { basename, join, resolve } from 'node:path';
import { launch, openReport } from './chromium.mjs';

const [outDir, ...reports] = process.argv.slice(2);
const browser = await launch();
try {
  for (const spec of reports) {
    const [html, fraction = '0.3'] = spec.split('@');
    const { page } = await openReport(browser, resolve(html));
    await page.evaluate((f) => {
      const r = window.lagrangeReport;
      const t = r.view.s.t;
      r.pause();
      r.seek(t[0] + Number(f) * (t[t.length - 1] - t[0]));
    }, fraction);
    const png = join(outDir, `${basename(html, '.html')}.png`);
    await page.locator('#view').screenshot({ path: png });
    console.log(`wrote ${png}`);
    await page.close();
  }
} finally {
  await browser.close();
}
