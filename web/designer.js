// phedra designer: edit a preset's control polylines in 3D and see the P-hedron
// fold, live. The geometry comes from the phedra core itself, compiled to
// WebAssembly (wasm/phedra.mjs, scripts/build-wasm.sh): every edit rebuilds the
// design from the preset exactly as `phedra` does, so the messages are the
// CLI's, and a saved preset gives the same `phedra sample` result.
import * as THREE from 'three';
import { createStage } from './scene.js';
import createPhedra from './wasm/phedra.mjs';

const $ = (id) => document.getElementById(id);
const format = (x) => (Math.abs(x) < 1e-3 && x !== 0 ? x.toExponential(2) : x.toFixed(4));

// --- three.js scene --------------------------------------------------------
// No MSAA: it costs more than the whole motion update in a software-rendered browser.
const { renderer, scene, camera, controls } = createStage({ antialias: false });
camera.up.set(0, 0, 1);  // presets are z-up

const surface = new THREE.Mesh(new THREE.BufferGeometry(),
  new THREE.MeshStandardMaterial({ color: 0x7fb3e0, side: THREE.DoubleSide, flatShading: true, roughness: 0.8 }));
const edges = new THREE.LineSegments(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: 0x20303f }));
scene.add(surface, edges);
const handles = new THREE.Group();
scene.add(handles);
const axisLine = new THREE.Line(new THREE.BufferGeometry(), new THREE.LineDashedMaterial({ color: 0x66bb6a, dashSize: 0.1, gapSize: 0.06 }));
scene.add(axisLine);

// --- the core --------------------------------------------------------------
const core = await createPhedra();
const designer = new core.Designer();
let preset = null;          // the preset shown (always valid)
let info = null;            // designer.info() of it
let fraction = 0.5;         // slider position in [0, 1]
let faces = null;           // Uint32Array of quads
let failure = null;         // the last refused edit: {field, message}
let figures = null;

const clone = (o) => JSON.parse(JSON.stringify(o));
const axisOf = (p) => new THREE.Vector3(...(p.axis || [0, 0, 1])).normalize();
const tOf = (f) => info.t_lambda + f * (info.t_mu - info.t_lambda);

/// Rebuilds the design from `candidate`; on refusal keeps the shown design and reports.
function apply(candidate, { keepFigures = false } = {}) {
  const result = designer.load(JSON.stringify(candidate));
  if (!result.ok) {
    failure = { field: result.field, message: result.message };
    showMessage();
    return false;
  }
  failure = null;
  preset = candidate;
  info = designer.info();
  faces = Uint32Array.from(designer.faces());
  rebuildGeometry();
  rebuildHandles();
  updatePanel();
  if (!keepFigures) scheduleFigures();
  showMessage();
  return true;
}

function rebuildGeometry() {
  const count = info.vertices;
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(3 * count), 3));
  const index = [];
  const lines = [];
  for (let f = 0; f < faces.length; f += 4) {
    const [a, b, c, d] = faces.subarray(f, f + 4);
    index.push(a, b, c, a, c, d);
    lines.push(a, b, b, c, c, d, d, a);
  }
  geometry.setIndex(index);
  surface.geometry.dispose();
  surface.geometry = geometry;
  const lineGeometry = new THREE.BufferGeometry();
  lineGeometry.setAttribute('position', geometry.getAttribute('position'));
  lineGeometry.setIndex(lines);
  edges.geometry.dispose();
  edges.geometry = lineGeometry;
  // Panel outlines help on small models and only cost drawing time on large ones.
  edges.visible = count <= 5000;
  updatePositions();
}

/// Evaluates the motion at the slider's t and uploads the positions.
function updatePositions() {
  const t = tOf(fraction);
  const positions = designer.evaluate(t);
  if (positions.ok === false) return;
  const attribute = surface.geometry.getAttribute('position');
  attribute.array.set(positions);
  attribute.needsUpdate = true;
  // (flat shading: the shader derives the normals, none to compute)
  surface.geometry.computeBoundingSphere();
  $('t').textContent = format(t);
}

// --- handles ---------------------------------------------------------------
const handleSize = () => 0.025 * info.model_size;
const materials = {
  trajectory: new THREE.MeshStandardMaterial({ color: 0xff9800 }),
  direction: new THREE.MeshStandardMaterial({ color: 0x42a5f5 }),
  apex: new THREE.MeshStandardMaterial({ color: 0x66bb6a }),
};

