// Dragging a handle with the pointer: which handle is picked (the one nearest
// the pointer on screen, lit and named while the pointer hovers it), where the
// pointer puts it (an apex along the apex line, a direction in its profile's
// plane, the rest in the plane facing the camera), and the edit that follows.
// The newest edit waits for the next frame (takePending); the release applies
// it, records the drag as one undoable edit and lets the design settle.
import * as THREE from 'three';
import { fieldOf } from './edits.js';
import { axisOf } from './handles.js';
import { clone } from './util.js';

/// `loop`: the render loop (lower resolution while dragging); `applyEdit(edit)`:
/// one drag step through the core; `settle()`: what follows when the hand stops.
export function createDragging({ renderer, camera, controls, state, handles, loop, applyEdit, settle }) {
  const raycaster = new THREE.Raycaster();
  let drag = null;
  let pending = null;

  function rayAt(event) {
    const rect = renderer.domElement.getBoundingClientRect();
    const ndc = new THREE.Vector2(((event.clientX - rect.left) / rect.width) * 2 - 1, -((event.clientY - rect.top) / rect.height) * 2 + 1);
    raycaster.setFromCamera(ndc, camera);
    return raycaster.ray;
  }

  // The handle the pointer would pick lights up, named (handles drawn close
  // together are told apart before the press, not after).
  renderer.domElement.addEventListener('pointermove', (event) => {
    if (drag || event.buttons) return;
    const near = handles.nearest(event.clientX, event.clientY);
    handles.hover(near);
    renderer.domElement.style.cursor = near ? 'grab' : '';
  });
  renderer.domElement.addEventListener('pointerleave', () => {
    if (drag) return;
    handles.hover(null);
    renderer.domElement.style.cursor = '';
  });

  renderer.domElement.addEventListener('pointerdown', (event) => {
    if (event.button !== 0) return;
    rayAt(event);
    // The handle whose centre is nearest the pointer on screen (they overlap where
    // heights are close), within a few pixels: not the nearest in depth.
    const hit = handles.nearest(event.clientX, event.clientY);
    if (!hit) return;
    const { key, index, kind } = hit;
    handles.hover(hit);
    renderer.domElement.style.cursor = 'grabbing';
    const at = handles.handlePosition(key, index);
    const a = axisOf(state.preset);
    // Where the pointer puts the handle: an apex moves along the apex line (the
    // point of it nearest the pointer's ray), a direction handle in the plane of
    // its profile's directions (orthogonal to the axis) unless that plane is seen
    // edge-on, everything else in the plane facing the camera.
    const facing = camera.getWorldDirection(new THREE.Vector3());
    const edgeOn = Math.abs(facing.dot(a)) < 0.15;
    const normal = kind === 'direction' && !edgeOn ? a : facing;
    drag = { kind, key, index, plane: new THREE.Plane().setFromNormalAndCoplanarPoint(normal, at),
             line: kind === 'apex' ? { foot: at.clone().addScaledVector(a, -at.dot(a)), axis: a } : null,
             before: clone(state.preset) };
    controls.enabled = false;
    renderer.domElement.setPointerCapture(event.pointerId);
    loop.beginDrag();
  });

  renderer.domElement.addEventListener('pointermove', (event) => {
    if (!drag) return;
    const ray = rayAt(event);
    let point = null;
    if (drag.line) {
      point = new THREE.Vector3();
      const { foot, axis } = drag.line, far = 1e4 * state.info.model_size;
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
    renderer.domElement.style.cursor = 'grab';
    if (pending) {
      applyEdit(pending);
      pending = null;
    }
    if (JSON.stringify(before) !== JSON.stringify(state.preset)) state.remember(before, `drag of ${fieldOf({ key, index })}`);
    loop.endDrag();
    settle();
  }
  renderer.domElement.addEventListener('pointerup', release);
  renderer.domElement.addEventListener('pointercancel', release);

  /// The edit that puts the dragged handle at `point`: {key, index, value}.
  function edited(handle, point) {
    const preset = state.preset;
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

  return {
    /// The drag under way ({kind, key, index, ...}) or null; measurements set one
    /// ({kind, index}) to run steps as while the hand moves (nothing settles).
    get current() { return drag; },
    set current(d) { drag = d; },
    /// The newest edit the pointer asked for since the last frame (then none), or null.
    takePending() {
      const edit = pending;
      pending = null;
      return edit;
    },
  };
}
