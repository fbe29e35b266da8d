// phedra viewer: loads /model.glb (written by `phedra generate`), shows it at
// t* (paused: Play starts the folding animation, back and forth), and lets the
// user scrub (marks at t_lambda, t* and t_mu under the slider), step, jump to t*
// or a limit, type a t, change the speed, fit the view and save a picture.
// The motion parameter t shown is the glTF time mapped back through the
// export's extras (time_map: time is linear in t but at the flexion limits).
// Every number on the page is written one way (4 significant digits).
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { createStage } from './scene.js';
import { addPanelOutlines } from './outline.js';
import { Folds, foldColours } from './folds.js';
import { tAtTime, timeOfT } from './time_map.js';
import { clampToCore, expandByShownVertices, forEachShownVertex, frameBox, groundGrid, isModelMesh, motionBox } from './framing.js';
import { foldAnglePlot } from './plot.js';
import { baseName, canonicalPreset, pageTitle, significant4 as format, statusSummary } from './text.js';

const $ = (id) => document.getElementById(id);
const { renderer, scene, camera, controls } = createStage();

// The member colours of the file, darkened on screen (linear factor; about 2/3 in
// sRGB): light hinge lines of both colours stand out on every member colour.
const memberShade = 0.42;

let gltf = null, mixer = null, action = null, info = {}, times = [], duration = 0;
let position = 0, direction = 1, playing = false, box = null, outlines = { edges: 0, invalid: 0 };
let folds = null, foldCounts = { mountains: 0, valleys: 0 }, foldsShownAt = -1, picked = -1, marker = null, plotAxis = null;
let fileName = null;    // the name of the file shown, when known (a file opened)
let presetFile = null;  // the shipped preset it is an export of, when known (the menu, or recognised)

/// t at animation time `seconds`: by the file's time map (linear in t but at
/// the flexion limits); older files: piecewise linear between keyframes.
function tAt(seconds) {
  if (info.time_map) return tAtTime(info.time_map, seconds);
  const ts = info.keyframe_t;
  if (seconds <= times[0]) return ts[0];
  for (let k = 1; k < times.length; ++k) {
    if (seconds <= times[k]) return ts[k - 1] + (ts[k] - ts[k - 1]) * (seconds - times[k - 1]) / (times[k] - times[k - 1]);
  }
  return ts[ts.length - 1];
}

/// The first animation time showing t (null when t is not animated).
function timeOf(t) {
  if (info.time_map) return timeOfT(info.time_map, t);
  const ts = info.keyframe_t;
  for (let k = 1; k < ts.length; ++k) {
    const a = ts[k - 1], b = ts[k];
    if ((t - a) * (t - b) <= 0) return a === b ? times[k] : times[k - 1] + (times[k] - times[k - 1]) * (t - a) / (b - a);
  }
  return null;
}

function setTime(seconds) {
  // A LoopOnce action that reached its end pauses itself (clampWhenFinished): wake it.
  action.paused = false;
  action.enabled = true;
  mixer.setTime(Math.min(Math.max(seconds, 0), duration));
  scene.updateMatrixWorld(true);
}

/// Shows animation time `seconds`: the pose, the slider, t with its fraction of the interval.
function show(seconds) {
  position = Math.min(Math.max(seconds, 0), duration);
  setTime(position);
  $('slider').value = Math.round(1000 * position / duration);
  const t = tAt(position);
  const fraction = (t - info.t_lambda) / (info.t_mu - info.t_lambda);
  $('t').textContent = format(t);
  $('fraction').textContent = `${(100 * fraction).toFixed(1)} % of the flexion interval`;
  // Mountain/valley colours follow the pose (while playing, ten times a second).
  const now = performance.now();
  if (folds && (!playing || now - foldsShownAt > 100)) {
    foldsShownAt = now;
    foldCounts = folds.update();
    $('folds').innerHTML = `hinges at this t: <span style="color:#${foldColours.mountain.toString(16)}">` +
      `${foldCounts.mountains} mountain</span>, <span style="color:#${foldColours.valley.toString(16)}">` +
      `${foldCounts.valleys} valley</span> (dimmed on panels seen from behind), the rest flat or boundary (dark); ` +
      'click a hinge for its fold angle over the motion';
  }
  if (picked >= 0) showPicked(t);
}

