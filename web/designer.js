// phedra designer: edit a preset's control polylines in 3D and see the P-hedron
// fold, live. The geometry comes from the phedra core itself, compiled to
// WebAssembly (wasm/phedra.mjs, scripts/build-wasm.sh): every edit rebuilds the
// design from the preset exactly as `phedra` does, so the messages are the
// CLI's, and a saved preset gives the same `phedra sample` result.
import * as THREE from 'three';
import { createStage } from './scene.js';
import { clampToCore, frameBox, groundGrid, readableNumbers } from './framing.js';
import { foldAngle, foldColours, hingesOf } from './folds.js';
import createPhedra from './wasm/phedra.mjs';

const $ = (id) => document.getElementById(id);
const format = (x) => (Math.abs(x) < 1e-3 && x !== 0 ? x.toExponential(2) : x.toFixed(4));

// --- three.js scene --------------------------------------------------------
// No MSAA: it costs more than the whole motion update in a software-rendered browser.
const { renderer, scene, camera, controls } = createStage({ antialias: false });
camera.up.set(0, 0, 1);  // presets are z-up

// Lambert: the matte look of a rough standard material at a fraction of its cost per pixel.
// Panels by validity (docs/design.md, Buildable designs): simple, not simple
// (a bow-tie or degenerate: cannot be cut as one plate), penetrating another
// panel (or folded through its hinge) at the slider's t.
const validityColours = { simple: 0x7fb3e0, invalid: 0xe53935, colliding: 0xff9800 };
const surface = new THREE.Mesh(new THREE.BufferGeometry(), ['simple', 'invalid', 'colliding'].map((k) =>
  // Pushed back a little in depth, so that the panel edges and fold lines drawn on them do not flicker.
  new THREE.MeshLambertMaterial({ color: validityColours[k], side: THREE.DoubleSide, flatShading: true,
                                  polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1 })));
// Without depth writes: the fold lines drawn after them cover them instead of fighting them pixel by pixel.
const edges = new THREE.LineSegments(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: 0x20303f, depthWrite: false }));
scene.add(surface, edges);
const handles = new THREE.Group();
scene.add(handles);
const axisLine = new THREE.Line(new THREE.BufferGeometry(), new THREE.LineDashedMaterial({ color: 0x66bb6a, dashSize: 0.1, gapSize: 0.06 }));
scene.add(axisLine);

// Drawn on demand: a frame is rendered only after something changed (an edit, the
// slider, the camera, the window), so an idle page costs nothing.
let needsRender = true;
const requestRender = () => { needsRender = true; };
controls.addEventListener('change', requestRender);
window.addEventListener('resize', requestRender);

// --- drag resolution ---------------------------------------------------------
// A renderer too slow to redraw the model at full resolution within a 60 Hz
// frame (software WebGL, weak GPUs) draws it at a lower resolution while a
// handle is dragged, sharp again when the hand stops. The full-resolution draw
// is timed once a model (a pixel read back waits for the rasterizer); a GPU
// that draws the model within the frame never sees a lower resolution.
const frameBudget = 1000 / 60;
const minimumDragRatio = 0.35;
let drawCost = null;      // ms of a draw at resolution fraction r: {fixed, fill} with cost = fixed + fill r^2; null until timed
let calibrate = true;     // time the next draws
let stepCost = 2;         // ms: the main-thread work of a drag step (running estimate)
let dragRatio = 1;        // the fraction of the resolution while dragging
const pixel = new Uint8Array(4);

/// Renders and waits for the rasterizer (reads a pixel back): milliseconds.
function timedDraw() {
  const gl = renderer.getContext();
  const t0 = performance.now();
  renderer.render(scene, camera);
  gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
  return performance.now() - t0;
}

/// Times a draw at full and at half resolution: what goes with the pixels (fill)
/// and what does not (vertices, the pipeline).
function calibrateDraw() {
  const full = timedDraw();
  renderer.setPixelRatio(window.devicePixelRatio * 0.5);
  timedDraw();  // the first draw at a new size allocates
  const half = timedDraw();
  renderer.setPixelRatio(window.devicePixelRatio);
  renderer.render(scene, camera);  // resizing cleared the canvas
  const fill = Math.max(0, (full - half) / 0.75);
  drawCost = { fixed: Math.max(0, full - fill), fill };
}

/// The fraction of the resolution at which a drag frame fits in a 60 Hz frame.
function chooseDragRatio() {
  const budget = frameBudget - stepCost - 2;  // 2 ms for the browser's own work
  if (drawCost === null || drawCost.fixed + drawCost.fill <= budget) return 1;
  const room = budget - drawCost.fixed;
  return room <= 0 || drawCost.fill === 0 ? minimumDragRatio : Math.min(1, Math.max(minimumDragRatio, Math.sqrt(room / drawCost.fill)));
}

function beginDrag() {
  dragRatio = chooseDragRatio();
  if (dragRatio < 1) renderer.setPixelRatio(window.devicePixelRatio * dragRatio);
  requestRender();
}

function endDrag() {
  if (dragRatio < 1) renderer.setPixelRatio(window.devicePixelRatio);
  dragRatio = 1;
  requestRender();
}
window.addEventListener('resize', () => { calibrate = true; });

// --- the core --------------------------------------------------------------
const core = await createPhedra();
const designer = new core.Designer();
let preset = null;          // the preset shown (always valid)
let info = null;            // designer.info() of it
let fraction = 0.5;         // slider position in [0, 1]
let faces = null;           // Uint32Array of quads
let failure = null;         // the last refused edit: {field, message}
let figures = null;
let invalidPanels = new Set();    // not simple (the shape is a constant of the design)
let collidingPanels = new Set();  // penetrating at the slider's t
let buildability = null;          // designer.buildability(...) of the shown design (null while it is computed)

const clone = (o) => JSON.parse(JSON.stringify(o));
const axisOf = (p) => new THREE.Vector3(...(p.axis || [0, 0, 1])).normalize();
const tOf = (f) => info.t_lambda + f * (info.t_mu - info.t_lambda);

/// Rebuilds the design from `candidate`; on refusal keeps the shown design and
/// reports. An accepted edit goes into the undo history (`what` says what it
/// was) and the slider moves to the new t*, where the surface passes through the handles.
function apply(candidate, { keepFigures = false, what = 'edit', record = true } = {}) {
  const result = designer.load(JSON.stringify(candidate));
  if (!result.ok) {
    failure = { field: result.field, message: result.message };
    showMessage();
    return false;
  }
  failure = null;
  if (record && preset) remember(preset, what);
  const before = info ? info.t_star : null;
  preset = candidate;
  showRepair('');  // a new design: an earlier repair's message no longer applies (Repair and Undo say theirs after)
  info = designer.info();
  faces = Uint32Array.from(designer.faces());
  invalidPanels = new Set(Array.from(designer.invalidPanels()));
  collidingPanels = new Set();
  followTStar(before);
  sizeHandles();
  rebuildGeometry();
  placeHandles();
  updatePanel();
  calibrate = true;
  if (!keepFigures) scheduleFigures();
  showMessage();
  if (framed) refitIfOutside();
  return true;
}

