// Plays the modes glTF of `phedra mechanics -o modes.glb` in three.js
// (GLTFLoader + AnimationMixer): the rest pose is the design at the file's t
// (every panel corner where `phedra sample` puts it), each field a pair of morph
// targets named "NAME +" and "NAME -", and at a quarter and three quarters of
// field k's oscillation the mesh is the rest pose plus and minus field k (its
// largest displacement 8 % of the model size), the other targets at rest.
// usage: node tests/js/check_modes_three.mjs PHEDRA_BINARY PRESET FILE.glb
import { readFile } from 'node:fs/promises';
import { execFileSync } from 'node:child_process';

const three = new URL('../../web/node_modules/three/', import.meta.url);
const THREE = await import(new URL('build/three.module.js', three));
const { GLTFLoader } = await import(new URL('examples/jsm/loaders/GLTFLoader.js', three));

const [phedra, preset, file] = process.argv.slice(2);
const bytes = await readFile(file);
const gltf = await new Promise((resolve, reject) =>
  new GLTFLoader().parse(bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength), '', resolve, reject));
const info = gltf.parser.json.asset.extras.phedra;
const failures = [];
const fail = (what) => failures.push(what);

let mesh = null;
gltf.scene.traverse((o) => { if (o.isMesh) mesh = o; });
const position = mesh.geometry.getAttribute('position');
const morphs = mesh.geometry.morphAttributes.position;
const names = Object.keys(mesh.morphTargetDictionary);
const fields = morphs.length / 2;
if (fields !== info.eigenvalues.length + (info.motion_alignment === null ? 0 : 1)) fail(`${fields} fields for ${info.eigenvalues.length} modes`);
for (let k = 0; k < fields; ++k) {
  const base = k < info.eigenvalues.length ? `mode ${k + 1}` : 'exact motion';
  if (names[2 * k] !== `${base} +` || names[2 * k + 1] !== `${base} -`) fail(`targets ${2 * k}, ${2 * k + 1} named ${names[2 * k]}, ${names[2 * k + 1]}`);
}

// The rest pose: every vertex of `phedra sample` at t (preset frame) is a vertex of the mesh.
const sample = JSON.parse(execFileSync(phedra, ['sample', preset, '--t', String(info.t), '--full-precision']).toString());
const size = Math.max(...[0, 1, 2].map((c) => {
  const values = sample.samples[0].vertices.map((p) => p[c]);
  return Math.max(...values) - Math.min(...values);
})) * Math.sqrt(3);
let restWorst = 0;
const v = new THREE.Vector3();
for (const [x, y, z] of sample.samples[0].vertices) {
  let nearest = Infinity;
  for (let i = 0; i < position.count; ++i) {
    v.fromBufferAttribute(position, i);
    nearest = Math.min(nearest, Math.hypot(v.x - x, v.y - z, v.z + y));
  }
  restWorst = Math.max(restWorst, nearest);
}
if (restWorst > 1e-5 * size) fail(`rest pose ${restWorst} from phedra sample`);

// Quarter and three quarters of each oscillation.
const mixer = new THREE.AnimationMixer(gltf.scene);
const clip = gltf.animations[0];
const action = mixer.clipAction(clip);
action.setLoop(THREE.LoopOnce);
action.clampWhenFinished = true;
action.play();
const seconds = info.seconds_per_field;
if (Math.abs(clip.duration - seconds * fields) > 1e-4) fail(`animation of ${clip.duration} s for ${fields} fields of ${seconds} s`);
let worst = 0;
for (let k = 0; k < fields; ++k) {
  for (const [phase, target] of [[0.25, 2 * k], [0.75, 2 * k + 1]]) {
    mixer.setTime((k + phase) * seconds);
    mesh.morphTargetInfluences.forEach((w, j) => {
      if (Math.abs(w - (j === target ? 1 : 0)) > 1e-6) fail(`field ${k} at ${phase}: target ${j} weight ${w}`);
    });
    let largest = 0;
    for (let i = 0; i < position.count; ++i) {
      const played = new THREE.Vector3();
      mesh.getVertexPosition(i, played);
      const rest = new THREE.Vector3().fromBufferAttribute(position, i);
      const d = new THREE.Vector3().fromBufferAttribute(morphs[target], i);
      worst = Math.max(worst, played.distanceTo(rest.clone().add(d)));
      largest = Math.max(largest, d.length());
    }
    if (Math.abs(largest - 0.08 * info.model_size) > 1e-4 * info.model_size) fail(`field ${k}: largest displacement ${largest}`);
  }
}
if (worst > 1e-6 * size) fail(`played positions ${worst} from rest + target`);
console.log(`${file}: ${position.count} vertices, ${fields} fields (${names.slice(0, 4).join(', ')}...), rest pose within ` +
  `${(restWorst / size).toExponential(2)} of phedra sample, played within ${(worst / size).toExponential(2)}` +
  (failures.length ? `; FAILED: ${failures.slice(0, 5).join('; ')}` : ''));
process.exit(failures.length ? 1 : 0);