/// The picked hinge: a marker on it and its fold angle now, and the plot's cursor at t.
function showPicked(t) {
  const [p, q] = folds.ends(picked);
  marker.geometry.setFromPoints([p, q]);
  const angle = folds.angle(folds.hinges[picked], folds.shownPositions());
  $('hinge-angle').textContent = `hinge ${picked} (vertices ${folds.hinges[picked].from}-${folds.hinges[picked].to}): ` +
    `${format(angle)} degrees (${Math.abs(angle) < 1e-6 ? 'flat' : angle > 0 ? 'valley' : 'mountain'})`;
  const cursor = $('hinge-plot').querySelector('.cursor');
  if (cursor) {
    const x = plotX(t);
    cursor.setAttribute('x1', x);
    cursor.setAttribute('x2', x);
  }
}
let plotX = () => 0;

/// Picks the hinge nearest `point` (on the surface) and plots its fold angle over
/// the motion, on an axis scaled to the angles it takes.
function pickHinge(point) {
  picked = folds.hingeNear(point);
  if (picked < 0) return;
  if (!marker) {
    marker = new THREE.Line(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: 0xffeb3b, depthTest: false }));
    marker.renderOrder = 5;
  }
  scene.add(marker);
  const keep = position, samples = [];
  for (let k = 0; k <= 120; ++k) {
    const seconds = duration * k / 120;
    setTime(seconds);
    samples.push([tAt(seconds), folds.angle(folds.hinges[picked], folds.shownPositions())]);
  }
  setTime(keep);
  const plot = foldAnglePlot(samples, { tLambda: info.t_lambda, tMu: info.t_mu, tStar: info.t_star, format });
  plotX = plot.x;
  plotAxis = plot.axis;
  $('hinge-plot').innerHTML = plot.svg;
  showPicked(tAt(position));
}

function setPlaying(on) {
  playing = on;
  $('play').textContent = playing ? 'Pause' : 'Play';
}

/// Marks under the slider at t_lambda, t* and t_mu (where the animation shows them
/// first), at the thumb's centre for that time (it runs from half a thumb, 8 px,
/// to the width less half a thumb).
function showMarks() {
  const marks = $('marks');
  marks.textContent = '';
  if (!duration) return;
  const at = { lo: timeOf(info.t_lambda), star: timeOf(info.t_star), hi: timeOf(info.t_mu) };
  const fraction = (seconds) => Math.min(1, Math.max(0, seconds / duration));
  for (const [key, label, t] of [['lo', 't\u03bb', info.t_lambda], ['star', 't*', info.t_star], ['hi', 't\u03bc', info.t_mu]]) {
    if (at[key] === null || at[key] === undefined) continue;
    const mark = document.createElement('span');
    mark.className = `mark ${key}`;
    mark.dataset.seconds = String(at[key]);
    mark.style.left = `calc(8px + ${fraction(at[key]).toFixed(4)} * (100% - 16px))`;
    mark.title = `${label} = ${format(t)}`;
    mark.textContent = label;
    marks.append(mark);
  }
  // t* next to a limit: its label goes one line down rather than over the limit's.
  const star = marks.querySelector('.star');
  if (star) {
    const r = star.getBoundingClientRect();
    const near = [...marks.querySelectorAll('.lo, .hi')].some((m) => { const q = m.getBoundingClientRect(); return q.left < r.right + 2 && r.left < q.right + 2; });
    star.classList.toggle('lower', near);
  }
}

/// Frames the whole motion in the part of the canvas the panel leaves free.
function fit() {
  if (!box) return;
  const canvas = renderer.domElement, panel = $('panel').getBoundingClientRect();
  frameBox(camera, controls, box, { left: panel.right + 8, width: canvas.clientWidth, height: canvas.clientHeight });
}
window.addEventListener('resize', fit);

function jumpTo(t) {
  const seconds = timeOf(t);
  if (seconds === null) {
    $('message').textContent = `t = ${format(t)} is not in the animation (it spans [${format(Math.min(...info.keyframe_t))}, ${format(Math.max(...info.keyframe_t))}])`;
    return false;
  }
  $('message').textContent = '';
  setPlaying(false);
  show(seconds);
  return true;
}

/// The keyframe before (-1) or after (+1) the shown time.
function step(sign) {
  setPlaying(false);
  const eps = 1e-6 * duration;
  const k = sign > 0 ? times.findIndex((x) => x > position + eps) : times.findLastIndex((x) => x < position - eps);
  if (k >= 0) show(times[k]);
}