/// The slider at t* (the input configuration: the surface passes through the
/// handles); `before`: t* of the previous design, to say when an edit moved it and why.
function followTStar(before) {
  fraction = (info.t_star - info.t_lambda) / (info.t_mu - info.t_lambda);
  $('slider').value = String(Math.round(fraction * 1000));
  const moved = before !== null && Math.abs(before - info.t_star) > 1e-12 * info.model_size;
  if (moved) {
    $('tstar-note').textContent = `t* moved from ${format(before)} to ${format(info.t_star)}: t is the axis coordinate ` +
      `of the moving apex ${info.moving_apex}, and this edit moved it`;
  } else if (before !== null) {
    $('tstar-note').textContent = '';
  }
}

// --- the view ------------------------------------------------------------------
/// Everything the design shows over its whole motion (the surface at 9 t across
/// the flexion interval), or at the slider's t only (`motion` false), and the handles.
function designBox(motion = true) {
  const v = new THREE.Vector3();
  const surfaceAt = (fractions, box) => {
    for (const f of fractions) {
      const x = designer.evaluate(tOf(f));
      if (x.ok === false) continue;
      for (let i = 0; i + 2 < x.length; i += 3) box.expandByPoint(v.set(x[i], x[i + 1], x[i + 2]));
    }
    return box;
  };
  const core = surfaceAt([fraction], new THREE.Box3());
  for (const mesh of Object.values(handleMeshes)) {
    const m = new THREE.Matrix4();
    for (let k = 0; k < mesh.count; ++k) {
      mesh.getMatrixAt(k, m);
      core.expandByPoint(v.setFromMatrixPosition(m));
    }
  }
  if (!motion) return core;
  // Over the motion, but not out to where a vertex passes near infinity.
  return clampToCore(surfaceAt([0, 1, 2, 3, 4, 5, 6, 7, 8].map((k) => k / 8), core.clone()), core);
}
/// Frames the design over its motion (Fit view, f), or as shown at the slider's
/// t (Fit t, Shift+F: larger, for editing), in the part of the canvas the panel leaves free.
let framed = false;  // the first framing happened
let ground = [];     // the ground grid and the axes, placed under the whole motion at each Fit view
function fitView({ motion = true } = {}) {
  framed = true;
  const canvas = renderer.domElement, panel = $('panel').getBoundingClientRect();
  const box = designBox(motion);
  if (motion && !box.isEmpty()) {
    scene.remove(...ground);
    const { grid, cell } = groundGrid(box, 'z');
    const axes = new THREE.AxesHelper(cell).translateX(box.min.x).translateY(box.min.y).translateZ(box.min.z);
    ground = [grid, axes];
    scene.add(...ground);
    $('scale').textContent = `grid cells of ${Number(cell.toPrecision(6))} model units; axes x red, y green, z (up) blue, one cell long`;
  }
  frameBox(camera, controls, box, { left: panel.right + 8, width: canvas.clientWidth, height: canvas.clientHeight });
  requestRender();
}
/// Refits when an edit took the shown surface out of the view, or left it a
/// speck in it (under a twentieth of the view each way: another design loaded
/// into a view framed for a much larger one); never while dragging.
function refitIfOutside() {
  if (drag || !framed) return;
  surface.geometry.computeBoundingBox();
  const b = surface.geometry.boundingBox, corner = new THREE.Vector3();
  const seen = new THREE.Box2();
  for (const x of [b.min.x, b.max.x]) for (const y of [b.min.y, b.max.y]) for (const z of [b.min.z, b.max.z]) {
    corner.set(x, y, z).project(camera);
    if (Math.abs(corner.x) > 1 || Math.abs(corner.y) > 1 || corner.z > 1) { fitView(); return; }
    seen.expandByPoint(new THREE.Vector2(corner.x, corner.y));
  }
  const size = seen.getSize(new THREE.Vector2());
  if (size.x < 0.1 && size.y < 0.1) fitView();
}
window.addEventListener('keydown', (e) => {
  if (e.target instanceof HTMLTextAreaElement || e.target instanceof HTMLInputElement) return;
  if (e.key === 'f') fitView();
  else if (e.key === 'F') fitView({ motion: false });
});
window.addEventListener('resize', () => { if (info) fitView(); });

// --- undo and redo ---------------------------------------------------------------
// Every accepted edit (a drag counts once, from press to release), repairs and
// mode switches included: [{preset, what}].
const history = [], future = [];
let loadedName = null;  // the name of the preset as loaded, to say what an edited design came from
function remember(previous, what) {
  history.push({ preset: clone(previous), what, origin: loadedName });
  if (history.length > 500) history.shift();
  future.length = 0;
  updateUndo();
}
function updateUndo() {
  $('undo').disabled = history.length === 0;
  $('redo').disabled = future.length === 0;
  $('undo').title = history.length ? `undo the last ${history[history.length - 1].what} (Ctrl+Z)` : 'nothing to undo';
  $('redo').title = future.length ? `redo the ${future[future.length - 1].what} (Ctrl+Shift+Z)` : 'nothing to redo';
}
/// Moves one design from the `from` stack to the `to` stack (undo: history ->
/// future; redo: the other way) and shows it; `verb` says which it was.
function travel(from, to, verb) {
  const entry = from.pop();
  if (!entry) return;
  const now = clone(preset);
  if (apply(entry.preset, { record: false })) {
    to.push({ preset: now, what: entry.what, origin: loadedName });
    loadedName = entry.origin;
    showRepair(entry.what === 'repair' && verb === 'undone' ? 'repair undone: the previous design is back' : `${entry.what} ${verb}`);
  } else {
    from.push(entry);
  }
  updateUndo();
}
const undo = () => travel(history, future, 'undone');
const redo = () => travel(future, history, 'redone');
window.addEventListener('keydown', (e) => {
  if (!(e.ctrlKey || e.metaKey) || e.target instanceof HTMLTextAreaElement || e.target instanceof HTMLInputElement) return;
  const key = e.key.toLowerCase();
  if (key === 'z' && !e.shiftKey) { e.preventDefault(); undo(); }
  else if ((key === 'z' && e.shiftKey) || key === 'y') { e.preventDefault(); redo(); }
});

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
  colourPanels();
  const lineGeometry = new THREE.BufferGeometry();
  lineGeometry.setAttribute('position', geometry.getAttribute('position'));
  lineGeometry.setIndex(lines);
  edges.geometry.dispose();
  edges.geometry = lineGeometry;
  // Panel outlines help on small models and only cost drawing time on large ones.
  edges.visible = count <= 5000;
  // Mountain and valley hinges, coloured by their fold at the slider's t (outlined models only).
  const panels = [];
  for (let f = 0; f < faces.length; f += 4) panels.push(Array.from(faces.subarray(f, f + 4)));
  hinges = edges.visible ? hingesOf(panels) : [];
  hingePanels = panels;
  hingeSigns = new Int8Array(hinges.length);
  for (const line of [mountainLines, valleyLines]) {
    line.geometry.dispose();
    line.geometry = new THREE.BufferGeometry();
    line.geometry.setAttribute('position', geometry.getAttribute('position'));
    line.geometry.setIndex([]);
  }
  updatePositions();
}

