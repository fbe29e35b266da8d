// Camera framing over a whole motion, and a ground grid with a round cell size
// that gives the model's scale.
import * as THREE from 'three';

const v = new THREE.Vector3(), m = new THREE.Vector3();

/// A mesh of the model itself: a morph primitive, or a panel node (whose parent
/// may be another panel: the hinge tree); not an outline or overlay the page
/// added to one (those follow their mesh and carry no vertex numbers).
export function isModelMesh(o) {
  return o.isMesh && (!o.parent?.isMesh || o.userData.vertices !== undefined);
}

/// Calls `visit(world position)` for every vertex of `object`'s meshes as shown
/// now (morph targets applied; the vector is reused).
export function forEachShownVertex(object, visit) {
  object.updateMatrixWorld(true);
  object.traverse((o) => {
    if (!isModelMesh(o)) return;
    const position = o.geometry.getAttribute('position');
    const morphs = o.geometry.morphAttributes.position;
    const weights = o.morphTargetInfluences ?? [];
    const active = morphs ? weights.map((w, j) => [w, j]).filter(([w]) => w !== 0) : [];
    for (let i = 0; i < position.count; ++i) {
      v.fromBufferAttribute(position, i);
      for (const [w, j] of active) v.add(m.fromBufferAttribute(morphs[j], i).multiplyScalar(w));
      visit(v.applyMatrix4(o.matrixWorld));
    }
  });
}

/// Extends `box` by every vertex of `object`'s meshes as shown now.
export function expandByShownVertices(box, object) {
  forEachShownVertex(object, (p) => box.expandByPoint(p));
  return box;
}

/// The union of the shown boxes at `times` (seconds), posing through `setTime`.
export function motionBox(object, setTime, times) {
  const box = new THREE.Box3();
  for (const t of times) {
    setTime(t);
    expandByShownVertices(box, object);
  }
  return box;
}

/// `box` (a motion's) limited to `core` (the pose at rest) grown by `factor`
/// times the core's diagonal on every side: a motion that passes near infinity
/// (a vertex sent far out next to a flexion limit) would otherwise frame the
/// model as a dot under a grid of kilometre cells.
export function clampToCore(box, core, factor = 2) {
  if (core.isEmpty() || box.isEmpty()) return box;
  const reach = factor * core.getSize(new THREE.Vector3()).length();
  return box.clone().intersect(core.clone().expandByScalar(reach));
}

/// Puts the camera so that `box` fills the view, looking from its current
/// direction (or a three-quarter view when it has none). `left`: pixels on the
/// left that a panel covers: the view is centred in the rest of the canvas.
export function frameBox(camera, controls, box, { left = 0, width = 0, height = 0 } = {}) {
  // The free part of the canvas: the optical centre moves to its middle, and
  // its width is what the horizontal field of view has to hold.
  let free = camera.aspect;
  if (width > 0 && height > 0) {
    const inset = Math.min(left, 0.6 * width);
    camera.aspect = width / height;
    camera.setViewOffset(width, height, -inset / 2, 0, width, height);
    free = (width - inset) / height;
  }
  const centre = box.getCenter(new THREE.Vector3());
  const radius = Math.max(1e-9, 0.5 * box.getSize(new THREE.Vector3()).length());
  const direction = camera.position.clone().sub(controls.target);
  if (direction.lengthSq() < 1e-18) direction.set(0.6, 0.5, 0.9);
  direction.normalize();
  const vertical = THREE.MathUtils.degToRad(camera.fov) / 2;
  const horizontal = Math.atan(Math.tan(vertical) * free);
  const distance = 1.08 * radius / Math.sin(Math.min(vertical, horizontal));
  camera.position.copy(centre).addScaledVector(direction, distance);
  camera.near = distance / 1000;
  camera.far = distance * 100;
  camera.updateProjectionMatrix();
  controls.target.copy(centre);
  controls.update();
}

/// 1, 2 or 5 times a power of ten, at least x.
export function roundUp125(x) {
  const p = Math.pow(10, Math.floor(Math.log10(x)));
  for (const k of [1, 2, 5, 10]) if (k * p >= x * (1 - 1e-12)) return k * p;
  return 10 * p;
}

/// A ground grid under `box` (at its lowest y, or z with `up` 'z': presets are
/// z-up, glTF y-up) with cells of a round size, about ten across the model.
/// Returns {grid, cell}.
export function groundGrid(box, up = 'y') {
  const size = box.getSize(new THREE.Vector3());
  const across = up === 'z' ? Math.max(size.x, size.y) : Math.max(size.x, size.z);
  const cell = roundUp125(Math.max(across, 1e-9) / 10);
  const cells = 2 * Math.ceil(0.5 * (across * 1.6) / cell);
  const grid = new THREE.GridHelper(cells * cell, cells, 0x56606c, 0x343b44);
  const centre = box.getCenter(new THREE.Vector3());
  if (up === 'z') {
    grid.rotation.x = Math.PI / 2;  // the helper lies in x-z
    grid.position.set(centre.x, centre.y, box.min.z);
  } else {
    grid.position.set(centre.x, box.min.y, centre.z);
  }
  return { grid, cell };
}