function download(name, data, type) {
  const link = document.createElement('a');
  link.download = name;
  link.href = URL.createObjectURL(new Blob([data], { type }));
  link.click();
  setTimeout(() => URL.revokeObjectURL(link.href), 1000);
}

/// What the designer exports, from the preset the file carries (extras.phedra.preset).
const presetActions = ['save-preset', 'export-fold', 'edit'];
function savePreset() {
  download(`${info.name ?? 'phedra'}.json`, `${JSON.stringify(JSON.parse(info.preset), null, 2)}\n`, 'application/json');
}
async function exportFold() {
  // The FOLD comes from the core compiled to WebAssembly: the same code as `phedra generate X.fold`.
  let createPhedra;
  try {
    createPhedra = (await import('./wasm/phedra.mjs')).default;
  } catch {
    $('message').textContent = 'FOLD needs the browser core: run `bash scripts/build-wasm.sh`, then reload';
    return;
  }
  const core = await createPhedra();
  const designer = new core.Designer();
  const loaded = designer.load(info.preset);
  if (!loaded.ok) {
    $('message').textContent = `the preset in this file does not load: ${loaded.error}`;
    return;
  }
  download(`${info.name ?? 'phedra'}.fold`, designer.fold(41), 'application/json');
  designer.delete();
}
/// Hands a preset to the designer page (same origin) and opens it there (`file`: its file's name, if known).
function openInDesigner(text, file = null) {
  sessionStorage.setItem('phedra-open-preset', text);
  if (file) sessionStorage.setItem('phedra-open-preset-file', file);
  else sessionStorage.removeItem('phedra-open-preset-file');
  location.href = '/designer.html';
}

function savePicture() {
  renderer.render(scene, camera);
  const link = document.createElement('a');
  link.download = `${info.name ?? 'phedra'}.png`;
  link.href = renderer.domElement.toDataURL('image/png');
  link.click();
}

function describeFigures() {
  const c = info.check;
  if (!c) return '';
  const kind = info.kind ?? '';
  const closed = /tube|grid|assembly|row/.test(kind), members = /grid|assembly|row/.test(kind);
  const parts = [`planarity ${format(c.planarity)}`, `isometry ${format(c.isometry)}`];
  if (closed) parts.push(`closure ${format(c.closure)}`);
  if (members) parts.push(`shared vertices ${format(c.shared_vertices)}`);
  let text = `check over ${c.samples} samples (relative to the model size): ${parts.join(', ')}`;
  if (info.max_vertex_error !== undefined) {
    text += `; between keyframes within ${format(info.max_vertex_error / info.model_size)} of the exact motion`;
  }
  return text;
}

function legend(json) {
  const materials = json.materials ?? [];
  if (materials.length < 2) return '';
  if (materials.length > 12) return `${materials.length} members, one colour each`;
  return materials.map((m) => {
    const [r, g, b] = (m.pbrMetallicRoughness?.baseColorFactor ?? [1, 1, 1]).map((x) => Math.round(255 * x));
    return `<span class="swatch" style="background: rgb(${r},${g},${b})"></span>${m.name}`;
  }).join(' ');
}

const timelineControls = ['slider', 'play', 'prev', 'next', 'to-lo', 'to-star', 'to-hi', 'type-t'];
let helpers = [];

/// Removes the shown model, its animation and its grid.
function clearModel() {
  if (!gltf) return;
  mixer?.stopAllAction();
  scene.remove(gltf.scene, ...helpers);
  gltf = mixer = action = box = folds = null;
  picked = -1;
  if (marker) scene.remove(marker);
  $('hinge-plot').textContent = $('hinge-angle').textContent = $('folds').textContent = '';
  times = [];
  duration = position = 0;
  direction = 1;
  setPlaying(false);
  $('marks').textContent = '';
  for (const id of ['restricted', 'legend', 'message', 'buildability', 'fraction']) $(id).textContent = '';
}