let hinges = [], hingePanels = [], hingeSigns = new Int8Array(0);
const foldLine = (colour) => {
  const line = new THREE.LineSegments(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: colour, depthFunc: THREE.LessEqualDepth }));
  line.renderOrder = 1;
  scene.add(line);
  return line;
};
const mountainLines = foldLine(foldColours.mountain), valleyLines = foldLine(foldColours.valley);
/// The hinges' mountain/valley colours at positions x; the index buffers change only when a sign does.
function colourFolds(x) {
  let changed = false, mountains = 0, valleys = 0;
  hinges.forEach((h, k) => {
    const angle = foldAngle(hingePanels[h.f], hingePanels[h.g], h.from, h.to, x);
    const sign = Math.abs(angle) < 1e-6 ? 0 : angle > 0 ? 1 : -1;
    if (sign !== hingeSigns[k]) { hingeSigns[k] = sign; changed = true; }
    if (sign < 0) ++mountains; else if (sign > 0) ++valleys;
  });
  if (changed) {
    const m = [], v = [];
    hinges.forEach((h, k) => { if (hingeSigns[k] < 0) m.push(h.from, h.to); else if (hingeSigns[k] > 0) v.push(h.from, h.to); });
    mountainLines.geometry.setIndex(m);
    valleyLines.geometry.setIndex(v);
  }
  foldCounts = { mountains, valleys };
}
let foldCounts = { mountains: 0, valleys: 0 };

/// Evaluates the motion at the slider's t and uploads the positions.
function updatePositions() {
  const t = tOf(fraction);
  const positions = designer.evaluate(t);
  if (positions.ok === false) return;
  const attribute = surface.geometry.getAttribute('position');
  attribute.array.set(positions);
  attribute.needsUpdate = true;
  if (hinges.length) colourFolds(positions);
  // (flat shading: the shader derives the normals, none to compute)
  surface.geometry.computeBoundingSphere();
  $('t').textContent = format(t);
  requestRender();
}

/// Orders the triangles by validity (simple, not simple, colliding) and gives
/// each range its material: one draw call a colour.
function colourPanels() {
  const geometry = surface.geometry;
  if (!faces) return;
  const order = [[], [], []];
  for (let f = 0; f < faces.length / 4; ++f) {
    const kind = collidingPanels.has(f) ? 2 : invalidPanels.has(f) ? 1 : 0;
    const [a, b, c, d] = faces.subarray(4 * f, 4 * f + 4);
    order[kind].push(a, b, c, a, c, d);
  }
  geometry.setIndex([...order[0], ...order[1], ...order[2]]);
  geometry.clearGroups();
  let start = 0;
  order.forEach((list, k) => {
    if (list.length) geometry.addGroup(start, list.length, k);
    start += list.length;
  });
  requestRender();
}

const sameSet = (a, b) => a.size === b.size && [...a].every((x) => b.has(x));

/// The panels that are not simple, from the core (cheap: every drag step).
function updateInvalidPanels() {
  const list = designer.invalidPanels();
  const next = new Set(list.ok === false ? [] : Array.from(list));
  if (!sameSet(next, invalidPanels)) {
    invalidPanels = next;
    colourPanels();
  }
}

/// The panels that collide at the slider's t (after the slider or an edit settles).
let collisionTimer = null;
function scheduleCollisions() {
  clearTimeout(collisionTimer);
  collisionTimer = setTimeout(() => {
    const list = designer.collisions(tOf(fraction));
    const next = new Set(list.ok === false ? [] : Array.from(list));
    if (!sameSet(next, collidingPanels)) {
      collidingPanels = next;
      colourPanels();
    }
  }, 60);
}

// --- handles ---------------------------------------------------------------
// One instanced mesh a kind (a draw call each, however many profiles) and one
// line set for the direction stems: a drag moves instances, it creates nothing.
// A fortieth of the model, smaller where the profiles are closer (a handle a profile).
let handleSize = () => 0.025 * info.model_size;

/// Sizes the handles for the shown preset: at most a third of the median trajectory segment.
function sizeHandles() {
  const t = Array.isArray(preset.trajectory) ? preset.trajectory : [];
  const lengths = t.slice(1).map((v, i) => Math.hypot(...v.map((x, k) => x - t[i][k]))).sort((a, b) => a - b);
  const spacing = lengths.length ? lengths[lengths.length >> 1] / 3 : Infinity;
  const size = Math.min(0.025 * info.model_size, spacing);
  handleSize = () => size;
}
const handleKinds = ['trajectory', 'direction', 'apex'];
const handleColours = { trajectory: 0xff9800, direction: 0x42a5f5, apex: 0x66bb6a };
const arrayHeightColour = 0xba68c8;  // heights of further members (grid u lines, row, couplings)
const wHeightColour = 0x4dd0e1;      // a grid's w lines
// kind -> THREE.InstancedMesh; userData.refs[instance] = {key, index}: what Designer.set edits
const handleMeshes = {};
const stems = new THREE.LineSegments(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: 0x42a5f5 }));
handles.add(stems);

/// The apex heights of the base member (open P-hedron or tube), or null (grid).
function baseHeights(p) {
  if (Array.isArray(p.apex_heights)) return p.apex_heights;
  if (p.tube && Array.isArray(p.tube.apex_heights)) return p.tube.apex_heights;
  return null;
}

/// Every height of the preset, an axis coordinate each: [{key, index, value, base}]
/// (`key` a dotted path for Designer.set; index -1: the number itself).
function heightRefs(p) {
  const refs = [];
  const list = (key, values, base) => {
    if (Array.isArray(values)) values.forEach((value, index) => { if (typeof value === 'number') refs.push({ key, index, value, base }); });
  };
  list('apex_heights', p.apex_heights, true);
  if (p.tube) list('tube.apex_heights', p.tube.apex_heights, true);
  if (p.grid) {
    list('grid.u_heights', p.grid.u_heights, false);
    list('grid.w_heights', p.grid.w_heights, false);
  }
  if (p.row) list('row.free_heights', p.row.free_heights, false);
  if (Array.isArray(p.couplings)) {
    p.couplings.forEach((c, k) => {
      if (!c || typeof c !== 'object') return;
      list(`couplings.${k}.free_heights`, c.free_heights, false);
      if (typeof c.free_height === 'number') refs.push({ key: `couplings.${k}.free_height`, index: -1, value: c.free_height, base: false });
    });
  }
  return refs;
}

/// The preset's field name of a handle, as the core's messages write it: "grid.u_heights[2]".
const fieldOf = (ref) => ref.key.replace(/\.(\d+)/g, '[$1]') + (ref.index >= 0 ? `[${ref.index}]` : '');

/// Sets what handle `ref` edits in preset `p` (the value the core accepted).
function setAt(p, ref, value) {
  const parts = ref.key.split('.');
  if (ref.index < 0) {
    const last = parts.pop();
    parts.reduce((o, k) => o[k], p)[last] = value;
  } else {
    parts.reduce((o, k) => o[k], p)[ref.index] = value;
  }
}

