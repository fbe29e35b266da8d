// phedra viewer: loads /model.glb (written by `phedra generate`), plays its
// folding animation, and lets a slider scrub it. The motion parameter t shown is
// the glTF time mapped back through the export's extras (keyframe_t, seconds).
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { createStage } from './scene.js';

const $ = (id) => document.getElementById(id);
const { renderer, scene, camera, controls } = createStage();

const format = (x) => (Math.abs(x) < 1e-3 && x !== 0 ? x.toExponential(3) : x.toFixed(4));
let mixer = null, duration = 0, playing = true, info = null, times = [];

function tAt(seconds) {
  // Piecewise linear between keyframes, as the animation interpolates.
  const ts = info.keyframe_t;
  if (seconds <= times[0]) return ts[0];
  for (let k = 1; k < times.length; ++k) {
    if (seconds <= times[k]) return ts[k - 1] + (ts[k] - ts[k - 1]) * (seconds - times[k - 1]) / (times[k] - times[k - 1]);
  }
  return ts[ts.length - 1];
}

function show(seconds) {
  mixer.setTime(Math.min(seconds, duration));
  $('t').textContent = format(tAt(seconds));
}

new GLTFLoader().load('/model.glb', (gltf) => {
  info = gltf.parser.json.asset.extras?.phedra ?? {};
  scene.add(gltf.scene);
  $('title').textContent = info.name ?? 'phedra';
  $('kind').textContent = info.kind ?? '';
  $('lo').textContent = format(info.t_lambda);
  $('hi').textContent = format(info.t_mu);
  $('tstar').textContent = format(info.t_star);
  const c = info.check;
  if (c) {
    $('figures').textContent = `check over ${c.samples} samples (relative to the model size): planarity ${format(c.planarity)}, ` +
      `isometry ${format(c.isometry)}, closure ${format(c.closure)}, shared ${format(c.shared_vertices)}` +
      (info.max_vertex_error !== undefined ? `; between keyframes within ${format(info.max_vertex_error / info.model_size)} of the exact motion` : '');
  }
  // What the command said of the design when it wrote the file (docs/design.md, Buildable designs).
  if (info.buildability) {
    const b = info.buildability;
    $('buildability').textContent = b.summary;
    $('buildability').style.color = b.buildable ? '#a5d6a7' : '#ffcc80';
  }
  const box = new THREE.Box3().setFromObject(gltf.scene);
  const centre = box.getCenter(new THREE.Vector3()), size = box.getSize(new THREE.Vector3()).length();
  camera.position.copy(centre).add(new THREE.Vector3(0.6, 0.5, 0.9).multiplyScalar(size));
  camera.near = size / 1000; camera.far = size * 100; camera.updateProjectionMatrix();
  controls.target.copy(centre);
  if (gltf.animations.length) {
    mixer = new THREE.AnimationMixer(gltf.scene);
    const action = mixer.clipAction(gltf.animations[0]);
    action.setLoop(THREE.LoopOnce);
    action.clampWhenFinished = true;
    action.play();
    duration = gltf.animations[0].duration;
    times = Array.from(gltf.animations[0].tracks[0].times);
    show(0);
  } else {
    $('slider').disabled = $('play').disabled = true;
    $('t').textContent = format(info.t ?? info.t_star);
  }
  const panels = info.panels ?? gltf.parser.json.nodes.length;
  $('status').textContent = `${panels} panels (${info.representation ?? 'nodes'})` + (duration ? `, ${times.length} keyframes` : ', static');
  window.phedraViewer.ready = true;
}, undefined, (error) => { $('status').textContent = `cannot load the model: ${error.message ?? error}`; console.error(error); });

$('slider').addEventListener('input', () => {
  playing = false;
  $('play').textContent = 'Play';
  show(duration * $('slider').value / 1000);
});
$('play').addEventListener('click', () => {
  playing = !playing;
  $('play').textContent = playing ? 'Pause' : 'Play';
});

const clock = new THREE.Clock();
let elapsed = 0;
renderer.setAnimationLoop(() => {
  const dt = clock.getDelta();
  if (mixer && playing) {
    elapsed = (elapsed + dt) % duration;
    show(elapsed);
    $('slider').value = Math.round(1000 * elapsed / duration);
  }
  controls.update();
  renderer.render(scene, camera);
});
// For tests and scripts: the world position of a mesh vertex, and the state.
window.phedraViewer = {
  ready: false,
  pause() { playing = false; },
  /// Mesh vertex `index` (as phedra numbers it: `phedra sample`'s order) in
  /// world space, as shown: morph targets applied, or through the panel node
  /// that holds it (extras.vertices).
  vertex(index) {
    let found = null;
    scene.traverse((o) => {
      if (found || !o.isMesh) return;
      const ids = o.userData.vertices;
      const local = ids ? ids.indexOf(index) : index;
      const position = o.geometry.getAttribute('position');
      if (local < 0 || local >= position.count) return;
      const v = new THREE.Vector3().fromBufferAttribute(position, local);
      const morphs = o.geometry.morphAttributes.position;
      if (morphs) {
        o.morphTargetInfluences.forEach((w, j) => {
          if (w) v.add(new THREE.Vector3().fromBufferAttribute(morphs[j], local).multiplyScalar(w));
        });
      }
      found = v.applyMatrix4(o.matrixWorld).toArray();
    });
    return found;
  },
  t() { return $('t').textContent; },
};