/// Shows a loaded glTF in place of the previous model.
function showModel(loaded) {
  clearModel();
  gltf = loaded;
  const json = gltf.parser.json;
  info = json.asset.extras?.phedra ?? {};
  scene.add(gltf.scene);
  const shaded = new Set();
  gltf.scene.traverse((o) => {
    if (!o.isMesh || shaded.has(o.material)) return;
    shaded.add(o.material);
    o.material.color.multiplyScalar(memberShade);
  });
  outlines = addPanelOutlines(gltf, info.buildability?.invalid_panels ?? []);
  folds = Folds.of(gltf);
  folds?.watch(camera);
  foldsShownAt = -1;
  plotAxis = null;
  showTitle();
  $('kind').textContent = info.kind ?? '';
  $('lo').textContent = format(info.t_lambda);
  $('hi').textContent = format(info.t_mu);
  $('tstar').textContent = format(info.t_star);
  $('figures').textContent = describeFigures();
  $('legend').innerHTML = legend(json);
  if (info.animated_interval) {
    $('restricted').textContent = `animated: the intersection-free part [${format(info.animated_interval[0])}, ${format(info.animated_interval[1])}]`;
  }
  // What the command said of the design when it wrote the file (docs/design.md, Buildable designs),
  // in the page's numbers, without the interval shown above.
  if (info.buildability) {
    const b = info.buildability;
    $('buildability').textContent = statusSummary(b.summary, format) + (outlines.invalid ? ' (invalid panels in red)' : '');
    $('buildability').style.color = b.buildable ? '#a5d6a7' : '#ffcc80';
  }
  for (const id of presetActions) $(id).disabled = !info.preset;
  $('preset-actions').title = info.preset ? '' : 'this file carries no preset (written by an older phedra)';
  const panels = info.panels ?? json.nodes.length;
  const animated = gltf.animations.length > 0;
  for (const id of timelineControls) $(id).disabled = !animated;
  if (animated) {
    mixer = new THREE.AnimationMixer(gltf.scene);
    action = mixer.clipAction(gltf.animations[0]);
    action.setLoop(THREE.LoopOnce);
    action.clampWhenFinished = true;
    action.play();
    duration = gltf.animations[0].duration;
    times = Array.from(gltf.animations[0].tracks[0].times);
    // Framing over the whole motion: the shown boxes at (up to 64 of) the keyframes.
    const every = Math.max(1, Math.ceil(times.length / 64));
    box = motionBox(gltf.scene, setTime, times.filter((_, k) => k % every === 0 || k === times.length - 1));
    show(timeOf(info.t_star) ?? 0);
    box = clampToCore(box, expandByShownVertices(new THREE.Box3(), gltf.scene));
    showMarks();
  } else {
    box = expandByShownVertices(new THREE.Box3(), gltf.scene);
    for (const id of timelineControls) $(id).disabled = true;
    $('t').textContent = format(info.t ?? info.t_star);
    setPlaying(false);
  }
  const { grid, cell } = groundGrid(box);
  const axes = new THREE.AxesHelper(cell).translateX(box.min.x).translateY(box.min.y).translateZ(box.max.z);
  scene.add(grid, axes);
  helpers = [grid, axes];
  $('scale').textContent = `grid cells of ${format(cell)} model units; axes x red, y (up) green, z blue, one cell long`;
  fit();
  $('status').textContent = `${panels} panels (${info.representation ?? 'nodes'}), ${outlines.edges} edges drawn` +
    (animated ? `, ${times.length} keyframes, ${format(duration)} s` : ', static');
  window.phedraViewer.ready = true;
  window.phedraViewer.loads += 1;
  if (!presetFile) recognisePreset();
}

function failed(error) {
  $('status').textContent = `cannot load the model: ${error.message ?? error}`;
  console.error(error);
}
/// The title: the preset's name, and the file when it says more (the tab's title too).
function showTitle() {
  const title = pageTitle({ name: info.name, file: fileName, page: 'phedra viewer' });
  const stem = (presetFile ?? '').replace(/\.json$/, '');
  $('title').textContent = title.name;
  const source = presetFile && stem !== title.name && presetFile !== fileName ? `export of ${presetFile}` : '';
  $('file').textContent = [title.file, source].filter(Boolean).join(', ');
  document.title = title.document;
}

/// The shipped preset the shown file is an export of (recognised by its preset:
/// a .glb does not say which file its preset came from).
async function recognisePreset() {
  if (!info.preset) return;
  try {
    const wanted = canonicalPreset(JSON.parse(info.preset));
    const list = await (await fetch('/presets/index.json')).json();
    for (const p of list.filter((e) => e.name === info.name)) {
      if (canonicalPreset(await (await fetch(`/presets/${p.file}`)).json()) === wanted) {
        presetFile = p.file;
        showTitle();
        return;
      }
    }
  } catch { /* no list: the name alone */ }
}

