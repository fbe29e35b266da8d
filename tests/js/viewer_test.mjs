// Opens the viewer page in headless Chromium (Debian's /usr/bin/chromium, driven
// by playwright-core) on an exported .glb and checks what a user sees and does:
// the model renders (the canvas is not blank), no console errors, panel edges
// drawn, invalid panels in red (as many as the file's buildability names), the
// whole motion framed (the model inside the canvas at t_lambda, t* and t_mu),
// the slider moves the pose and t, Play continues from where the slider is,
// back and forth at the ends, stepping to keyframes, jumping to t* and the
// limits, a typed t (and a refused one), a PNG saved, and the status line.
// Issue 28: the page opens paused at t* with a Play button; marks under the
// slider at t_lambda, t* and t_mu; the fold-angle plot scaled to the data; one
// number format (the flexion interval shown once); the title from the preset's
// name and its file.
// usage: node tests/js/viewer_test.mjs PHEDRA_BINARY FILE.glb SCREENSHOT.png PANELS INVALID [REPRESENTATION]
import { readFileSync } from 'node:fs';
import path from 'node:path';
import { canvasColours, launch, serve } from './browser.mjs';

const [phedra, glb, screenshot, panels, invalid, representation = 'morph targets'] = process.argv.slice(2);
const { server, address } = await serve(phedra, glb, /http:\/\/127\.0\.0\.1:\d+\//);

const failures = [];
const check = (ok, message) => { if (!ok) failures.push(message); };
const browser = await launch();
let passed = 0;
try {
  const page = await browser.newPage({ viewport: { width: 1366, height: 768 }, acceptDownloads: true });
  const errors = [];
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  page.on('pageerror', (e) => errors.push(String(e)));
  await page.goto(address);
  await page.waitForFunction(() => window.phedraViewer?.ready === true, null, { timeout: 30000 });
  const viewer = (f, ...args) => page.evaluate(f, ...args);
  // It opens paused at t*, and the button says what it will do: Play.
  {
    await page.waitForTimeout(300);
    const opened = await viewer(() => ({ ...window.phedraViewer.state(), t: window.phedraViewer.t(), play: document.getElementById('play').textContent,
                                         star: document.getElementById('tstar').textContent }));
    check(!opened.playing && opened.play === 'Play' && opened.t === opened.star, `opened ${opened.playing ? 'playing' : 'paused'} at t = ${opened.t} (t* ${opened.star}), the button says ${opened.play}`);
  }
  await viewer(() => window.phedraViewer.pause());
  await page.waitForTimeout(300);
  const info = await viewer(() => ({ ...window.phedraViewer.state() }));
  // Rendered: the WebGL canvas holds more than the background colour.
  const colours = await canvasColours(page);
  check(colours >= 10, `the canvas looks blank (${colours} colours)`);
  // Legible geometry: edges, and the invalid panels the file names, in red.
  check(info.edges >= Number(panels), `${info.edges} edges drawn for ${panels} panels`);
  check(info.invalid === Number(invalid), `${info.invalid} panels drawn red, the file names ${invalid}`);
  const status = await page.$eval('#status', (e) => e.textContent);
  check(status.startsWith(`${panels} panels (${representation})`), `status line: "${status}"`);

  // Framing over the whole motion: inside the canvas (and not a speck) at both limits and t*.
  const times = await viewer(() => {
    const v = window.phedraViewer;
    return [v.timeOf(Number(document.getElementById('lo').textContent)), 0, v.state().duration, v.state().duration / 2];
  });
  for (const seconds of times) {
    const b = await viewer((s) => window.phedraViewer.screenBox(s), seconds);
    const inside = b.minX >= -1.001 && b.maxX <= 1.001 && b.minY >= -1.001 && b.maxY <= 1.001;
    check(inside, `at ${seconds} s the model leaves the canvas: ${JSON.stringify(b)}`);
    check(Math.max(b.maxX - b.minX, b.maxY - b.minY) > 0.25, `at ${seconds} s the model is a speck: ${JSON.stringify(b)}`);
  }

  // Marks under the slider at t_lambda, t* and t_mu, under the thumb at those times.
  {
    const marks = await page.$$eval('#marks .mark', (list) => list.map((m) => {
      const r = m.getBoundingClientRect(), s = document.getElementById('slider').getBoundingClientRect();
      const f = Number(m.dataset.seconds) / window.phedraViewer.state().duration;
      return { label: m.textContent, x: r.left + r.width / 2, thumb: s.left + 8 + f * (s.width - 16), title: m.title };
    }));
    check(marks.map((m) => m.label).join(' ') === 't\u03bb t* t\u03bc', `slider marks ${marks.map((m) => m.label)}`);
    for (const m of marks) check(Math.abs(m.x - m.thumb) <= 3, `the ${m.label} mark at x ${m.x.toFixed(0)}, the thumb there at ${m.thumb.toFixed(0)}`);
  }
  // One number format: 4 significant digits; the flexion interval shown once.
  {
    const text = await page.$eval('#panel', (e) => [...e.querySelectorAll('.row, #kind')].map((x) => x.textContent).join(' '));
    const long = (text.match(/(?<![\w.])-?\d+\.\d+(?![\w.])/g) ?? []).filter((x) => x.replace(/^-?0\.0*|[-.]/g, '').length > 4);
    check(long.length === 0, `numbers of more than 4 significant digits: ${long.slice(0, 5).join(', ')}`);
    const interval = await viewer(() => `[${document.getElementById('lo').textContent}, ${document.getElementById('hi').textContent}]`);
    check(text.split(interval).length === 2, `the flexion interval ${interval} shown ${text.split(interval).length - 1} times`);
  }
  // The title: the preset's name (and the file it came from when that says more).
  {
    const [title, file, tab] = await Promise.all([page.$eval('#title', (e) => e.textContent), page.$eval('#file', (e) => e.textContent), page.title()]);
    const stored = JSON.parse(JSON.parse(readFileSync(glb).subarray(20, 20 + readFileSync(glb).readUInt32LE(12)).toString('utf8')).asset.extras.phedra.preset ?? '{}');
    check(title === stored.name && tab.startsWith(title), `title "${title}" (tab "${tab}") for the preset "${stored.name}"`);
    if (stored.name === 'mixed-signs') check(file.endsWith('export of default.json'), `the export of default.json is titled "${title}" "${file}"`);
    check(file.startsWith(path.basename(glb)) || title === path.basename(glb).replace(/\.glb$/, ''), `the served file ${path.basename(glb)} is not named: "${title}" "${file}"`);
  }

  // Mountain and valley hinges coloured; a click on a hinge plots its fold angle over the motion.
  check(info.mountains + info.valleys > 0, `no hinge coloured mountain or valley: ${JSON.stringify(info)}`);
  {
    // The hinge nearest the middle of the canvas (one surely in view).
    const at = await viewer(() => {
      const v = window.phedraViewer, r = document.querySelector('#view canvas').getBoundingClientRect();
      let best = null;
      for (let k = 0; k < v.hinges(); ++k) {
        const p = v.hingeScreen(k), d = Math.hypot(p[0] - (r.left + r.width / 2), p[1] - (r.top + r.height / 2));
        if (!best || d < best.d) best = { d, p };
      }
      return best.p;
    });
    await page.mouse.click(at[0], at[1]);
    await page.waitForTimeout(200);
    const picked = await viewer(() => window.phedraViewer.state().picked);
    check(picked >= 0, 'a click on a hinge picked none');
    const points = await page.$eval('#hinge-plot', (e) => e.querySelector('polyline')?.getAttribute('points').split(' ').length ?? 0);
    check(points === 121, `the fold-angle plot has ${points} points`);
    const angle = await page.$eval('#hinge-angle', (e) => e.textContent);
    check(/^hinge \d+ \(vertices \d+-\d+\): -?[\d.e-]+ degrees \((valley|mountain|flat)\)$/.test(angle), `picked hinge line: "${angle}"`);
    // The plot's axis is scaled to the angles the hinge takes: within 3 times their range (at least a degree).
    const axis = await viewer(() => window.phedraViewer.plotAxis());
    const range = Math.max(axis.max - axis.min, 1);
    check(axis.lo <= axis.min && axis.hi >= axis.max && axis.hi - axis.lo <= 3 * range,
      `the fold-angle axis [${axis.lo}, ${axis.hi}] for angles in [${axis.min}, ${axis.max}]`);
    if (screenshot) await page.screenshot({ path: screenshot.replace(/\.png$/, '-hinge-plot.png') });
  }

  // The slider moves the model and t.
  const pose = () => viewer(() => [window.phedraViewer.vertex(5), window.phedraViewer.t(), window.phedraViewer.state().position]);
  const before = await pose();
  await page.$eval('#slider', (s) => { s.value = 300; s.dispatchEvent(new Event('input')); });
  const after = await pose();
  const moved = Math.hypot(...before[0].map((x, i) => x - after[0][i]));
  check(moved > 1e-6, 'the slider did not change the pose');
  check(before[1] !== after[1], 'the slider did not change the shown t');
  // Play continues from the slider's place.
  // Bounded by the wall time between the two clicks (a loaded machine can take seconds to click).
  const started = Date.now();
  await page.click('#play');
  await page.waitForTimeout(400);
  await page.click('#play');
  const elapsed = (Date.now() - started) / 1000;
  const played = (await pose())[2];
  check(played > after[2] && played < after[2] + elapsed + 0.25,
    `Play went from ${after[2]} s to ${played} s in ${elapsed} s, not on from the slider`);
  // Back and forth: from near the end, playing turns round.
  await page.$eval('#slider', (s) => { s.value = 990; s.dispatchEvent(new Event('input')); });
  await page.click('#play');
  await page.waitForTimeout(600);
  await page.click('#play');
  const turned = await viewer(() => window.phedraViewer.state());
  check(turned.direction === -1 && turned.position < turned.duration, `at the end playback did not turn round: ${JSON.stringify(turned)}`);
  // Jumps and steps.
  await page.click('#to-star');
  const star = await page.$eval('#tstar', (e) => e.textContent);
  check(await viewer(() => window.phedraViewer.t()) === star, `t* button shows t = ${await viewer(() => window.phedraViewer.t())}, t* is ${star}`);
  await page.click('#to-lo');
  check((await page.$eval('#fraction', (e) => e.textContent)).startsWith('0.0 %'), 'the t_lambda button is not at 0 % of the interval');
  await page.click('#next');
  const next = await viewer(() => window.phedraViewer.state().position);
  check(next > 0, 'the next-keyframe button did not move');
  await page.click('#prev');
  check(await viewer(() => window.phedraViewer.state().position) === 0, 'the previous-keyframe button did not go back to the first keyframe');
  // A typed t, and one that is not a number.
  const target = await viewer(() => { const v = window.phedraViewer; return 0.5 * (Number(document.getElementById('lo').textContent) + Number(document.getElementById('hi').textContent)); });
  await page.fill('#type-t', String(target));
  await page.press('#type-t', 'Enter');
  const typed = Number(await viewer(() => window.phedraViewer.t()));
  check(Math.abs(typed - target) <= 1e-3 * Math.abs(target) + 1e-3, `typed t = ${target}, shows ${typed}`);
  await page.fill('#type-t', 'abc');
  await page.press('#type-t', 'Enter');
  check((await page.$eval('#message', (e) => e.textContent)).includes('is not a number'), 'a typed non-number is not refused');
  // A PNG of the view.
  const [download] = await Promise.all([page.waitForEvent('download'), page.click('#png')]);
  check(download.suggestedFilename().endsWith('.png'), `saved "${download.suggestedFilename()}"`);
  // The shipped presets menu shows a preset through its default export; Open .glb shows a file.
  const options = await page.$$eval('#presets option', (list) => list.map((o) => o.value).filter(Boolean));
  check(options.includes('helix-tube') && options.includes('grid-3x3'), `presets menu: ${options}`);
  const loads = await viewer(() => window.phedraViewer.loads);
  await page.selectOption('#presets', 'helix-tube');
  await page.waitForFunction((n) => window.phedraViewer.loads > n, loads, { timeout: 30000 });
  const helix = [await page.$eval('#title', (e) => e.textContent), await page.$eval('#status', (e) => e.textContent)];
  check(helix[0] === 'helix-tube' && helix[1].startsWith('72 panels (morph targets)'), `the helix-tube preset shows ${helix}`);
  await page.setInputFiles('#open', glb);
  await page.waitForFunction((n) => window.phedraViewer.loads > n + 1, loads, { timeout: 30000 });
  check((await page.$eval('#status', (e) => e.textContent)).startsWith(`${panels} panels`), 'Open .glb did not show the file again');
  // The buildability the command stored in the file.
  const buildability = await page.$eval('#buildability', (e) => e.textContent);
  const buildable = Number(invalid) === 0;
  check(buildable ? buildability.startsWith('buildable over the whole flexion interval') : buildability.includes('(invalid panels in red)'),
        `buildability line: "${buildability}"`);
  // What the designer exports, from the preset the file carries: the preset, its FOLD; and the preset in the designer.
  for (const id of ['save-preset', 'export-fold', 'edit']) {
    check(!(await page.$eval(`#${id}`, (e) => e.disabled)), `#${id} is disabled for a file phedra wrote`);
  }
  const fileName = await page.$eval('#title', (e) => e.textContent);
  {
    const [saved] = await Promise.all([page.waitForEvent('download'), page.click('#save-preset')]);
    const preset = JSON.parse(readFileSync(await saved.path(), 'utf8'));
    check(saved.suggestedFilename() === `${fileName}.json` && preset.name === fileName, `Save preset wrote ${saved.suggestedFilename()} named ${preset.name}`);
    const [fold] = await Promise.all([page.waitForEvent('download', { timeout: 60000 }), page.click('#export-fold')]);
    const doc = JSON.parse(readFileSync(await fold.path(), 'utf8'));
    check(doc.file_spec === 1.2 && doc.file_frames?.length === 41 && doc.edges_assignment?.length > 0,
          `FOLD: spec ${doc.file_spec}, ${doc.file_frames?.length} frames besides the key frame`);
  }
  await page.click('#to-star');
  await page.waitForTimeout(200);
  if (screenshot) await page.screenshot({ path: screenshot });
  check(!errors.length, `console errors: ${errors.join(' | ')}`);
  // Edit in designer: the designer page opens with the file's preset.
  await page.click('#edit');
  await page.waitForURL(/designer\.html$/, { timeout: 30000 });
  await page.waitForFunction(() => document.getElementById('name')?.value, null, { timeout: 60000 });
  const designed = await page.$eval('#name', (e) => e.value);
  check(designed === fileName, `Edit in designer opened "${designed}", the file is "${fileName}"`);
  console.log(`viewer ${glb}: ${colours} colours, ${info.edges} edges, ${info.invalid} red, vertex moved ${moved.toExponential(3)}, ` +
              `t ${before[1]} -> ${after[1]}, played ${after[2].toFixed(2)} -> ${played.toFixed(2)} s`);
  passed = failures.length ? 0 : 1;
} finally {
  await browser.close();
  server.kill();
}
if (failures.length) { console.log(failures.join('\n')); process.exit(1); }
console.log(`${passed} passed, 0 failed`);
