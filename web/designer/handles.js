// The handles: where the preset's control points are (trajectory points,
// direction tips, heights on the apex line), drawn as one instanced mesh a
// kind (a draw call each, however many profiles) and one line set for the
// direction stems: a drag moves instances, it creates nothing. Also finds the
// handle a field names, where a handle is on screen, the handle nearest a
// point of the screen (handles close together are told apart by the pointer,
// not by depth), and shows the hovered and the selected handle larger, lit,
// with their names next to them.
import * as THREE from 'three';
import { fieldOf, heightRefs } from './edits.js';
import { $, format } from './util.js';

/// The unit axis of a preset (z unless it says otherwise).
export const axisOf = (p) => new THREE.Vector3(...(p.axis || [0, 0, 1])).normalize();

const handleKinds = ['trajectory', 'direction', 'apex'];
const hoverColour = new THREE.Color(0xffffff), selectColour = new THREE.Color(0xffeb3b);
const sameRef = (a, b) => Boolean(a && b && a.key === b.key && a.index === b.index);
/// How many pixels from a handle's centre the pointer still picks it (or its own radius on screen, if larger).
export const pickRadius = 14;

/// What a person calls a handle: "trajectory point 3", "apex S_2", "u line 2 of the grid".
export function handleName({ key, index }) {
  if (key === 'trajectory') return `trajectory point ${index}`;
  if (key === 'directions') return `direction of profile ${index}`;
  if (key === 'apex_heights' || key === 'tube.apex_heights') return `apex S_${index}`;
  if (key === 'grid.u_heights') return `u line ${index} of the grid`;
  if (key === 'grid.w_heights') return `w line ${index} of the grid`;
  if (key === 'row.free_heights') return `height of row cell ${index + 1}`;
  const coupling = /^couplings\.(\d+)\.free_height/.exec(key);
  if (coupling) return `free height${index >= 0 ? ` ${index}` : ''} of coupling ${coupling[1]}`;
  return fieldOf({ key, index });
}
const handleColours = { trajectory: 0xff9800, direction: 0x42a5f5, apex: 0x66bb6a };
const arrayHeightColour = 0xba68c8;  // heights of further members (grid u lines, row, couplings)
const wHeightColour = 0x4dd0e1;      // a grid's w lines

function handleGeometry(kind, count) {
  // Many handles (a handle a profile of a long model) are drawn as octahedra: 8
  // triangles each instead of 192 (what a software renderer pays for the most).
  if (count > 200) return new THREE.OctahedronGeometry(kind === 'direction' ? 1.2 : 1);
  return kind === 'direction' ? new THREE.BoxGeometry(1.4, 1.4, 1.4) : new THREE.SphereGeometry(1, 16, 12);
}