/// Where every handle is: {kind: [{key, index, position, colour}]}, the direction stems, and the apex line.
function handlePlaces() {
  const places = { trajectory: [], direction: [], apex: [] };
  const stemPoints = [];
  const trajectory = Array.isArray(preset.trajectory) ? preset.trajectory : [];
  trajectory.forEach((v, i) => places.trajectory.push({ key: 'trajectory', index: i, position: new THREE.Vector3(...v) }));
  if (Array.isArray(preset.directions)) {
    preset.directions.forEach((d, i) => {
      const dir = new THREE.Vector3(...d);
      if (dir.lengthSq() === 0 || !trajectory[i]) return;
      const foot = new THREE.Vector3(...trajectory[i]);
      const position = foot.clone().addScaledVector(dir.normalize(), 0.12 * info.model_size);
      places.direction.push({ key: 'directions', index: i, position });
      stemPoints.push(foot, position);
    });
  }
  // Every height is an axis coordinate on the apex line, which the apexes of the base show.
  const apexes = designer.apexes(info.t_star);
  const a = axisOf(preset);
  const first = apexes.length >= 3 ? new THREE.Vector3(apexes[0], apexes[1], apexes[2]) : null;
  const foot = first ? first.clone().addScaledVector(a, -first.dot(a)) : null;
  const heights = [];
  if (foot) {
    for (const ref of heightRefs(preset)) {
      places.apex.push({ key: ref.key, index: ref.index, position: foot.clone().addScaledVector(a, ref.value),
                         colour: ref.base ? handleColours.apex : ref.key === 'grid.w_heights' ? wHeightColour : arrayHeightColour });
      heights.push(ref.value);
    }
    for (let j = 0; j < apexes.length / 3; ++j) heights.push(new THREE.Vector3(apexes[3 * j], apexes[3 * j + 1], apexes[3 * j + 2]).dot(a));
  }
  return { places, stemPoints, apexLine: foot ? { foot, axis: a, lo: Math.min(...heights), hi: Math.max(...heights) } : null };
}

function handleGeometry(kind, count) {
  // Many handles (a handle a profile of a long model) are drawn as octahedra: 8
  // triangles each instead of 192 (what a software renderer pays for the most).
  if (count > 200) return new THREE.OctahedronGeometry(kind === 'direction' ? 1.2 : 1);
  return kind === 'direction' ? new THREE.BoxGeometry(1.4, 1.4, 1.4) : new THREE.SphereGeometry(1, 16, 12);
}

/// Puts the handles where the preset says; rebuilds an instanced mesh only when its count changes.
function placeHandles() {
  const { places, stemPoints, apexLine } = handlePlaces();
  const size = handleSize();
  const matrix = new THREE.Matrix4();
  const colour = new THREE.Color();
  for (const kind of handleKinds) {
    const list = places[kind];
    let mesh = handleMeshes[kind];
    if (!mesh || mesh.count !== list.length) {
      if (mesh) {
        handles.remove(mesh);
        mesh.geometry.dispose();
        mesh.dispose();
      }
      // Drawn over the surface: a handle behind it can still be seen and grabbed.
      const material = new THREE.MeshStandardMaterial({ color: kind === 'apex' ? 0xffffff : handleColours[kind], depthTest: false });
      mesh = new THREE.InstancedMesh(handleGeometry(kind, list.length), material, list.length);
      mesh.userData.kind = kind;
      mesh.renderOrder = 10;
      handleMeshes[kind] = mesh;
      handles.add(mesh);
    }
    mesh.userData.refs = list.map((h) => ({ key: h.key, index: h.index }));
    list.forEach((h, k) => {
      mesh.setMatrixAt(k, matrix.makeScale(size, size, size).setPosition(h.position));
      if (h.colour !== undefined) mesh.setColorAt(k, colour.setHex(h.colour));
    });
    mesh.instanceMatrix.needsUpdate = true;
    requestRender();
    if (mesh.instanceColor) mesh.instanceColor.needsUpdate = true;
    mesh.computeBoundingSphere();
  }
  const stemPositions = stems.geometry.getAttribute('position');
  if (!stemPositions || stemPositions.count !== stemPoints.length) {
    stems.geometry.dispose();
    stems.geometry = new THREE.BufferGeometry().setFromPoints(stemPoints);
  } else {
    stemPoints.forEach((p, k) => stemPositions.setXYZ(k, p.x, p.y, p.z));
    stemPositions.needsUpdate = true;
    stems.geometry.computeBoundingSphere();
  }
  if (apexLine) {
    const { foot, axis, lo, hi } = apexLine;
    axisLine.geometry.dispose();
    axisLine.geometry = new THREE.BufferGeometry().setFromPoints([foot.clone().addScaledVector(axis, lo - 0.2 * info.model_size),
                                                                  foot.clone().addScaledVector(axis, hi + 0.2 * info.model_size)]);
    axisLine.computeLineDistances();
  }
}

/// The handle that edits `key` (a Designer.set path) entry `index`: {kind, instance} or null.
function findHandle(key, index) {
  for (const kind of handleKinds) {
    const mesh = handleMeshes[kind];
    const k = mesh ? mesh.userData.refs.findIndex((r) => r.key === key && r.index === index) : -1;
    if (k >= 0) return { kind, instance: k };
  }
  return null;
}

/// The position of the handle that edits `key` entry `index`, or null.
function handlePosition(key, index) {
  const found = findHandle(key, index);
  if (!found) return null;
  const matrix = new THREE.Matrix4();
  handleMeshes[found.kind].getMatrixAt(found.instance, matrix);
  return new THREE.Vector3().setFromMatrixPosition(matrix);
}

/// The position of the handle a message of the core names ("directions[2]: ..."), or null.
function handleOf(field) {
  if (!field) return null;
  for (const kind of handleKinds) {
    for (const ref of handleMeshes[kind]?.userData.refs ?? []) {
      const f = fieldOf(ref);
      if (field === f || field.startsWith(f + '.') || field.startsWith(f + '[') || field.startsWith(f + ',')) return handlePosition(ref.key, ref.index);
    }
  }
  return null;
}

function screenOf(position) {
  const p = position.clone().project(camera);
  const rect = renderer.domElement.getBoundingClientRect();
  return [rect.left + (p.x + 1) / 2 * rect.width, rect.top + (1 - p.y) / 2 * rect.height];
}

// --- messages and panel ----------------------------------------------------
/// The status when the last edit was accepted: what the buildability report
/// says ("buildable over [a, b]", or what is wrong), never just "valid".
function statusText() {
  if (buildability) return readableNumbers(buildability.summary);
  if (invalidPanels.size) {
    const list = [...invalidPanels].slice(0, 8).join(', ') + (invalidPanels.size > 8 ? ', …' : '');
    return `not buildable: ${invalidPanels.size} of ${info.faces} panels cannot be cut as one plate (panels ${list})`;
  }
  return 'every panel is simple; checking the motion for collisions…';
}