function apexHeights(p) {
  if (Array.isArray(p.apex_heights)) return { list: p.apex_heights, owner: p, key: 'apex_heights', field: 'apex_heights' };
  if (p.tube && Array.isArray(p.tube.apex_heights)) return { list: p.tube.apex_heights, owner: p.tube, key: 'apex_heights', field: 'tube.apex_heights' };
  return null;
}

function rebuildHandles() {
  handles.clear();
  const size = handleSize();
  const sphere = new THREE.SphereGeometry(size, 16, 12);
  const cube = new THREE.BoxGeometry(1.4 * size, 1.4 * size, 1.4 * size);
  if (Array.isArray(preset.trajectory)) {
    preset.trajectory.forEach((v, i) => {
      const h = new THREE.Mesh(sphere, materials.trajectory);
      h.position.set(...v);
      h.userData = { kind: 'trajectory', index: i };
      handles.add(h);
    });
  }
  if (Array.isArray(preset.directions) && Array.isArray(preset.trajectory)) {
    preset.directions.forEach((d, i) => {
      const dir = new THREE.Vector3(...d);
      if (dir.lengthSq() === 0 || !preset.trajectory[i]) return;
      const h = new THREE.Mesh(cube, materials.direction);
      h.position.set(...preset.trajectory[i]).addScaledVector(dir.normalize(), 0.12 * info.model_size);
      h.userData = { kind: 'direction', index: i };
      handles.add(h);
      const line = new THREE.Line(new THREE.BufferGeometry().setFromPoints([new THREE.Vector3(...preset.trajectory[i]), h.position.clone()]),
        new THREE.LineBasicMaterial({ color: 0x42a5f5 }));
      handles.add(line);
    });
  }
  const apexes = Float64Array.from(designer.apexes(info.t_star));
  const heights = apexHeights(preset);
  const points = [];
  for (let j = 0; j < apexes.length / 3; ++j) points.push(new THREE.Vector3(apexes[3 * j], apexes[3 * j + 1], apexes[3 * j + 2]));
  if (heights) {
    heights.list.forEach((_, j) => {
      if (!points[j]) return;
      const h = new THREE.Mesh(sphere, materials.apex);
      h.position.copy(points[j]);
      h.userData = { kind: 'apex', index: j };
      handles.add(h);
    });
  }
  if (points.length >= 2) {
    const a = axisOf(preset);
    const lo = Math.min(...points.map((p) => p.dot(a))), hi = Math.max(...points.map((p) => p.dot(a)));
    const base = points[0].clone().addScaledVector(a, -points[0].dot(a));
    axisLine.geometry.dispose();
    axisLine.geometry = new THREE.BufferGeometry().setFromPoints([base.clone().addScaledVector(a, lo - 0.2 * info.model_size),
                                                                  base.clone().addScaledVector(a, hi + 0.2 * info.model_size)]);
    axisLine.computeLineDistances();
  }
}

function handleOf(field) {
  const m = /^(trajectory|directions|apex_heights|tube\.apex_heights)\[(\d+)\]/.exec(field || '');
  if (!m) return null;
  const kind = m[1] === 'trajectory' ? 'trajectory' : m[1] === 'directions' ? 'direction' : 'apex';
  return handles.children.find((h) => h.userData.kind === kind && h.userData.index === Number(m[2])) || null;
}

function screenOf(object) {
  const p = object.getWorldPosition(new THREE.Vector3()).project(camera);
  const rect = renderer.domElement.getBoundingClientRect();
  return [rect.left + (p.x + 1) / 2 * rect.width, rect.top + (1 - p.y) / 2 * rect.height];
}

// --- messages and panel ----------------------------------------------------
function showMessage() {
  const message = $('message'), label = $('label');
  if (!failure) {
    message.textContent = 'valid';
    message.classList.remove('error');
    label.hidden = true;
    return;
  }
  const text = failure.field ? `${failure.field}: ${failure.message}` : failure.message;
  message.textContent = text;
  message.classList.add('error');
  const handle = handleOf(failure.field);
  if (handle) {
    const [x, y] = screenOf(handle);
    label.style.left = `${x + 12}px`;
    label.style.top = `${y - 10}px`;
    label.textContent = text;
    label.hidden = false;
  } else {
    label.hidden = true;
  }
}

