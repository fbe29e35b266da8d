// Drag steps of the browser designer (issue 8, docs/performance.md): opens
// `phedra view` on open P-hedra of 10^3, 10^4 and 10^5 vertices in Debian's
// Chromium (headless, through playwright-core), and times drag steps of
// trajectory point 1 through the code a drag runs (window.phedraDesigner.measure):
//   core   Designer.set (validation, construction, flexion interval), info, evaluate
//   step   the frame's edit: the core, the upload of the positions, handles, labels
//   full   the step and a draw at full resolution, waited for (a pixel read back)
//   frame  the same at the resolution a drag uses (`ratio` of the full one: lower
//          only when the full draw does not fit in a 60 Hz frame)
//   load   an edit through the preset's text instead (sign toggles, the JSON editor)
//   keep   a keep-buildable drag step (Designer.keep: the check at t* of simple
//          panels and no collision), and steps of a height dragged where panels
//          would cross (the other heights projected, or the handle stopped)
// and then drags trajectory point 1 with the mouse for 120 moves, recording every
// animation frame: how long its work took (edit, render), the interval to the next
// frame, and how many frames a 60 Hz display would have missed.
// Both software renderers of this GPU-less machine are measured (llvmpipe, SwiftShader):
// `frame` waits for the drawn frame (a pixel read back), so it includes the rasterization.
// usage: node bench/designer.mjs PHEDRA_BINARY [--runs N] [--json] [--vertices A,B,...]
//                                [--renderers llvmpipe,swiftshader]
import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { helixPreset, launch, renderers, serve } from '../tests/js/browser.mjs';

const args = process.argv.slice(2);
const option = (name, fallback) => { const k = args.indexOf(name); return k >= 0 ? args[k + 1] : fallback; };
const phedra = args[0];
if (!phedra || phedra.startsWith('--')) {
  console.error('usage: node bench/designer.mjs PHEDRA_BINARY [--runs N] [--json] [--vertices A,B,...] [--renderers llvmpipe,swiftshader]');
  process.exit(2);
}
const known = { '--runs': 1, '--json': 0, '--vertices': 1, '--renderers': 1 };
for (let k = 1; k < args.length; k += 1 + (known[args[k]] ?? 0)) {
  if (!(args[k] in known)) {
    console.error(`unknown option "${args[k]}" (known: ${Object.keys(known).join(', ')})`);
    process.exit(2);
  }
}
const runs = Number(option('--runs', '40'));
const sizes = option('--vertices', '1000,10000,100000').split(',').map(Number);
const chosen = option('--renderers', 'llvmpipe,swiftshader').split(',');
for (const r of chosen) {
  if (!renderers[r]) {
    console.error(`--renderers: unknown renderer "${r}" (known: ${Object.keys(renderers).join(', ')})`);
    process.exit(2);
  }
}
const stat = (values) => {
  const s = values.slice().sort((x, y) => x - y);
  return { median: s[s.length >> 1] ?? NaN, worst: s[s.length - 1] ?? NaN };
};

/// Drags trajectory point 1 with the mouse in `moves` small moves; the frames that applied an edit.
async function mouseDrag(page, moves) {
  const [x, y] = await page.evaluate(() => window.phedraDesigner.handleScreen('trajectory', 1));
  await page.mouse.move(x, y);
  await page.mouse.down();
  await page.evaluate(() => window.phedraDesigner.recordFrames());
  for (let k = 1; k <= moves; ++k) await page.mouse.move(x + 40 * Math.sin(k / 10), y - 30 * Math.sin(k / 15));
  await page.mouse.up();
  const log = await page.evaluate(() => window.phedraDesigner.stopFrames());
  const edits = log.filter((f) => f.edit);
  const intervals = log.slice(1).map((f, k) => f.start - log[k].start);
  return {
    frames: log.length,
    edits: edits.length,
    work: stat(edits.map((f) => f.work)),
    interval: stat(intervals),
    // a frame whose work does not end within 16.7 ms of its start misses the display's next refresh
    over: edits.filter((f) => f.work > 1000 / 60).length,
  };
}