function showMessage() {
  const message = $('message'), label = $('label');
  if (!failure) {
    message.textContent = statusText();
    message.classList.remove('error');
    message.classList.toggle('buildable', Boolean(buildability && buildability.buildable));
    message.classList.toggle('unbuildable', Boolean(invalidPanels.size || (buildability && !buildability.buildable)));
    label.hidden = true;
    return;
  }
  message.classList.remove('buildable', 'unbuildable');
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

/// The figures of the design: name, kind, counts, the interval and t*.
function updateLabels() {
  $('title').textContent = info.name;
  $('kind').textContent = `${info.kind}, ${info.vertices} vertices, ${info.faces} panels`;
  $('lo').textContent = format(info.t_lambda);
  $('hi').textContent = format(info.t_mu);
  $('tstar').textContent = format(info.t_star);
  const star = (info.t_star - info.t_lambda) / (info.t_mu - info.t_lambda);
  $('tstarmark').style.left = `calc(8px + ${star.toFixed(4)} * (100% - 16px))`;
  const ticks = $('tstarmark').parentElement;
  ticks.classList.remove('crowded');
  const mark = $('tstarmark').getBoundingClientRect();
  const overlaps = (r) => r.left < mark.right + 4 && mark.left < r.right + 4;
  if (overlaps($('lo').getBoundingClientRect()) || overlaps($('hi').getBoundingClientRect())) ticks.classList.add('crowded');
}

/// Everything the panel shows: the labels, the preset's text, mode and signs.
function updatePanel() {
  updateLabels();
  $('json').value = JSON.stringify(preset, null, 2);
  $('mode').value = modeOf(preset);
  $('grid-size').hidden = !preset.grid;
  if (preset.grid) {
    $('cells-u').value = String(preset.grid.u_heights.length - 1);
    $('cells-w').value = String(preset.grid.w_heights.length - 1);
  }
  $('row-size').hidden = !preset.row;
  if (preset.row) {
    $('row-cells').value = String(preset.row.free_heights.length);
    $('row-side').value = String(preset.row.side);
  }
  // Controls only where they act: apexes are added and removed on open designs.
  const open = Array.isArray(preset.apex_heights);
  $('add-apex').hidden = $('remove-apex').hidden = !open;
  $('remove-apex').disabled = open && preset.apex_heights.length <= 3;
  $('remove-profile').disabled = preset.trajectory.length <= 2;
  if (document.activeElement !== $('name')) $('name').value = preset.name ?? '';
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

/// The buildable part of the interval on the bar under the slider, and why not.
function showBuildability() {
  const bar = $('buildable-part');
  const range = info.t_mu - info.t_lambda;
  const b = buildability;
  if (b && b.interval && range > 0) {
    bar.hidden = false;
    bar.style.left = `${(100 * (b.interval[0] - info.t_lambda)) / range}%`;
    bar.style.width = `${Math.max(0.5, (100 * (b.interval[1] - b.interval[0])) / range)}%`;
    bar.title = `buildable over [${format(b.interval[0])}, ${format(b.interval[1])}]`;
  } else {
    bar.hidden = true;
  }
  const why = $('why'), list = $('why-list');
  list.textContent = '';
  const invalid = b ? b.invalid : [];
  why.hidden = invalid.length === 0;
  $('why-count').textContent = `${invalid.length} panel${invalid.length === 1 ? '' : 's'} cannot be cut as one plate: why, and what to change`;
  for (const p of invalid.slice(0, 12)) {
    const item = document.createElement('li');
    item.textContent = `panel ${p.panel} (${p.shape}): ${p.why}`;
    for (const h of p.hints) {
      const hint = document.createElement('div');
      hint.className = 'change';
      hint.textContent = `change: ${h}`;
      item.append(hint);
    }
    list.append(item);
  }
  if (invalid.length > 12) {
    const more = document.createElement('li');
    more.textContent = `… and ${invalid.length - 12} more (phedra check --json lists them all)`;
    list.append(more);
  }
}

let figuresTimer = null;
function scheduleFigures() {
  clearTimeout(figuresTimer);
  buildability = null;
  showBuildability();
  showMessage();
  figuresTimer = setTimeout(() => {
    // The sweep's samples a side: the command's (0: 200 up to 2000 panels), fewer on
    // larger models (the summary says when it was coarser than 200).
    buildability = designer.buildability(true, info.faces <= 2000 ? 0 : Math.max(8, Math.round(200000 / info.faces)), 8);
    if (buildability.ok === false) buildability = null;
    if (keepHeld && buildability && !buildability.buildable && keepBuildable()) {
      const fixed = [keepHeld];
      keepHeld = null;
      repairDesign({ fixed });  // the motion too, the held handle where the hand left it
    }
    keepHeld = null;
    showBuildability();
    showMessage();
    scheduleCollisions();
    figures = designer.check(41);
    const closure = figures.closed ? `, closure ${format(figures.closure)}` : '';
    $('figures').textContent = `over the interval: planarity ${format(figures.planarity)}, isometry ${format(figures.isometry)}${closure} (of the model size)` +
      (figures.warning ? ` — ${figures.warning}` : '');
  }, 150);
}

// --- repair (issue 14) ---------------------------------------------------------
// The nearest buildable design, found by the same core as `phedra repair`
// (NLopt compiled to WebAssembly). The search runs on this thread: the status
// says so first. Its result replaces the design; Undo brings the previous back.
const repairSeconds = 10;

function showRepair(text, changes = []) {
  const result = $('repair-result'), list = $('repair-list');
  result.hidden = !text;
  result.textContent = text;
  list.textContent = '';
  $('repair-changes').hidden = changes.length === 0;
  for (const c of changes) {
    const item = document.createElement('li');
    const what = c.field.startsWith('directions') ? `turned ${format(c.change)} degrees`
      : `${c.change >= 0 ? '+' : ''}${format(c.change)}, ${format(c.relative)} of the model size`;
    item.textContent = `${c.field}: ${c.before} → ${c.after} (${what})`;
    list.append(item);
  }
}

/// `fixed`: preset fields (JSON pointers) that stay, e.g. the handle a keep-buildable drag held.
function repairDesign({ fixed = [] } = {}) {
  $('repair').disabled = true;
  showRepair(`repairing: searching the nearest buildable design (up to ${repairSeconds} s)…`);
  // Two frames, so that the status is on screen before the search holds the thread.
  requestAnimationFrame(() => requestAnimationFrame(() => {
    const r = designer.repair(JSON.stringify({ max_seconds: repairSeconds, fixed }));
    $('repair').disabled = false;
    if (!r.ok) {
      showRepair(`repair refused: ${r.field ? `${r.field}: ` : ''}${r.message}`);
    } else if (r.already_buildable) {
      showRepair('already buildable over the whole flexion interval: nothing to repair');
    } else if (!r.found) {
      showRepair(`no buildable design found in ${format(r.seconds)} s: ${r.closest}`);
    } else {
      if (apply(JSON.parse(r.preset), { what: 'repair' })) {
        const part = r.fraction >= 1 ? '' : ` (over ${Math.round(100 * r.fraction)} % of the way from t* to the limits: the widest part found)`;
        showRepair(`repaired${part}: ${r.changes.length} field${r.changes.length === 1 ? '' : 's'} changed, distance ` +
          `${format(r.distance)} of the model size, ${r.evaluations} designs in ${format(r.seconds)} s. Undo brings the previous design back.`, r.changes);
      }
    }
  }));
}

$('repair').addEventListener('click', () => repairDesign());
$('undo').addEventListener('click', undo);
$('redo').addEventListener('click', redo);

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
  // Of the handles under the pointer (they overlap where heights are close),
  // the one whose centre is nearest the pointer on screen, not the nearest in depth.
  const hits = raycaster.intersectObjects(Object.values(handleMeshes), false);
  if (!hits.length) return;
  const onScreen = (h) => {
    const { key, index } = h.object.userData.refs[h.instanceId];
    const [x, y] = screenOf(handlePosition(key, index));
    return Math.hypot(x - event.clientX, y - event.clientY);
  };
  const hit = hits.reduce((best, h) => (onScreen(h) < onScreen(best) ? h : best));
  const { key, index } = hit.object.userData.refs[hit.instanceId];
  const kind = hit.object.userData.kind;
  const at = handlePosition(key, index);
  const a = axisOf(preset);
  // Where the pointer puts the handle: an apex moves along the apex line (the
  // point of it nearest the pointer's ray), a direction handle in the plane of
  // its profile's directions (orthogonal to the axis) unless that plane is seen
  // edge-on, everything else in the plane facing the camera.
  const facing = camera.getWorldDirection(new THREE.Vector3());
  const edgeOn = Math.abs(facing.dot(a)) < 0.15;
  const normal = kind === 'direction' && !edgeOn ? a : facing;
  drag = { kind, key, index, plane: new THREE.Plane().setFromNormalAndCoplanarPoint(normal, at),
           line: kind === 'apex' ? { foot: at.clone().addScaledVector(a, -at.dot(a)), axis: a } : null,
           before: clone(preset) };
  controls.enabled = false;
  renderer.domElement.setPointerCapture(event.pointerId);
  beginDrag();
});