function updatePanel() {
  $('title').textContent = info.name;
  $('kind').textContent = `${info.kind}, ${info.vertices} vertices, ${info.faces} panels`;
  $('lo').textContent = format(info.t_lambda);
  $('hi').textContent = format(info.t_mu);
  $('tstar').textContent = format(info.t_star);
  const star = (info.t_star - info.t_lambda) / (info.t_mu - info.t_lambda);
  $('tstarmark').style.marginLeft = `${Math.round(star * 100 - 50)}%`;
  $('json').value = JSON.stringify(preset, null, 2);
  $('mode').value = preset.grid ? 'grid' : preset.tube ? preset.tube.type : 'open';
  $('grid-size').hidden = !preset.grid;
  if (preset.grid) {
    $('cells-u').value = String(preset.grid.u_heights.length - 1);
    $('cells-w').value = String(preset.grid.w_heights.length - 1);
  }
  const signs = $('signs');
  signs.textContent = '';
  if (typeof preset.signs === 'string') {
    signs.append('signs ');
    [...preset.signs].forEach((s, k) => {
      const b = document.createElement('button');
      b.type = 'button';
      b.textContent = s;
      b.title = `sign of S_${k + 1}`;
      b.dataset.index = String(k);
      b.addEventListener('click', () => {
        const c = clone(preset);
        c.signs = c.signs.slice(0, k) + (s === '+' ? '-' : '+') + c.signs.slice(k + 1);
        apply(c);
      });
      signs.append(b);
    });
  }
}

let figuresTimer = null;
function scheduleFigures() {
  clearTimeout(figuresTimer);
  figuresTimer = setTimeout(() => {
    figures = designer.check(41);
    const closure = figures.closed ? `, closure ${format(figures.closure)}` : '';
    $('figures').textContent = `over the interval: planarity ${format(figures.planarity)}, isometry ${format(figures.isometry)}${closure} (of the model size)` +
      (figures.warning ? ` — ${figures.warning}` : '');
  }, 150);
}

// --- dragging ----------------------------------------------------------------
const raycaster = new THREE.Raycaster();
let drag = null;
let pending = null;

function rayAt(event) {
  const rect = renderer.domElement.getBoundingClientRect();
  const ndc = new THREE.Vector2(((event.clientX - rect.left) / rect.width) * 2 - 1, -((event.clientY - rect.top) / rect.height) * 2 + 1);
  raycaster.setFromCamera(ndc, camera);
  return raycaster.ray;
}

renderer.domElement.addEventListener('pointerdown', (event) => {
  rayAt(event);
  const hit = raycaster.intersectObjects(handles.children.filter((h) => h.isMesh), false)[0];
  if (!hit) return;
  const normal = camera.getWorldDirection(new THREE.Vector3());
  drag = { ...hit.object.userData, plane: new THREE.Plane().setFromNormalAndCoplanarPoint(normal, hit.object.position) };
  controls.enabled = false;
  renderer.domElement.setPointerCapture(event.pointerId);
});

renderer.domElement.addEventListener('pointermove', (event) => {
  if (!drag) return;
  const point = rayAt(event).intersectPlane(drag.plane, new THREE.Vector3());
  if (!point) return;
  pending = edited(drag, point);
});

renderer.domElement.addEventListener('pointerup', () => {
  if (!drag) return;
  drag = null;
  controls.enabled = true;
  if (pending) {
    applyEdit(pending);
    pending = null;
  }
  scheduleFigures();
});

/// The edit that puts the dragged handle at `point`: {key, index, value}.
function edited(handle, point) {
  const a = axisOf(preset);
  if (handle.kind === 'trajectory') return { key: 'trajectory', index: handle.index, value: point.toArray() };
  if (handle.kind === 'direction') {
    const d = point.clone().sub(new THREE.Vector3(...preset.trajectory[handle.index]));
    d.addScaledVector(a, -d.dot(a));  // directions stay orthogonal to the axis
    return { key: 'directions', index: handle.index, value: d.toArray() };
  }
  // The height is the coordinate along the axis.
  return { key: apexHeights(preset).field, index: handle.index, value: [point.dot(a), 0, 0] };
}

