// Loads a .glb with three.js (GLTFLoader + AnimationMixer), poses it at every
// keyframe and halfway between every two, and compares the world positions of
// every panel's vertices with `phedra sample` at the t the file's time map
// gives (extras.phedra.time_map: linear in t but at the flexion limits). Exits 1 when a deviation exceeds the tolerance:
// float32 precision at keyframes, the file's vertex_tolerance (plus float32)
// between them; relative to the model size.
// usage: node tests/js/compare_three.mjs PHEDRA_BINARY PRESET FILE.glb [relative tolerance]
import { readFile } from 'node:fs/promises';
import { execFileSync } from 'node:child_process';
import { tAtTime } from '../../web/time_map.js';

// The same module instance GLTFLoader imports as 'three' (the package's "import" entry).
const three = new URL('../../web/node_modules/three/', import.meta.url);
const THREE = await import(new URL('build/three.module.js', three));
const { GLTFLoader } = await import(new URL('examples/jsm/loaders/GLTFLoader.js', three));

const [phedra, preset, file, tol = '2e-5'] = process.argv.slice(2);
const bytes = await readFile(file);
const buffer = bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength);
const gltf = await new Promise((resolve, reject) => new GLTFLoader().parse(buffer, '', resolve, reject));
const info = gltf.parser.json.asset.extras.phedra;
const ts = info.keyframe_t;
const seconds = info.seconds;
const size = info.model_size;

const times = gltf.animations[0].tracks[0].times;
// Forward keyframes only (a ping-pong file plays them back too), and the middles.
const forward = [];
for (let k = 0; k < ts.length && (k === 0 || ts[k] !== ts[k - 1]); ++k) {
  if (k > 0 && ts[k] < ts[k - 1]) break;
  forward.push(k);
}
const poses = [];  // [animation time, t, tolerance]
const between = (info.vertex_tolerance ?? 0) / size;
for (const k of forward) {
  poses.push([null, ts[k], Number(tol), k]);
  // An interval already at the minimum spacing (next to a flexion limit) is held to what the file says of it.
  const narrow = times[k + 1] - times[k] < 2.0001 * (info.minimum_keyframe_spacing_seconds ?? 0);
  const allowed = narrow ? Math.max(between, (info.limit_vertex_error ?? 0) / size) : between;
  // Halfway in time; t from the file's time map (linear in t but at the flexion limits).
  const middle = 0.5 * (times[k] + times[k + 1]);
  const t = info.time_map ? tAtTime(info.time_map, middle) : 0.5 * (ts[k] + ts[k + 1]);
  if (k + 1 < forward.length) poses.push([null, t, allowed + Number(tol), k + 0.5]);
}
const args = ['sample', preset];
for (const [, t] of poses) args.push('--t', String(t));
const sample = JSON.parse(execFileSync(phedra, args, { maxBuffer: 1 << 30 }).toString());

const panels = [];
gltf.scene.traverse((o) => { if (o.isMesh) panels.push(o); });
const mixer = new THREE.AnimationMixer(gltf.scene);
const action = mixer.clipAction(gltf.animations[0]);
action.setLoop(THREE.LoopOnce);   // so that the last keyframe is not wrapped to the first
action.clampWhenFinished = true;
action.play();

let worst = 0, where = '', worstBetween = 0, failed = false;
const v = new THREE.Vector3();
for (let p = 0; p < poses.length; ++p) {
  const [, t, limit, at] = poses[p];
  const k = Math.floor(at);
  // setTime rewinds, then advances to this time (halfway: the middle of the keyframes' times).
  mixer.setTime(at === k ? times[k] : 0.5 * (times[k] + times[k + 1]));
  gltf.scene.updateMatrixWorld(true);
  const expected = sample.samples[p].vertices;
  let here = 0, hereWhere = '';
  for (const mesh of panels) {
    const position = mesh.geometry.getAttribute('position');
    const morphs = mesh.geometry.morphAttributes.position;
    // Node panels name their 4 mesh vertices; a morph mesh holds all of them in order.
    const ids = mesh.userData.vertices ?? [...Array(position.count).keys()];
    for (let c = 0; c < ids.length; ++c) {
      v.fromBufferAttribute(position, c);
      if (morphs) {
        mesh.morphTargetInfluences.forEach((w, j) => {
          if (w) v.add(new THREE.Vector3().fromBufferAttribute(morphs[j], c).multiplyScalar(w));
        });
      }
      v.applyMatrix4(mesh.matrixWorld);
      const [x, y, z] = expected[ids[c]];
      const d = Math.hypot(v.x - x, v.y - z, v.z + y);  // glTF (x, y, z) = preset (x, z, -y)
      if (d > here) { here = d; hereWhere = `${mesh.name} vertex ${ids[c]} at t = ${t}`; }
    }
  }
  if (here / size > limit) failed = true;
  if (at === k && here > worst) { worst = here; where = hereWhere; }
  if (at !== k && here > worstBetween) worstBetween = here;
}
console.log(`${file}: ${panels.length} meshes, ${info.panels ?? panels.length} panels, ${ts.length} keyframes (${seconds} s), ` +
  `largest deviation from phedra sample at keyframes ${(worst / size).toExponential(3)} of the model size` +
  `${where ? ' (' + where + ')' : ''}, halfway between them ${(worstBetween / size).toExponential(3)} (tolerance ${between.toExponential(1)})`);
process.exit(failed ? 1 : 0);
