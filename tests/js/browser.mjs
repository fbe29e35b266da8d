// What the browser tests share: `phedra view` started on a free port, Debian's
// Chromium launched headless through playwright-core, and a look at the canvas.
import { createRequire } from 'node:module';
import { spawn } from 'node:child_process';

const require = createRequire(new URL('../../web/package.json', import.meta.url));
const { chromium } = require('playwright-core');

/// Starts `phedra view FILE --port 0`; resolves to {server, address} once it prints an address matching `pattern`.
export function serve(phedra, file, pattern) {
  const server = spawn(phedra, ['view', file, '--port', '0'], { stdio: ['ignore', 'pipe', 'inherit'] });
  return new Promise((resolve, reject) => {
    let text = '';
    server.stdout.on('data', (d) => { text += d; const m = text.match(pattern); if (m) resolve({ server, address: m[0] }); });
    server.on('exit', (code) => reject(new Error(`phedra view exited with ${code}`)));
    setTimeout(() => reject(new Error('phedra view printed no address')), 10000);
  });
}

/// The software renderers this machine offers WebGL (it has no GPU): Mesa's llvmpipe
/// through ANGLE's GL-EGL backend, or Chromium's own SwiftShader.
export const renderers = {
  llvmpipe: ['--use-gl=angle', '--use-angle=gl-egl', '--ignore-gpu-blocklist'],
  swiftshader: ['--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
};

export function launch(renderer = 'swiftshader', extra = []) {
  return chromium.launch({
    executablePath: '/usr/bin/chromium',
    args: ['--no-sandbox', '--disable-quic', '--no-first-run', '--disable-background-networking',
           '--disable-component-update', '--disable-sync', ...renderers[renderer], ...extra],
  });
}

/// How many distinct colours (5 bits a channel) the WebGL canvas in #view shows: a blank one shows 1.
export function canvasColours(page) {
  return page.evaluate(() => {
    const source = document.querySelector('#view canvas');
    const copy = document.createElement('canvas');
    copy.width = 200; copy.height = 140;
    const g = copy.getContext('2d');
    g.drawImage(source, 0, 0, copy.width, copy.height);
    const data = g.getImageData(0, 0, copy.width, copy.height).data;
    const seen = new Set();
    for (let i = 0; i < data.length; i += 4) seen.add((data[i] >> 3) << 10 | (data[i + 1] >> 3) << 5 | (data[i + 2] >> 3));
    return seen.size;
  });
}

/// An open P-hedron of about `vertices` vertices on a third of a helix, all signs +
/// (10^4: 101 profiles of 100 vertices, 9,900 panels).
export function helixPreset(vertices) {
  // About sqrt(N) profiles on a third of a helix's turn and as many apex heights
  // (climbing in a zigzag, scaled with the profiles' spacing): panels about as
  // wide as long, every one simple, the motion free of collisions (buildable
  // with the default size bounds: a 9-column helix of 10^4 vertices had slivers).
  const profiles = Math.round(Math.sqrt(vertices)) + 1, m = profiles - 1, heights = profiles - 2, s = 10 / profiles;
  const trajectory = [], directions = [], apex_heights = [];
  for (let i = 0; i <= m; ++i) {
    const q = 0.33 * 2 * Math.PI * i / m;
    trajectory.push([3 * Math.cos(q), 3 * Math.sin(q), 1.32 * i / m]);
    const r = q - 20 * Math.PI / 180;  // turned this way every panel is simple and the motion collision-free
    directions.push([Math.cos(r), Math.sin(r), 0]);
  }
  for (let k = 0; k < heights; ++k) apex_heights.push(s * (0.5 * k + (k % 2 ? 2.5 : 0) - 1.5));
  return { name: `helix-${profiles}x${heights + 1}`, trajectory, directions, apex_heights, signs: '+'.repeat(heights - 2) };
}