const scratch = mkdtempSync(path.join(tmpdir(), 'phedra-bench-designer-'));
const results = [];
try {
  for (const renderer of chosen) {
    const browser = await launch(renderer);
    try {
      for (const count of sizes) {
        const file = path.join(scratch, `helix-${count}.json`);
        writeFileSync(file, JSON.stringify(helixPreset(count)));
        const { server, address } = await serve(phedra, file, /http:\/\/127\.0\.0\.1:\d+\/designer\.html/);
        try {
          const page = await browser.newPage({ viewport: { width: 1100, height: 760 } });
          await page.goto(address);
          await page.waitForFunction(() => window.phedraDesigner?.ready === true, null, { timeout: 120000 });
          await page.evaluate((n) => window.phedraDesigner.measure(n), Math.max(5, runs >> 1));  // warm-up
          const figures = await page.evaluate((n) => window.phedraDesigner.measure(n), runs);
          figures.renderer = renderer;
          // What WebGL really runs on (ANGLE falls back to SwiftShader when llvmpipe is missing).
          figures.gl = await page.evaluate(() => {
            const gl = document.querySelector('#view canvas').getContext('webgl2');
            const ext = gl.getExtension('WEBGL_debug_renderer_info');
            return ext ? gl.getParameter(ext.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER);
          });
          figures.canvas = await page.evaluate(() => { const c = document.querySelector('#view canvas'); return [c.width, c.height]; });
          figures.drag = await mouseDrag(page, 120);
          results.push(figures);
          await page.close();
        } finally {
          server.kill();
        }
      }
    } finally {
      await browser.close();
    }
  }
} finally {
  rmSync(scratch, { recursive: true, force: true });
}
if (args.includes('--json')) {
  console.log(JSON.stringify({ runs, results }, null, 2));
} else {
  const ms = (f) => `${f.median.toFixed(2)} (${f.worst.toFixed(2)})`;
  console.log(`drag steps of trajectory point 1, ${runs} runs, milliseconds: median (worst); 60 Hz frame = 16.7 ms`);
  console.log(['renderer', 'vertices', 'panels', 'core', 'step', 'full', 'ratio', 'frame', 'load', 'keep', 'keep, crossing'].map((h) => h.padStart(15)).join(''));
  for (const r of results) {
    console.log([r.renderer, String(r.vertices), String(r.panels), ms(r.core), ms(r.step), ms(r.full), r.ratio.toFixed(2), ms(r.frame), ms(r.load), ms(r.keep), ms(r.keepProjection)]
      .map((c) => c.padStart(15)).join(''));
  }
  console.log(`keep: a keep-buildable drag step of trajectory point 1 (the check at t*: simple panels, no collision;`);
  console.log(`  ${results.map((r) => `${r.kept} of ${runs}`).join(', ')} steps buildable as the hand put them, the others projected or stopped);`);
  console.log('keep, crossing: steps of apex height 1 dragged where panels would cross: the other heights projected');
  console.log(`(${results.map((r) => r.projected).join(', ')} steps) or the handle stopped at the wall (${results.map((r) => r.clamped).join(', ')} steps)`);
  console.log(`canvas ${results[0]?.canvas.join(' x ')} pixels, headless Chromium; WebGL on:`);
  for (const name of chosen) console.log(`  ${name}: ${results.find((r) => r.renderer === name)?.gl}`);
  console.log('\nmouse drags of trajectory point 1 (120 moves): frames drawn, those that applied an edit, their main-thread');
  console.log('work (edit + render call), how many of them took over 16.7 ms, and the intervals between drawn frames');
  console.log(['renderer', 'vertices', 'frames', 'edits', 'work', 'over 16.7 ms', 'interval'].map((h) => h.padStart(16)).join(''));
  for (const r of results) {
    const d = r.drag;
    console.log([r.renderer, String(r.vertices), String(d.frames), String(d.edits), ms(d.work), String(d.over), ms(d.interval)].map((c) => c.padStart(16)).join(''));
  }
}