/// Loads a .glb from the server (the file `phedra view` was given, or a preset's export).
function loadUrl(url, what) {
  $('status').textContent = `loading ${what}…`;
  new GLTFLoader().load(url, showModel, undefined, failed);
}
/// Loads a .glb the user picked or dropped.
async function loadFile(file) {
  if (/\.json$/i.test(file.name)) {
    openInDesigner(await file.text(), file.name);  // a preset: the designer edits it (and says what is wrong with it)
    return;
  }
  if (!/\.(glb|gltf)$/i.test(file.name)) {
    $('status').textContent = `${file.name}: the viewer shows .glb files (phedra generate PRESET -o FILE.glb) and opens presets (.json) in the designer`;
    return;
  }
  $('status').textContent = `loading ${file.name}…`;
  $('presets').value = '';
  fileName = baseName(file.name);
  presetFile = null;
  new GLTFLoader().parse(await file.arrayBuffer(), '', showModel, failed);
}
// The file `phedra view` serves, named for the title (before the model shows).
fetch('/served.json').then((r) => (r.ok ? r.json() : {})).then((served) => {
  if (served.file && !fileName && !presetFile) fileName = baseName(served.file);
}).catch(() => {}).finally(() => loadUrl('/model.glb', 'the model'));

// The shipped presets (as `phedra view` serves them), each shown through its default export.
fetch('/presets/index.json').then((r) => (r.ok ? r.json() : [])).then((list) => {
  for (const p of list) {
    const option = document.createElement('option');
    option.value = p.file.replace(/\.json$/, '');
    option.textContent = p.name;
    option.title = p.description;
    $('presets').append(option);
  }
  $('presets').disabled = list.length === 0;
}).catch(() => { $('presets').disabled = true; });
$('presets').addEventListener('change', (e) => {
  if (!e.target.value) return;
  fileName = null;
  presetFile = `${e.target.value}.json`;
  loadUrl(`/presets/${e.target.value}.glb`, `the preset ${e.target.value} (exporting it)`);
});
$('open').addEventListener('change', (e) => { if (e.target.files[0]) loadFile(e.target.files[0]); });
window.addEventListener('dragover', (e) => e.preventDefault());
window.addEventListener('drop', (e) => {
  e.preventDefault();
  if (e.dataTransfer.files[0]) loadFile(e.dataTransfer.files[0]);
});

$('slider').addEventListener('input', () => {
  setPlaying(false);
  show(duration * $('slider').value / 1000);
});
$('play').addEventListener('click', () => {
  // Play from where the slider is; at the end of a one-way run start over.
  if (!playing && $('loop').value === 'once' && position >= duration) position = 0;
  setPlaying(!playing);
});
$('prev').addEventListener('click', () => step(-1));
$('next').addEventListener('click', () => step(1));
$('to-lo').addEventListener('click', () => jumpTo(info.t_lambda));
$('to-star').addEventListener('click', () => jumpTo(info.t_star));
$('to-hi').addEventListener('click', () => jumpTo(info.t_mu));
$('type-t').addEventListener('change', () => {
  const t = Number($('type-t').value);
  if ($('type-t').value.trim() === '' || !Number.isFinite(t)) {
    $('message').textContent = `"${$('type-t').value}" is not a number`;
    return;
  }
  jumpTo(t);
});
$('fit').addEventListener('click', fit);
// Turning the view changes which panels are seen from behind: their hinges dim (ten times a second at most, and once it stops).
let facingTimer = null;
controls.addEventListener('change', () => {
  clearTimeout(facingTimer);
  const refresh = () => { if (folds && !playing) { foldsShownAt = performance.now(); foldCounts = folds.update(); } };
  if (performance.now() - foldsShownAt > 100) refresh();
  facingTimer = setTimeout(refresh, 120);
});
// A click (not a drag of the view) on the surface picks the nearest hinge.
let pressed = null;
renderer.domElement.addEventListener('pointerdown', (e) => { pressed = [e.clientX, e.clientY]; });
renderer.domElement.addEventListener('pointerup', (e) => {
  if (!pressed || !folds || Math.hypot(e.clientX - pressed[0], e.clientY - pressed[1]) > 4) return;
  const rect = renderer.domElement.getBoundingClientRect();
  const raycaster = new THREE.Raycaster();
  raycaster.setFromCamera(new THREE.Vector2((e.clientX - rect.left) / rect.width * 2 - 1, -(e.clientY - rect.top) / rect.height * 2 + 1), camera);
  const surfaces = [];
  gltf.scene.traverse((o) => { if (o.isMesh) surfaces.push(o); });  // front faces, and the back faces' meshes
  const hit = raycaster.intersectObjects(surfaces, false)[0];
  if (hit) pickHinge(hit.point);
});
$('png').addEventListener('click', savePicture);
$('save-preset').addEventListener('click', savePreset);
$('export-fold').addEventListener('click', exportFold);
$('edit').addEventListener('click', () => openInDesigner(info.preset, fileName ?? presetFile));
window.addEventListener('keydown', (e) => {
  if (e.target instanceof HTMLInputElement || e.target instanceof HTMLSelectElement) return;
  if (e.key === 'f') fit();
  else if (e.key === ' ') { e.preventDefault(); if (mixer) setPlaying(!playing); }
  else if (e.key === 'ArrowLeft' && mixer) step(-1);
  else if (e.key === 'ArrowRight' && mixer) step(1);
});

