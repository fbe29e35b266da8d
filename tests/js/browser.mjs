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

export function launch() {
  return chromium.launch({
    executablePath: '/usr/bin/chromium',
    args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
           '--disable-component-update', '--disable-sync', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
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
