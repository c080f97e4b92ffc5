#!/usr/bin/env node
// Opens a running viewer (for example the URL `bash scripts/view.sh`
// prints) in headless Chromium, waits until the stream is done, saves a
// screenshot and prints what the page drew: each level with its bytes,
// hash and time, and the time from the first byte to level 0 on screen.
// The evidence for "view.sh opens the example and refines it" without a
// display; with view.sh --rate it also measures a throttled connection.
//
//   node web/tools/screenshot.mjs URL OUT.png [--timeout SECONDS]
import { chromium } from 'playwright-core';

const [url, out] = process.argv.slice(2);
if (!url || !out) {
  console.error('usage: node web/tools/screenshot.mjs URL OUT.png [--timeout SECONDS]');
  process.exit(2);
}
const t = process.argv.indexOf('--timeout');
const timeout = 1000 * (t > 0 ? Number(process.argv[t + 1]) : 120);
const browser = await chromium.launch({ executablePath: process.env.DBSS_CHROMIUM ?? '/usr/bin/chromium',
  args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist'] });
try {
  const page = await browser.newPage({ viewport: { width: 900, height: 700 } });
  const problems = [];
  page.on('pageerror', (e) => problems.push(e.message));
  await page.goto(url);
  await page.waitForFunction(() => window.dbssViewer && window.dbssViewer.done, null, { timeout });
  // One more frame, so the finest level is on the canvas.
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  await page.screenshot({ path: out });
  const s = await page.evaluate(() => window.dbssViewer);
  for (const l of s.levels) console.log(`level ${l.level} ${JSON.stringify(l)}`);
  console.log(`shown ${s.shown}, error ${s.error ? s.error.codeName : 'none'}, bytes ${s.bytes}, ` +
    `first byte to level 0 drawn ${s.firstDrawnMs == null ? '-' : s.firstDrawnMs.toFixed(0) + ' ms'}`);
  if (problems.length) console.log(`page errors: ${problems.join('; ')}`);
  console.log(`screenshot: ${out}`);
  process.exitCode = s.error || problems.length || s.shown < 0 ? 1 : 0;
} finally {
  await browser.close();
}