/// Applies one edit through the core without the round trip through JSON text
/// (the hot path while dragging); the topology does not change.
function applyEdit(edit) {
  const result = designer.set(edit.key, edit.index, ...edit.value);
  if (!result.ok) {
    failure = { field: result.field, message: result.message };
    showMessage();
    return false;
  }
  failure = null;
  if (edit.key === 'trajectory' || edit.key === 'directions') preset[edit.key][edit.index] = edit.value;
  else apexHeights(preset).list[edit.index] = edit.value[0];
  info = designer.info();
  updatePositions();
  rebuildHandles();
  updatePanel();
  showMessage();
  return true;
}

// --- controls --------------------------------------------------------------
$('slider').addEventListener('input', (e) => {
  fraction = Number(e.target.value) / 1000;
  updatePositions();
});

/// Grid heights: cell (0, 0) has apexes (z0, z1, z2, z3); every further line of a
/// family keeps the spacing of the first two.
function gridHeights(z, cellsU, cellsW) {
  const line = (a, b, count) => Array.from({ length: count + 1 }, (_, k) => a + k * (b - a));
  return { u_heights: line(z[0], z[2], cellsU), w_heights: line(z[1], z[3], cellsW) };
}

function cellZ(p) {
  if (p.grid) return [p.grid.u_heights[0], p.grid.w_heights[0], p.grid.u_heights[1], p.grid.w_heights[1]];
  const heights = apexHeights(p);
  return heights ? heights.list.slice() : [-1.5, 1.0, -0.5, 2.0];
}

for (const id of ['cells-u', 'cells-w']) {
  $(id).addEventListener('change', () => {
    if (!preset.grid) return;
    const c = clone(preset);
    c.grid = gridHeights(cellZ(c), Math.max(1, Number($('cells-u').value)), Math.max(1, Number($('cells-w').value)));
    apply(c);
  });
}

$('mode').addEventListener('change', (e) => {
  const c = clone(preset);
  const z = cellZ(c);
  delete c.grid;
  if (e.target.value === 'grid') {
    delete c.apex_heights;
    delete c.signs;
    delete c.tube;
    c.grid = gridHeights(z, Math.max(1, Number($('cells-u').value)), Math.max(1, Number($('cells-w').value)));
  } else if (e.target.value === 'open') {
    delete c.tube;
    c.apex_heights = z.length >= 5 ? z : [...z.slice(0, 4), z[0] + 1.3];
    c.signs = '+'.repeat(c.apex_heights.length - 2);
  } else {
    delete c.apex_heights;
    delete c.signs;
    const q = z.slice(0, 4);
    while (q.length < 4) q.push(q[q.length - 1] + 1);
    if (e.target.value === 'anti-parallelogram') q[3] = q[0] + q[2] - q[1];  // its symmetry condition
    c.tube = { type: e.target.value, apex_heights: q };
  }
  if (!apply(c)) e.target.value = preset.grid ? 'grid' : preset.tube ? preset.tube.type : 'open';
});

$('add-profile').addEventListener('click', () => {
  const c = clone(preset);
  const n = c.trajectory.length;
  const last = new THREE.Vector3(...c.trajectory[n - 1]), prev = new THREE.Vector3(...c.trajectory[n - 2]);
  c.trajectory.push(last.clone().add(last.clone().sub(prev)).toArray());
  c.directions.push(c.directions[n - 1].slice());
  apply(c);
});
$('remove-profile').addEventListener('click', () => {
  const c = clone(preset);
  if (c.trajectory.length <= 2) return;
  c.trajectory.pop();
  c.directions.pop();
  apply(c);
});
$('add-apex').addEventListener('click', () => {
  const c = clone(preset);
  if (!Array.isArray(c.apex_heights)) return;
  const h = c.apex_heights, n = h.length;
  h.push(h[n - 2] + 0.6 * (h[n - 2] - h[n - 3]));
  c.signs += '+';
  apply(c);
});
$('remove-apex').addEventListener('click', () => {
  const c = clone(preset);
  if (!Array.isArray(c.apex_heights) || c.apex_heights.length <= 3) return;
  c.apex_heights.pop();
  c.signs = c.signs.slice(0, -1);
  apply(c);
});
$('json').addEventListener('input', (e) => {
  try {
    apply(JSON.parse(e.target.value));
  } catch (error) {
    failure = { field: '', message: `preset JSON: ${error.message}` };
    showMessage();
  }
});

