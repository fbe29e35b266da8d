// Opens the viewer page in headless Chromium (Debian's /usr/bin/chromium, driven
// by playwright-core): the model renders (the canvas is not blank), no console
// errors, moving the slider changes the pose and the shown t, and the page says
// whether the design can be built (the file's extras).
// usage: node tests/js/viewer_test.mjs PHEDRA_BINARY FILE.glb SCREENSHOT.png
import { canvasColours, launch, serve } from './browser.mjs';

const [phedra, glb, screenshot] = process.argv.slice(2);
const { server, address } = await serve(phedra, glb, /http:\/\/127\.0\.0\.1:\d+\//);

const failures = [];
const browser = await launch();
try {
  const page = await browser.newPage({ viewport: { width: 1000, height: 700 } });
  const errors = [];
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  page.on('pageerror', (e) => errors.push(String(e)));
  await page.goto(address);
  await page.waitForFunction(() => window.phedraViewer?.ready === true, null, { timeout: 30000 });
  await page.evaluate(() => window.phedraViewer.pause());
  await page.waitForTimeout(300);
  // Rendered: the WebGL canvas holds more than the background colour.
  const colours = await canvasColours(page);
  if (colours < 10) failures.push(`the canvas looks blank (${colours} colours)`);
  if (screenshot) await page.screenshot({ path: screenshot });
  // The slider moves the model.
  const before = await page.evaluate(() => [window.phedraViewer.vertex(37), window.phedraViewer.t()]);
  await page.$eval('#slider', (s) => { s.value = 900; s.dispatchEvent(new Event('input')); });
  await page.waitForTimeout(200);
  const after = await page.evaluate(() => [window.phedraViewer.vertex(37), window.phedraViewer.t()]);
  const moved = Math.hypot(...before[0].map((x, i) => x - after[0][i]));
  if (!(moved > 1e-6)) failures.push('the slider did not change the pose');
  if (before[1] === after[1]) failures.push('the slider did not change the shown t');
  // The buildability the command stored in the file.
  const buildability = await page.$eval('#buildability', (e) => e.textContent);
  if (!buildability.startsWith('buildable over the whole flexion interval')) failures.push(`buildability line: "${buildability}"`);
  // The panels counted as the design has them (one morph mesh holds all 216).
  const status = await page.$eval('#status', (e) => e.textContent);
  if (!status.startsWith('216 panels (morph targets)')) failures.push(`status line: "${status}"`);
  if (errors.length) failures.push(`console errors: ${errors.join(' | ')}`);
  console.log(`viewer: ${colours} colours, corner moved ${moved.toExponential(3)}, t ${before[1]} -> ${after[1]}`);
} finally {
  await browser.close();
  server.kill();
}
if (failures.length) { console.log(failures.join('\n')); process.exit(1); }
console.log('1 passed, 0 failed');
