// The camera on the design: Fit view (f) frames it over its whole motion with a
// ground grid under it, Fit t (Shift+F) as shown at the slider's t, in the part
// of the canvas the panel leaves free. An edit, a repair or another design
// keeps the camera where the user put it; only a design that left the free
// part of the view (or became a speck in it) is framed again. Every refit after
// the first is animated: the view glides, it does not jump. The framing goes by
// the handles (the design's input) and the surface around them: a vertex that
// passes near infinity next to a flexion limit neither frames nor refits.
import * as THREE from 'three';
import { clampToCore, frameBox, groundGrid } from '../framing.js';
import { $ } from './util.js';

const glideMs = 350;

/// `isDragging()`: a handle is being dragged (no refit then).
export function createFraming({ renderer, scene, camera, controls, state, designer, handles, surface, isDragging, requestRender }) {
  let framed = false;  // the first framing happened
  let ground = [];     // the ground grid and the axes, placed under the whole motion at each Fit view
  let glide = null;    // the camera's move under way: {from, to, start}

  /// The handles' positions (the design's input: always finite, unlike a vertex
  /// that passes near infinity next to a flexion limit), less the ones far out
  /// (beyond 20 times the median distance from their median point: an apex where
  /// two nearly parallel lines meet, next to an oversized panel, would make the
  /// design a speck).
  function handlePoints() {
    const points = [], m = new THREE.Matrix4();
    for (const mesh of handles.meshes()) {
      for (let k = 0; k < mesh.count; ++k) {
        mesh.getMatrixAt(k, m);
        points.push(new THREE.Vector3().setFromMatrixPosition(m));
      }
    }
    return withoutFarOnes(points);
  }

  /// The points less those beyond 20 times the median distance from their median
  /// point: an apex or a vertex where two nearly parallel lines meet (an
  /// oversized panel, 1e8 units long) would make the design a speck.
  function withoutFarOnes(points) {
    if (points.length < 3) return points;
    const median = (values) => values.slice().sort((a, b) => a - b)[Math.floor(values.length / 2)];
    const centre = new THREE.Vector3(median(points.map((p) => p.x)), median(points.map((p) => p.y)), median(points.map((p) => p.z)));
    const reach = 20 * median(points.map((p) => p.distanceTo(centre)));
    return reach > 0 ? points.filter((p) => p.distanceTo(centre) <= reach) : points;
  }

  /// Everything the design shows over its whole motion (the surface at 9 t across
  /// the flexion interval), or at the slider's t only (`motion` false), and the
  /// handles; not out to where a vertex passes near infinity (within twice the
  /// size of the handles and the shown surface around them), nor to the far
  /// vertices of oversized panels (withoutFarOnes).
  function designBox(motion = true) {
    const surfaceAt = (fractions, box) => {
      for (const f of fractions) {
        const x = designer.evaluate(state.tOf(f));
        if (x.ok === false) continue;
        const points = [];
        for (let i = 0; i + 2 < x.length; i += 3) points.push(new THREE.Vector3(x[i], x[i + 1], x[i + 2]));
        for (const p of withoutFarOnes(points)) box.expandByPoint(p);
      }
      return box;
    };
    const input = new THREE.Box3().setFromPoints(handlePoints());
    const core = clampToCore(surfaceAt([state.fraction], input.clone()), input);
    if (!motion) return core;
    return clampToCore(surfaceAt([0, 1, 2, 3, 4, 5, 6, 7, 8].map((k) => k / 8), core.clone()), core);
  }

  const pose = () => ({ position: camera.position.clone(), target: controls.target.clone() });

  /// Puts the camera at fraction s of the glide (the offset from the target turned
  /// and scaled, the target moved in a line), eased.
  function glideTo(s) {
    const { from, to } = glide;
    const e = s < 0.5 ? 2 * s * s : 1 - 2 * (1 - s) * (1 - s);
    const a = from.position.clone().sub(from.target), b = to.position.clone().sub(to.target);
    const length = a.length() * Math.pow(b.length() / a.length(), e);
    const direction = a.normalize().lerp(b.normalize(), e);
    if (direction.lengthSq() < 1e-12) direction.copy(b);
    controls.target.lerpVectors(from.target, to.target, e);
    camera.position.copy(controls.target).addScaledVector(direction.normalize(), length);
    camera.lookAt(controls.target);
    requestRender();
  }

  function step() {
    if (!glide) return;
    const s = Math.min(1, (performance.now() - glide.start) / glideMs);
    glideTo(s);
    if (s < 1) requestAnimationFrame(step);
    else { glide = null; controls.update(); requestRender(); }
  }
  // The user takes the camera: the glide stops where it is.
  controls.addEventListener('start', () => { glide = null; });

  /// Frames the design over its motion (Fit view, f), or as shown at the slider's
  /// t (Fit t, Shift+F: larger, for editing), in the part of the canvas the panel
  /// leaves free; `animate` false: at once (the first framing, a resized window).
  function fitView({ motion = true, animate = true } = {}) {
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
    const from = pose();  // where the camera is now (mid-glide, too)
    frameBox(camera, controls, box, { left: panel.right + 8, width: canvas.clientWidth, height: canvas.clientHeight });
    const to = pose();
    if (animate && framed && from.position.distanceTo(to.position) + from.target.distanceTo(to.target) > 0) {
      glide = { from, to, start: performance.now() };
      glideTo(0);
      requestAnimationFrame(step);
    } else {
      glide = null;
    }
    framed = true;
    requestRender();
  }

  /// Refits (animated) when the design left the free part of the view (the canvas
  /// right of the panel): a handle out by more than a few per cent of it, or a
  /// fifth of the surface's vertices (a vertex alone far out next to a flexion
  /// limit does not count); or when the handles became a speck in it (under a
  /// twentieth of it each way: another design loaded into a view framed for a
  /// much larger one). Never while dragging. Returns whether it refitted.
  function refitIfOutside() {
    if (isDragging() || !framed || glide) return false;
    const rect = renderer.domElement.getBoundingClientRect(), panel = $('panel').getBoundingClientRect();
    const left = Math.min(panel.right, rect.left + 0.6 * rect.width), width = rect.right - left, height = rect.height;
    const slack = 0.04, p = new THREE.Vector3();
    const out = (q) => {
      p.copy(q).project(camera);
      if (p.z > 1) return true;  // behind the camera
      const sx = rect.left + (p.x + 1) / 2 * rect.width, sy = rect.top + (1 - p.y) / 2 * rect.height;
      return sx < left - slack * width || sx > rect.right + slack * width || sy < rect.top - slack * height || sy > rect.bottom + slack * height;
    };
    const points = handlePoints();
    const x = surface.positions(), v = new THREE.Vector3();
    let outside = 0;
    for (let i = 0; i + 2 < x.length; i += 3) if (out(v.set(x[i], x[i + 1], x[i + 2]))) ++outside;
    const gone = points.some(out) || outside > 0.2 * (x.length / 3);
    const seen = new THREE.Box2();
    for (const q of points) {
      p.copy(q).project(camera);
      seen.expandByPoint(new THREE.Vector2(p.x * rect.width / 2, p.y * rect.height / 2));
    }
    const size = seen.getSize(new THREE.Vector2());
    const speck = points.length > 0 && size.x < 0.05 * width && size.y < 0.05 * height;
    if (gone || speck) fitView();
    return gone || speck;
  }

  window.addEventListener('keydown', (e) => {
    if (e.target instanceof HTMLTextAreaElement || e.target instanceof HTMLInputElement || e.ctrlKey || e.metaKey) return;
    if (e.key === 'f') fitView();
    else if (e.key === 'F') fitView({ motion: false });
  });
  window.addEventListener('resize', () => { if (state.info) fitView({ animate: false }); });
  $('fit').addEventListener('click', () => fitView());
  $('fit-t').addEventListener('click', () => fitView({ motion: false }));

  return {
    fitView,
    refitIfOutside,
    get framed() { return framed; },
    /// The camera is gliding to a new framing.
    get moving() { return glide !== null; },
    /// The camera's distance from the point it orbits.
    distance: () => camera.position.distanceTo(controls.target),
  };
}