renderer.domElement.addEventListener('pointermove', (event) => {
  if (!drag) return;
  const ray = rayAt(event);
  let point = null;
  if (drag.line) {
    point = new THREE.Vector3();
    const { foot, axis } = drag.line, far = 1e4 * info.model_size;
    ray.distanceSqToSegment(foot.clone().addScaledVector(axis, -far), foot.clone().addScaledVector(axis, far), null, point);
  } else {
    point = ray.intersectPlane(drag.plane, new THREE.Vector3());
  }
  if (!point) return;
  pending = edited(drag, point);
});

function release() {
  if (!drag) return;
  const { before, key, index } = drag;
  drag = null;
  controls.enabled = true;
  if (pending) {
    applyEdit(pending);
    pending = null;
  }
  if (JSON.stringify(before) !== JSON.stringify(preset)) remember(before, `drag of ${fieldOf({ key, index })}`);
  endDrag();
  settle();
}
renderer.domElement.addEventListener('pointerup', release);
renderer.domElement.addEventListener('pointercancel', release);

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
  return { key: handle.key, index: handle.index, value: [point.dot(a), 0, 0] };
}

// Keep buildable (issue 14): each drag step projects the rest of the design
// (the apex heights) onto the designs whose panels are simple and whose t* is
// free of collisions, within this budget of the frame; the handle stops where
// that is impossible. When the hand stops, the motion over the whole interval
// is repaired too (the held field fixed), undoably.
const keepBudget = 7;  // ms: with the stop at the wall (5 designs) and the redraw, within a 60 Hz frame
let keepHeld = null;    // the JSON pointer of the field the last keep-buildable drag held
let lastKeep = null;    // designer.keep's answer to the last step
const keepBuildable = () => $('keep').checked;
const pointerOf = (edit) => `/${edit.key.replaceAll('.', '/')}${edit.index >= 0 ? `/${edit.index}` : ''}`;

/// Applies one edit through the core without the round trip through JSON text
/// (the hot path while dragging); the topology does not change.
function applyEdit(edit) {
  const keep = keepBuildable();
  const result = keep ? designer.keep(edit.key, edit.index, ...edit.value, keepBudget) : designer.set(edit.key, edit.index, ...edit.value);
  if (!result.ok) {
    failure = { field: result.field, message: result.message };
    showMessage();
    return false;
  }
  failure = null;
  if (keep) {
    keepHeld = pointerOf(edit);
    lastKeep = result;
    preset = JSON.parse(designer.presetText());  // projected or stopped at the wall
    showRepair(result.clamped ? 'keep buildable: the handle stops here; further, a panel would not be simple or t* would collide'
      : result.projected ? 'keep buildable: the other apex heights follow the handle' : '');
  } else {
    setAt(preset, edit, edit.key === 'trajectory' || edit.key === 'directions' ? edit.value : edit.value[0]);
  }
  const before = info.t_star;
  info = designer.info();
  followTStar(before);
  buildability = null;  // the sweep follows when the drag ends (settle)
  updateInvalidPanels();
  if (collidingPanels.size) {
    collidingPanels = new Set();
    colourPanels();
  }
  updatePositions();
  placeHandles();
  updateLabels();
  showMessage();
  return true;
}

/// Once a drag ends: the preset's text and the check figures follow (both cost
/// more than a drag step on a large model, so they wait for the hand to stop).
function settle() {
  $('json').value = JSON.stringify(preset, null, 2);
  refitIfOutside();
  scheduleFigures();
}

// --- controls --------------------------------------------------------------
// Large models: the colliding panels follow when the slider is let go, not at
// every pause of the hand (their search then takes longer than a frame).
const largeModel = () => info.faces > 3000;
$('slider').addEventListener('input', (e) => {
  fraction = Number(e.target.value) / 1000;
  updatePositions();
  if (!largeModel()) scheduleCollisions();
});
$('slider').addEventListener('change', () => { if (largeModel()) scheduleCollisions(); });

/// The mode a preset is in (the mode selector's value).
const modeOf = (p) => (p.grid ? 'grid' : p.row ? 'row' : p.tube ? p.tube.type : 'open');

/// A row of `cells` face-coupled cells on `side` of the tube with apexes z: the
/// new cell shares the tube's line z[side + 1]; the far lines keep the spacing
/// of that family (z[side + 1] - z[side + 3]).
function rowOf(z, cells, side) {
  const near = z[(side + 1) % 4], step = near - z[(side + 3) % 4];
  return { side, free_heights: Array.from({ length: cells }, (_, k) => near + (k + 1) * step) };
}

/// Grid heights: cell (0, 0) has apexes (z0, z1, z2, z3); every further line of a
/// family keeps the spacing of the first two.
function gridHeights(z, cellsU, cellsW) {
  const line = (a, b, count) => Array.from({ length: count + 1 }, (_, k) => a + k * (b - a));
  return { u_heights: line(z[0], z[2], cellsU), w_heights: line(z[1], z[3], cellsW) };
}

function cellZ(p) {
  if (p.grid) return [p.grid.u_heights[0], p.grid.w_heights[0], p.grid.u_heights[1], p.grid.w_heights[1]];
  const heights = baseHeights(p);
  return heights ? heights.slice() : [-1.5, 1.0, -0.5, 2.0];
}

for (const id of ['cells-u', 'cells-w']) {
  $(id).addEventListener('change', () => {
    if (!preset.grid) return;
    const c = clone(preset);
    c.grid = gridHeights(cellZ(c), Math.max(1, Number($('cells-u').value)), Math.max(1, Number($('cells-w').value)));
    apply(c);
  });
}

for (const id of ['row-cells', 'row-side']) {
  $(id).addEventListener('change', () => {
    if (!preset.row || !preset.tube) return;
    const c = clone(preset);
    c.row = rowOf(c.tube.apex_heights, Math.max(1, Number($('row-cells').value)), Number($('row-side').value));
    apply(c);
  });
}