export function createHandles({ scene, camera, renderer, state, designer, requestRender }) {
  const handles = new THREE.Group();
  scene.add(handles);
  const axisLine = new THREE.Line(new THREE.BufferGeometry(), new THREE.LineDashedMaterial({ color: 0x66bb6a, dashSize: 0.1, gapSize: 0.06 }));
  scene.add(axisLine);
  // kind -> THREE.InstancedMesh; userData.refs[instance] = {key, index}: what Designer.set edits
  const handleMeshes = {};
  const stems = new THREE.LineSegments(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: 0x42a5f5 }));
  handles.add(stems);
  // A fortieth of the model, smaller where the profiles are closer (a handle a profile).
  let handleSize = () => 0.025 * scale();

  /// The size handles are drawn at: the model's, but at most twice the extent of
  /// the input (trajectory and heights): next to a flexion limit the model's size
  /// runs away with a vertex passing near infinity, the handles must not.
  function scale() {
    const t = Array.isArray(state.preset?.trajectory) ? state.preset.trajectory : [];
    const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
    for (const v of t) v.forEach((x, i) => { lo[i] = Math.min(lo[i], x); hi[i] = Math.max(hi[i], x); });
    const heights = heightRefs(state.preset ?? {}).map((r) => r.value);
    const along = heights.length ? Math.max(...heights) - Math.min(...heights) : 0;
    const extent = Math.hypot(...hi.map((x, i) => (Number.isFinite(x - lo[i]) ? x - lo[i] : 0)), along);
    return extent > 0 ? Math.min(state.info.model_size, 2 * extent) : state.info.model_size;
  }
  let lastSize = 0;
  let hovered = null;   // {key, index}: the handle under the pointer (or being dragged)
  let selected = null;  // {key, index}: the handle a cause of the panel selected

  /// The colour of a handle: its own, lit towards white when hovered, yellow when selected.
  const styled = (out, hex, ref) => (sameRef(ref, selected) ? out.copy(selectColour)
    : sameRef(ref, hovered) ? out.setHex(hex).lerp(hoverColour, 0.55) : out.setHex(hex));

  /// Sizes the handles for the shown preset: at most a third of the median trajectory segment.
  function sizeHandles() {
    const t = Array.isArray(state.preset.trajectory) ? state.preset.trajectory : [];
    const lengths = t.slice(1).map((v, i) => Math.hypot(...v.map((x, k) => x - t[i][k]))).sort((a, b) => a - b);
    const spacing = lengths.length ? lengths[lengths.length >> 1] / 3 : Infinity;
    const size = Math.min(0.025 * scale(), spacing);
    handleSize = () => size;
  }

  /// Where every handle is: {kind: [{key, index, position, colour}]}, the direction stems, and the apex line.
  function handlePlaces() {
    const { preset, info } = state;
    const reach = 0.12 * scale();  // the length of a direction's stem
    const places = { trajectory: [], direction: [], apex: [] };
    const stemPoints = [];
    const trajectory = Array.isArray(preset.trajectory) ? preset.trajectory : [];
    trajectory.forEach((v, i) => places.trajectory.push({ key: 'trajectory', index: i, position: new THREE.Vector3(...v) }));
    if (Array.isArray(preset.directions)) {
      preset.directions.forEach((d, i) => {
        const dir = new THREE.Vector3(...d);
        if (dir.lengthSq() === 0 || !trajectory[i]) return;
        const foot = new THREE.Vector3(...trajectory[i]);
        const position = foot.clone().addScaledVector(dir.normalize(), reach);
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
        // White: each instance has its colour (lit when hovered or selected).
        const material = new THREE.MeshStandardMaterial({ color: 0xffffff, depthTest: false });
        mesh = new THREE.InstancedMesh(handleGeometry(kind, list.length), material, list.length);
        mesh.userData.kind = kind;
        mesh.renderOrder = 10;
        handleMeshes[kind] = mesh;
        handles.add(mesh);
      }
      mesh.userData.refs = list.map((h) => ({ key: h.key, index: h.index }));
      // The colours (and their upload) only when they change: not at every drag step.
      const colours = list.map((h) => h.colour ?? handleColours[kind]);
      const recolour = !mesh.instanceColor || !mesh.userData.colours || colours.some((c, k) => c !== mesh.userData.colours[k]);
      mesh.userData.colours = colours;
      let coloured = false;
      list.forEach((h, k) => {
        const lit = sameRef(h, hovered) || sameRef(h, selected);
        const s = size * (lit ? 1.7 : 1);
        mesh.setMatrixAt(k, matrix.makeScale(s, s, s).setPosition(h.position));
        if (recolour || lit) { mesh.setColorAt(k, styled(colour, colours[k], h)); coloured = true; }
      });
      mesh.instanceMatrix.needsUpdate = true;
      requestRender();
      if (coloured) mesh.instanceColor.needsUpdate = true;
      mesh.computeBoundingSphere();
    }
    lastSize = size;
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
      const modelSize = scale();
      axisLine.geometry.dispose();
      axisLine.geometry = new THREE.BufferGeometry().setFromPoints([foot.clone().addScaledVector(axis, lo - 0.2 * modelSize),
                                                                    foot.clone().addScaledVector(axis, hi + 0.2 * modelSize)]);
      axisLine.computeLineDistances();
    }
    if (hovered || selected) updateLabels();
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

  /// Where a point of the scene is on the page: [x, y] in CSS pixels.
  function screenOf(position) {
    const p = position.clone().project(camera);
    const rect = renderer.domElement.getBoundingClientRect();
    return [rect.left + (p.x + 1) / 2 * rect.width, rect.top + (1 - p.y) / 2 * rect.height];
  }

  /// Rescales and recolours the handles after the hovered or selected one changed.
  function restyle() {
    const matrix = new THREE.Matrix4(), colour = new THREE.Color(), p = new THREE.Vector3(), q = new THREE.Quaternion(), s = new THREE.Vector3();
    for (const mesh of Object.values(handleMeshes)) {
      mesh.userData.refs.forEach((ref, k) => {
        mesh.getMatrixAt(k, matrix);
        matrix.decompose(p, q, s);
        const size = lastSize * (sameRef(ref, hovered) || sameRef(ref, selected) ? 1.7 : 1);
        mesh.setMatrixAt(k, matrix.makeScale(size, size, size).setPosition(p));
        mesh.setColorAt(k, styled(colour, mesh.userData.colours[k], ref));
      });
      mesh.instanceMatrix.needsUpdate = true;
      if (mesh.instanceColor) mesh.instanceColor.needsUpdate = true;
    }
    updateLabels();
    requestRender();
  }

  /// The handle nearest the page point (x, y) within pickRadius pixels (or its own
  /// radius on screen): {kind, key, index, distance} or null. Nearest on screen,
  /// not in depth: of handles drawn over each other, the one whose centre the pointer is on.
  function nearest(x, y) {
    const matrix = new THREE.Matrix4(), p = new THREE.Vector3(), edge = new THREE.Vector3();
    const rect = renderer.domElement.getBoundingClientRect();
    const right = new THREE.Vector3().setFromMatrixColumn(camera.matrixWorld, 0);
    let best = null;
    for (const kind of handleKinds) {
      const mesh = handleMeshes[kind];
      if (!mesh) continue;
      mesh.userData.refs.forEach((ref, k) => {
        mesh.getMatrixAt(k, matrix);
        p.setFromMatrixPosition(matrix);
        edge.copy(p).addScaledVector(right, lastSize).project(camera);
        p.project(camera);
        if (p.z > 1) return;  // behind the camera
        const sx = rect.left + (p.x + 1) / 2 * rect.width, sy = rect.top + (1 - p.y) / 2 * rect.height;
        const radius = Math.max(pickRadius, (Math.abs(edge.x - p.x) / 2) * rect.width + 3);
        const distance = Math.hypot(sx - x, sy - y);
        if (distance <= radius && (!best || distance < best.distance)) best = { kind, key: ref.key, index: ref.index, distance };
      });
    }
    return best;
  }

  /// The handle's label: its name, its field and value.
  function labelOf(ref) {
    const at = ref.key.split('.').reduce((o, part) => o?.[part], state.preset);
    const value = ref.index >= 0 ? at?.[ref.index] : at;
    return `${handleName(ref)} · ${fieldOf(ref)}${typeof value === 'number' ? ` = ${format(value)}` : ''}`;
  }

  /// The name next to the hovered handle, else next to the selected one.
  function updateLabels() {
    const label = $('handle-label');
    const ref = hovered ?? selected;
    const at = ref ? handlePosition(ref.key, ref.index) : null;
    if (!label || !at) { if (label) label.hidden = true; return; }
    const [x, y] = screenOf(at);
    label.textContent = labelOf(ref);
    label.style.left = `${x + 14}px`;
    label.style.top = `${y - 28}px`;
    label.classList.toggle('selected', !hovered || sameRef(hovered, selected));
    label.hidden = false;
  }

  return {
    /// The handle under the pointer ({key, index} or null): drawn larger and lit, named.
    hover(ref) {
      const next = ref ? { key: ref.key, index: ref.index } : null;
      if (sameRef(next, hovered) || (!next && !hovered)) return;
      hovered = next;
      restyle();
    },
    /// The selected handle (a cause clicked; null: none): drawn larger, yellow, named.
    select(ref) {
      selected = ref && findHandle(ref.key, ref.index) ? { key: ref.key, index: ref.index } : null;
      restyle();
      return selected !== null;
    },
    get hovered() { return hovered; },
    get selected() { return selected; },
    nearest,
    updateLabels,
    size: sizeHandles,
    place: placeHandles,
    /// The instanced meshes (trajectory, direction, apex): to pick and to frame.
    meshes: () => Object.values(handleMeshes),
    handlePosition,
    handleOf,
    screenOf,
  };
}