const clock = new THREE.Clock();
renderer.setAnimationLoop(() => {
  const dt = Math.min(clock.getDelta(), 0.1);  // a stalled frame (a busy tab) does not make the motion jump
  if (mixer && playing) {
    let next = position + direction * Number($('speed').value) * dt;
    const mode = $('loop').value;
    if (next > duration || next < 0) {
      if (mode === 'ping-pong') {
        next = next > duration ? 2 * duration - next : -next;
        direction = -direction;
      } else if (mode === 'loop') {
        direction = 1;
        next = next > duration ? next - duration : duration + next;
      } else {
        next = Math.min(Math.max(next, 0), duration);
        setPlaying(false);
      }
    }
    show(next);
  }
  controls.update();
  renderer.render(scene, camera);
});

// For tests and scripts: the world position of a mesh vertex, and the state.
window.phedraViewer = {
  ready: false,
  loads: 0,  // models shown so far (the file, then presets and files the user opens)
  pause() { setPlaying(false); },
  play() { setPlaying(true); },
  /// Mesh vertex `index` (as phedra numbers it: `phedra sample`'s order) in
  /// world space, as shown: morph targets applied, or through the panel node
  /// that holds it (extras.vertices).
  vertex(index) {
    let found = null;
    scene.traverse((o) => {
      if (found || !isModelMesh(o)) return;
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
  state() { return { position, duration, playing, direction, keyframes: times.length, ...outlines, ...foldCounts, picked }; },
  /// The fold-angle plot's value axis and the angles it shows: {lo, hi, step, ticks, min, max}, or null.
  plotAxis: () => plotAxis,
  /// Hinges drawn dimmed (both their panels seen from behind).
  dimmedHinges: () => (folds ? folds.back.reduce((n, b, k) => n + (b && folds.signs[k] ? 1 : 0), 0) : 0),
  /// Where on the page the middle of hinge k is shown (pixels), for a click on it.
  hingeScreen(k) {
    const [p, q] = folds.ends(k), m = p.add(q).multiplyScalar(0.5).project(camera);
    const rect = renderer.domElement.getBoundingClientRect();
    return [rect.left + (m.x + 1) / 2 * rect.width, rect.top + (1 - m.y) / 2 * rect.height];
  },
  hinges: () => folds?.hinges.length ?? 0,
  /// The model's extent on screen (normalised device coordinates, -1..1 fills
  /// the canvas) at animation time `seconds` (default: as shown).
  screenBox(seconds) {
    const keep = position;
    if (seconds !== undefined && mixer) setTime(seconds);
    const out = { minX: Infinity, maxX: -Infinity, minY: Infinity, maxY: -Infinity };
    forEachShownVertex(gltf.scene, (p) => {
      p.project(camera);
      out.minX = Math.min(out.minX, p.x); out.maxX = Math.max(out.maxX, p.x);
      out.minY = Math.min(out.minY, p.y); out.maxY = Math.max(out.maxY, p.y);
    });
    if (mixer) setTime(keep);
    return out;
  },
  timeOf,
};