// Each mode keeps the design it last had: switching back restores it.
const modeMemory = {};
$('mode').addEventListener('change', (e) => {
  modeMemory[modeOf(preset)] = clone(preset);
  if (modeMemory[e.target.value]) {
    if (!apply(clone(modeMemory[e.target.value]), { what: 'mode switch' })) e.target.value = modeOf(preset);
    return;
  }
  const c = clone(preset);
  const z = cellZ(c);
  delete c.grid;
  delete c.row;
  if (e.target.value === 'grid') {
    delete c.apex_heights;
    delete c.signs;
    delete c.tube;
    c.grid = gridHeights(z, Math.max(1, Number($('cells-u').value)), Math.max(1, Number($('cells-w').value)));
  } else if (e.target.value === 'open') {
    delete c.tube;
    delete c.couplings;  // they attach to tubes
    c.apex_heights = z.length >= 5 ? z : [...z.slice(0, 4), z[0] + 1.3];
    c.signs = '+'.repeat(c.apex_heights.length - 2);
  } else {
    delete c.apex_heights;
    delete c.signs;
    const q = z.slice(0, 4);
    while (q.length < 4) q.push(q[q.length - 1] + 1);
    if (e.target.value === 'anti-parallelogram') q[3] = q[0] + q[2] - q[1];  // its symmetry condition
    const row = e.target.value === 'row';
    c.tube = { type: row ? 'parallelogram' : e.target.value, apex_heights: q };
    if (row) c.row = rowOf(q, Math.max(1, Number($('row-cells').value)), Number($('row-side').value));
  }
  if (!apply(c, { what: 'mode switch' })) e.target.value = modeOf(preset);
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
/// The preset as saved: its name from the name box (the loaded name + "-edited"
/// once the design changed and no other was typed), its description what the design is now.
function savedPreset() {
  const p = clone(preset);
  const changed = history.length > 0;
  const typed = $('name').value.trim();
  p.name = typed && typed !== loadedName ? typed : changed ? `${loadedName || 'design'}-edited` : loadedName || 'design';
  if (changed) {
    p.description = `${info.kind}, ${info.faces} panels, t* = ${format(info.t_star)} in [${format(info.t_lambda)}, ` +
      `${format(info.t_mu)}]; ${statusText()}. Edited in the phedra designer from "${loadedName}".`;
  }
  return p;
}
$('save').addEventListener('click', () => {
  const p = savedPreset();
  download(`${p.name}.json`, JSON.stringify(p, null, 2) + '\n', 'application/json');
});
$('name').addEventListener('change', () => {
  const name = $('name').value.trim();
  if (name && name !== preset.name) apply({ ...clone(preset), name }, { what: 'rename' });
});
/// Opens a preset the user picked, dropped or chose from the shipped ones (undoable).
function openPreset(text, name) {
  try {
    const loaded = JSON.parse(text);
    if (apply(loaded, { what: `load of ${name}` })) loadedName = loaded.name ?? name.replace(/\.json$/, '');
  } catch (error) {
    failure = { field: '', message: `${name}: ${error.message}` };
    showMessage();
  }
}
/// The preset a .glb of phedra carries (extras.phedra.preset in its JSON chunk), or null.
function presetInGlb(bytes) {
  const view = new DataView(bytes);
  if (bytes.byteLength < 20 || view.getUint32(0, true) !== 0x46546c67) return null;  // 'glTF'
  const length = view.getUint32(12, true);
  const json = JSON.parse(new TextDecoder().decode(new Uint8Array(bytes, 20, length)));
  return json.asset?.extras?.phedra?.preset ?? null;
}
/// A preset (.json), or the preset inside a .glb phedra wrote.
async function openFile(file) {
  if (!/\.(glb)$/i.test(file.name)) {
    openPreset(await file.text(), file.name);
    return;
  }
  let text = null;
  try {
    text = presetInGlb(await file.arrayBuffer());
  } catch { /* not a readable .glb: said below */ }
  if (text) {
    openPreset(text, file.name.replace(/\.glb$/i, '.json'));
  } else {
    failure = { field: '', message: `${file.name} carries no preset (not written by phedra, or by an older one): view it with phedra view ${file.name}` };
    showMessage();
  }
}
$('load').addEventListener('change', async (e) => {
  const file = e.target.files[0];
  if (file) openFile(file);
});
window.addEventListener('dragover', (e) => e.preventDefault());
window.addEventListener('drop', async (e) => {
  e.preventDefault();
  const file = e.dataTransfer.files[0];
  if (file) openFile(file);
});
// The shipped presets, as `phedra view` serves them.
fetch('/presets/index.json').then((r) => (r.ok ? r.json() : [])).then((list) => {
  for (const p of list) {
    const option = document.createElement('option');
    option.value = p.file;
    option.textContent = p.name;
    option.title = p.description;
    $('presets').append(option);
  }
  $('presets').disabled = list.length === 0;
}).catch(() => { $('presets').disabled = true; });
$('presets').addEventListener('change', async (e) => {
  const file = e.target.value;
  if (!file) return;
  openPreset(await (await fetch(`/presets/${file}`)).text(), file);
  e.target.value = '';
});
/// The animated .glb, written by the core as `phedra generate -o X.glb` writes it.
function glbBytes() {
  const bytes = designer.glb(true, false);
  if (bytes.ok === false) throw new Error(bytes.message);
  return Uint8Array.from(bytes);
}
$('export-glb').addEventListener('click', () => download(`${preset.name || 'phedra'}.glb`, glbBytes(), 'model/gltf-binary'));
$('export-fold').addEventListener('click', () => download(`${preset.name || 'phedra'}.fold`, designer.fold(41), 'application/json'));
$('fit').addEventListener('click', () => fitView());
$('fit-t').addEventListener('click', () => fitView({ motion: false }));
$('png').addEventListener('click', () => {
  renderer.render(scene, camera);
  const a = document.createElement('a');
  a.download = `${preset.name || 'phedra'}.png`;
  a.href = renderer.domElement.toDataURL('image/png');
  a.click();
});

// --- start -----------------------------------------------------------------
let frameLog = null;  // while recording (bench/designer.mjs): [{start, work, edit}] a frame

function frame() {
  const start = performance.now();
  const edited = pending !== null;
  if (pending) {
    const edit = pending;
    pending = null;
    if (applyEdit(edit) && !drag) settle();
    stepCost = 0.8 * stepCost + 0.2 * (performance.now() - start);
  }
  controls.update();
  if (needsRender) {
    needsRender = false;
    renderer.render(scene, camera);
    if (calibrate && !drag) {
      // The draw above uploaded what changed; time the next ones.
      calibrate = false;
      calibrateDraw();
    }
    if (frameLog) frameLog.push({ start, work: performance.now() - start, edit: edited });
  }
  requestAnimationFrame(frame);
}

/// The preset to start with: one the viewer handed over ("Edit in designer", a
/// dropped .json), else the one `phedra view PRESET` serves, else the default.
async function initialPreset() {
  const handed = sessionStorage.getItem('phedra-open-preset');
  if (handed) {
    sessionStorage.removeItem('phedra-open-preset');
    try {
      return JSON.parse(handed);
    } catch (error) {
      failure = { field: '', message: `the preset handed over is not JSON: ${error.message}` };
    }
  }
  for (const url of ['/preset.json', '/presets/default.json']) {
    const response = await fetch(url);
    if (response.ok) return response.json();
  }
  return {};
}
const initial = await initialPreset();
loadedName = initial.name ?? null;
if (!apply(initial, { record: false })) {
  $('message').textContent = `the preset is refused: ${failure.field}: ${failure.message}`;
}
if (info) {
  // Start at t*, where the handles (the input) lie on the surface.
  fraction = (info.t_star - info.t_lambda) / (info.t_mu - info.t_lambda);
  $('slider').value = String(Math.round(fraction * 1000));
  updatePositions();
  camera.position.set(1.6, -2.2, 1.2);  // the direction fitView looks from at first
  fitView();
}
requestAnimationFrame(frame);

/// For tests and measurements.
window.phedraDesigner = {
  ready: info !== null,
  info: () => info,
  /// Hinges coloured mountain / valley at the slider's t.
  folds: () => foldCounts,
  preset: () => clone(preset),
  presetText,
  message: () => $('message').textContent,
  labelText: () => ($('label').hidden ? '' : $('label').textContent),
  t: () => tOf(fraction),
  vertex: (k) => Array.from(surface.geometry.getAttribute('position').array.slice(3 * k, 3 * k + 3)),
  /// Every vertex at the slider's t in double precision, straight from the core.
  positions: () => Array.from(designer.evaluate(tOf(fraction))),
  handlePosition: (kind, index) => handlePosition(kind, index)?.toArray() ?? null,
  /// The surface's extent on screen (normalised device coordinates) at fraction f of the interval.
  screenBox: (f) => {
    const x = designer.evaluate(tOf(f)), v = new THREE.Vector3();
    const out = { minX: Infinity, maxX: -Infinity, minY: Infinity, maxY: -Infinity };
    for (let i = 0; i + 2 < x.length; i += 3) {
      v.set(x[i], x[i + 1], x[i + 2]).project(camera);
      out.minX = Math.min(out.minX, v.x); out.maxX = Math.max(out.maxX, v.x);
      out.minY = Math.min(out.minY, v.y); out.maxY = Math.max(out.maxY, v.y);
    }
    return out;
  },
  handleScreen: (kind, index) => {
    const p = handlePosition(kind, index);
    return p ? screenOf(p) : null;
  },
  apply: (p) => apply(p),
  /// One drag step as the hand makes it: {key, index, value: [x, y, z] (a height: [h, 0, 0])}.
  edit: (edit) => applyEdit(edit),
  /// designer.keep's answer to the last keep-buildable step.
  lastKeep: () => lastKeep,
  figures: () => figures,
  /// The last buildability report (null while it is computed), the panels shown
  /// red (not simple) and orange (colliding at the slider's t).
  buildability: () => buildability,
  invalidPanels: () => [...invalidPanels].sort((a, b) => a - b),
  collidingPanels: () => [...collidingPanels].sort((a, b) => a - b),
  /// Moves the slider to t (as a user would) and waits for the colours.
  setT: (t) => {
    fraction = Math.min(1, Math.max(0, (t - info.t_lambda) / (info.t_mu - info.t_lambda)));
    $('slider').value = String(Math.round(fraction * 1000));
    $('slider').dispatchEvent(new Event('input'));
    $('slider').dispatchEvent(new Event('change'));
  },
  /// The bar of the buildable part: [left, width] in % of the slider, or null.
  buildableBar: () => ($('buildable-part').hidden ? null : [parseFloat($('buildable-part').style.left), parseFloat($('buildable-part').style.width)]),
  whyText: () => ($('why').hidden ? '' : $('why-list').textContent),
  glbSize: () => glbBytes().byteLength,
  fold: () => designer.fold(5),
  /// Records every animation frame (its start, the time its work took, whether it
  /// applied an edit) until stopFrames() returns the log.
  /// The resolution a drag would use now (a fraction of the full one) and the timed full draw (ms).
  dragResolution: () => ({ ratio: chooseDragRatio(), drawCost, canvas: [renderer.domElement.width, renderer.domElement.height] }),
  recordFrames: () => { frameLog = []; },
  stopFrames: () => { const log = frameLog; frameLog = null; return log; },
  /// Times `runs` drag steps of trajectory point 1 through the code a drag runs:
  /// milliseconds (median, worst) of `core` (Designer.set, info, evaluate), `step`
  /// (the frame's applyEdit: the core, the upload of the positions, the handles and
  /// labels), `full` (the step and a draw at full resolution, waited for) and
  /// `frame` (the same at the resolution a drag uses, `ratio` of the full one);
  /// for reference `load`, an edit through the preset's text (sign toggles, mode
  /// changes, the JSON editor); `keep`, the step of a keep-buildable drag
  /// (Designer.keep: the check at t*), and `keepProjection`, such steps of a
  /// height dragged where panels would cross (the other heights projected, or
  /// the handle stopped: `projected`, `clamped` count them).
  measure(runs) {
    const start = clone(preset);
    const moved = (k) => start.trajectory[1].map((x, i) => x + (i === 2 ? 1e-3 * Math.sin(k) : 0));
    const time = (body) => {
      const times = [];
      for (let k = 0; k < runs; ++k) {
        const t0 = performance.now();
        body(k);
        times.push(performance.now() - t0);
      }
      times.sort((x, y) => x - y);
      return { median: times[times.length >> 1], worst: times[times.length - 1] };
    };
    const wasDragging = drag;
    drag = { kind: 'trajectory', index: 1 };  // as while the hand moves: nothing settles
    const core = time((k) => {
      designer.set('trajectory', 1, ...moved(k));
      designer.info();
      designer.evaluate(tOf(fraction));
    });
    const step = time((k) => applyEdit({ key: 'trajectory', index: 1, value: moved(k) }));
    // A frame waits for the rasterizer (a pixel read back): at full resolution, and
    // at the resolution a drag uses (the same unless the full one does not fit).
    const drawn = (k) => {
      applyEdit({ key: 'trajectory', index: 1, value: moved(k) });
      timedDraw();
    };
    const full = time(drawn);
    beginDrag();
    const ratio = dragRatio;
    const frame = time(drawn);
    endDrag();
    // Keep-buildable steps (issue 14): the check at t* (simple panels, no
    // collision), and the projection of the apex heights when it fails.
    $('keep').checked = true;
    let projected = 0, clamped = 0;
    const keep = time((k) => {
      applyEdit({ key: 'trajectory', index: 1, value: moved(k) });
      projected += lastKeep?.projected ? 1 : 0;
      clamped += lastKeep?.clamped ? 1 : 0;
    });
    // A height dragged where its panels would cross (z1 below z2: the '+' faces
    // of that column cross): the other heights follow, or the handle stops.
    apply(start);
    const keepProjection = time((k) => {
      applyEdit({ key: 'apex_heights', index: 1, value: [start.apex_heights[2] - 0.1 - 0.01 * k, 0, 0] });
      projected += lastKeep?.projected ? 1 : 0;
      clamped += lastKeep?.clamped ? 1 : 0;
    });
    $('keep').checked = false;
    keepHeld = null;
    const load = time((k) => {
      const c = clone(start);
      c.trajectory[1] = moved(k);
      designer.load(JSON.stringify(c));
      designer.info();
      designer.evaluate(tOf(fraction));
    });
    drag = wasDragging;
    apply(start);
    return { vertices: info.vertices, panels: info.faces, core, step, full, frame, ratio, load, keep, keepProjection, projected, clamped };
  },
};
