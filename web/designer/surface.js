// The model in the scene: the panels coloured by validity, their outlines, the
// hinges coloured mountain / valley at the slider's t, and one panel
// highlighted (the panel a cause of the list names). The positions come from
// the core (Designer.evaluate), the panels to colour from its checks.
import * as THREE from 'three';
import { foldAngle, foldColours, hingesOf } from '../folds.js';
import { $ } from './util.js';

// Lambert: the matte look of a rough standard material at a fraction of its cost per pixel.
// Panels by validity (docs/design.md, Buildable designs): simple, not simple
// (a bow-tie or degenerate: cannot be cut as one plate), penetrating another
// panel (or folded through its hinge) at the slider's t. A slate grey-blue, dark
// enough that both hinge colours (light orange, light blue: a pair colour-blind
// eyes tell apart) stand out on it alike (contrast about 2.4 : 1 each on the lit side);
// colliding purple, not orange: the mountain lines stay visible on it.
const validityColours = { simple: 0x74869a, invalid: 0xe53935, colliding: 0xab47bc };

const sameSet = (a, b) => a.size === b.size && [...a].every((x) => b.has(x));

/// `state`: the DesignState; `designer`: the core's Designer; `showT(t)`: says
/// the t the positions are at; `screenOf(point)`: where a point is on the page.
export function createSurface({ scene, state, designer, requestRender, showT, screenOf = null, onPositions = null }) {
  const surface = new THREE.Mesh(new THREE.BufferGeometry(), ['simple', 'invalid', 'colliding'].map((k, rank) =>
    // Pushed back a little in depth, so that the panel edges and fold lines drawn on them do not flicker;
    // colliding panels least, simple ones most: where panels lie on one another (a hinge folded
    // shut, a bow-tie's two triangles, panels through each other) the one in trouble is drawn
    // whole on top, not in stripes with its neighbour.
    new THREE.MeshLambertMaterial({ color: validityColours[k], side: THREE.DoubleSide, flatShading: true,
                                    polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 3 - rank })));
  // Without depth writes: the fold lines drawn after them cover them instead of fighting them pixel by pixel.
  const edges = new THREE.LineSegments(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: 0x20303f, depthWrite: false }));
  scene.add(surface, edges);

  let hinges = [], hingePanels = [], hingeSigns = new Int8Array(0);
  let foldCounts = { mountains: 0, valleys: 0 };
  const foldLine = (colour) => {
    const line = new THREE.LineSegments(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: colour, depthFunc: THREE.LessEqualDepth }));
    line.renderOrder = 1;
    scene.add(line);
    return line;
  };
  const mountainLines = foldLine(foldColours.mountain), valleyLines = foldLine(foldColours.valley);
  // The highlighted panel: its outline over everything, and a fill.
  const highlight = new THREE.LineSegments(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: 0xffeb3b, depthTest: false }));
  highlight.renderOrder = 9;
  const highlightFill = new THREE.Mesh(new THREE.BufferGeometry(), new THREE.MeshBasicMaterial({
    color: 0xffeb3b, transparent: true, opacity: 0.45, side: THREE.DoubleSide, depthWrite: false, polygonOffset: true, polygonOffsetFactor: -1, polygonOffsetUnits: -1 }));
  highlight.visible = highlightFill.visible = false;
  scene.add(highlight, highlightFill);
  let highlighted = -1;

  /// A new topology (state.info, state.faces): the index buffers, outlines and hinges, then the positions.
  function rebuild() {
    const faces = state.faces;
    const count = state.info.vertices;
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
    for (const line of [mountainLines, valleyLines, highlight, highlightFill]) {
      line.geometry.dispose();
      line.geometry = new THREE.BufferGeometry();
      line.geometry.setAttribute('position', geometry.getAttribute('position'));
      line.geometry.setIndex([]);
    }
    highlighted = -1;
    highlight.visible = highlightFill.visible = false;
    updatePositions();
  }

  /// Highlights panel k (-1: none): outlined over everything, filled, named on screen.
  function highlightPanel(k) {
    const faces = state.faces;
    highlighted = faces && k >= 0 && 4 * k + 3 < faces.length ? k : -1;
    highlight.visible = highlightFill.visible = highlighted >= 0;
    if (highlighted >= 0) {
      const [a, b, c, d] = faces.subarray(4 * k, 4 * k + 4);
      highlight.geometry.setIndex([a, b, b, c, c, d, d, a]);
      highlightFill.geometry.setIndex([a, b, c, a, c, d]);
      highlight.geometry.computeBoundingSphere();
      highlightFill.geometry.computeBoundingSphere();
    }
    updatePanelLabel();
    requestRender();
    return highlighted >= 0;
  }

  /// The highlighted panel's centre as drawn, or null.
  function panelCentre() {
    if (highlighted < 0) return null;
    const x = surface.geometry.getAttribute('position').array, centre = new THREE.Vector3();
    for (const v of state.faces.subarray(4 * highlighted, 4 * highlighted + 4)) centre.add(new THREE.Vector3(x[3 * v], x[3 * v + 1], x[3 * v + 2]));
    return centre.multiplyScalar(0.25);
  }

  /// "panel 18" on the page, at the highlighted panel (after a draw: the camera may have moved).
  function updatePanelLabel() {
    const label = $('panel-label'), centre = panelCentre();
    if (!label) return;
    label.hidden = !centre || !screenOf;
    if (label.hidden) return;
    const [x, y] = screenOf(centre);
    label.textContent = `panel ${highlighted}`;
    label.style.left = `${x - 24}px`;
    label.style.top = `${y + 10}px`;
  }

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

  /// Evaluates the motion at the slider's t and uploads the positions.
  function updatePositions() {
    const t = state.tOf(state.fraction);
    const positions = designer.evaluate(t);
    if (positions.ok === false) return;
    const attribute = surface.geometry.getAttribute('position');
    attribute.array.set(positions);
    attribute.needsUpdate = true;
    if (hinges.length) colourFolds(positions);
    // (flat shading: the shader derives the normals, none to compute)
    surface.geometry.computeBoundingSphere();
    if (highlighted >= 0) {
      highlight.geometry.computeBoundingSphere();
      highlightFill.geometry.computeBoundingSphere();
      updatePanelLabel();
    }
    showT(t);
    if (onPositions) onPositions(t);
    requestRender();
  }

  /// Orders the triangles by validity (simple, not simple, colliding) and gives
  /// each range its material: one draw call a colour.
  function colourPanels() {
    const geometry = surface.geometry;
    const faces = state.faces;
    if (!faces) return;
    const order = [[], [], []];
    for (let f = 0; f < faces.length / 4; ++f) {
      const kind = state.collidingPanels.has(f) ? 2 : state.invalidPanels.has(f) ? 1 : 0;
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

  /// The panels that are not simple, from the core (cheap: every drag step).
  function updateInvalidPanels() {
    const list = designer.invalidPanels();
    const next = new Set(list.ok === false ? [] : Array.from(list));
    if (!sameSet(next, state.invalidPanels)) {
      state.invalidPanels = next;
      colourPanels();
    }
  }

  /// No panel colliding (a drag step: the search follows when the hand stops).
  function clearCollisions() {
    if (state.collidingPanels.size) {
      state.collidingPanels = new Set();
      colourPanels();
    }
  }

  /// The panels that collide at the slider's t (after the slider or an edit settles).
  let collisionTimer = null;
  function scheduleCollisions() {
    clearTimeout(collisionTimer);
    collisionTimer = setTimeout(() => {
      const t = state.tOf(state.fraction);
      const list = designer.collisions(t);
      const next = new Set(list.ok === false ? [] : Array.from(list));
      // At t* itself a collision the report found (a hinge shut and through
      // there is not a penetration the per-t test sees): its panels too.
      const atStar = state.buildability?.at_t_star;
      if (atStar && Math.abs(t - state.info.t_star) <= 1e-9 * Math.max(1, Math.abs(state.info.t_mu - state.info.t_lambda))) {
        for (const p of atStar.panels) next.add(p);
      }
      if (!sameSet(next, state.collidingPanels)) {
        state.collidingPanels = next;
        colourPanels();
      }
    }, 60);
  }

  return {
    rebuild,
    updatePositions,
    /// The panels drawn or not (the thick plates show in their place; outlines and hinges stay).
    showPanels(visible) { surface.visible = visible; requestRender(); },
    highlightPanel,
    updatePanelLabel,
    /// The highlighted panel (-1: none).
    get highlighted() { return highlighted; },
    updateInvalidPanels,
    clearCollisions,
    scheduleCollisions,
    /// Hinges coloured mountain / valley at the slider's t: {mountains, valleys}.
    get foldCounts() { return foldCounts; },
    /// Every vertex as drawn (x, y, z each; single precision).
    positions: () => surface.geometry.getAttribute('position')?.array ?? new Float32Array(0),
    /// Vertex k as drawn (single precision).
    vertex: (k) => Array.from(surface.geometry.getAttribute('position').array.slice(3 * k, 3 * k + 3)),
    /// The box of the surface as drawn.
    boundingBox() {
      surface.geometry.computeBoundingBox();
      return surface.geometry.boundingBox;
    },
  };
}
