// three.js figures of a glTF export (issue 15): GLTFLoader parse time (best of
// 3) and the draw calls it makes (meshes x primitives, one per member for the
// morph targets; one per panel for --nodes). Target: under 1 s at 10^4 panels.
// usage: node bench/three_load.mjs FILE.glb
import { readFile } from 'node:fs/promises';

const three = new URL('../web/node_modules/three/', import.meta.url);
await import(new URL('build/three.module.js', three));
const { GLTFLoader } = await import(new URL('examples/jsm/loaders/GLTFLoader.js', three));
const bytes = await readFile(process.argv[2]);
const buffer = bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength);
let best = Infinity, gltf = null;
for (let k = 0; k < 3; ++k) {
  const start = performance.now();
  gltf = await new Promise((resolve, reject) => new GLTFLoader().parse(buffer.slice(0), '', resolve, reject));
  best = Math.min(best, performance.now() - start);
}
let draws = 0;
gltf.scene.traverse((o) => { if (o.isMesh) ++draws; });
const info = gltf.parser.json.asset.extras?.phedra ?? {};
console.log(JSON.stringify({ file: process.argv[2], panels: info.panels, representation: info.representation,
  parse_ms: Math.round(best), draw_calls: draws, members: gltf.parser.json.materials.length }));