function download(name, data, type) {
  const url = URL.createObjectURL(new Blob([data], { type }));
  const a = document.createElement('a');
  a.href = url;
  a.download = name;
  a.click();
  setTimeout(() => URL.revokeObjectURL(url), 1000);
}
const presetText = () => JSON.stringify(preset, null, 2) + '\n';
$('save').addEventListener('click', () => download(`${preset.name || 'preset'}.json`, presetText(), 'application/json'));
$('load').addEventListener('change', async (e) => {
  const file = e.target.files[0];
  if (!file) return;
  try {
    apply(JSON.parse(await file.text()));
  } catch (error) {
    failure = { field: '', message: `${file.name}: ${error.message}` };
    showMessage();
  }
});
/// The animated .glb, written by the core as `phedra generate -o X.glb` writes it.
function glbBytes() {
  const bytes = designer.glb(false, false);
  if (bytes.ok === false) throw new Error(bytes.message);
  return Uint8Array.from(bytes);
}
$('export-glb').addEventListener('click', () => download(`${preset.name || 'phedra'}.glb`, glbBytes(), 'model/gltf-binary'));
$('export-fold').addEventListener('click', () => download(`${preset.name || 'phedra'}.fold`, designer.fold(41), 'application/json'));

// --- start -----------------------------------------------------------------
function frame() {
  if (pending) {
    const edit = pending;
    pending = null;
    if (applyEdit(edit) && !drag) scheduleFigures();
  }
  controls.update();
  renderer.render(scene, camera);
  requestAnimationFrame(frame);
}

const initial = await (await fetch('/preset.json')).json();
if (!apply(initial)) {
  $('message').textContent = `the preset is refused: ${failure.field}: ${failure.message}`;
}
if (info) {
  // Start at t*, where the handles (the input) lie on the surface.
  fraction = (info.t_star - info.t_lambda) / (info.t_mu - info.t_lambda);
  $('slider').value = String(Math.round(fraction * 1000));
  updatePositions();
  surface.geometry.computeBoundingSphere();
  const sphere = surface.geometry.boundingSphere;
  controls.target.copy(sphere.center);
  camera.position.copy(sphere.center).add(new THREE.Vector3(1.6, -2.2, 1.2).multiplyScalar(sphere.radius));
  camera.near = sphere.radius / 100;
  camera.far = sphere.radius * 100;
  camera.updateProjectionMatrix();
}
requestAnimationFrame(frame);

/// For tests and measurements.
window.phedraDesigner = {
  ready: info !== null,
  info: () => info,
  preset: () => clone(preset),
  presetText,
  message: () => $('message').textContent,
  labelText: () => ($('label').hidden ? '' : $('label').textContent),
  t: () => tOf(fraction),
  vertex: (k) => Array.from(surface.geometry.getAttribute('position').array.slice(3 * k, 3 * k + 3)),
  /// Every vertex at the slider's t in double precision, straight from the core.
  positions: () => Array.from(designer.evaluate(tOf(fraction))),
  handleScreen: (kind, index) => {
    const h = handles.children.find((x) => x.userData.kind === kind && x.userData.index === index);
    return h ? screenOf(h) : null;
  },
  apply: (p) => apply(p),
  figures: () => figures,
  glbSize: () => glbBytes().byteLength,
  fold: () => designer.fold(5),
  /// Times `runs` edits of trajectory point 1 (rebuild from the preset, evaluate,
  /// upload, render): milliseconds, median and worst, core alone and in all.
  measure(runs, draw = true) {
    const core = [], total = [];
    const start = clone(preset);
    for (let k = 0; k < runs; ++k) {
      const c = clone(start);
      c.trajectory[1] = c.trajectory[1].map((x, i) => x + (i === 2 ? 1e-3 * Math.sin(k) : 0));
      const t0 = performance.now();
      designer.load(JSON.stringify(c));
      info = designer.info();
      const positions = designer.evaluate(tOf(fraction));
      const t1 = performance.now();
      const attribute = surface.geometry.getAttribute('position');
      attribute.array.set(positions);
      attribute.needsUpdate = true;

      if (draw) {
        renderer.render(scene, camera);
        renderer.getContext().finish();
      }
      const t2 = performance.now();
      core.push(t1 - t0);
      total.push(t2 - t0);
    }
    designer.load(JSON.stringify(start));
    const stat = (a) => { const s = a.slice().sort((x, y) => x - y); return { median: s[s.length >> 1], worst: s[s.length - 1] }; };
    return { vertices: info.vertices, core: stat(core), total: stat(total) };
  },
};
