// window.phedraDesigner: the page as tests/js/designer_test.mjs and
// bench/designer.mjs see it (read what is shown, edit as the hand does, time
// drag steps). Nothing on the page uses it.
import * as THREE from 'three';
import { $, clone } from './util.js';

/// `parts`: the page's modules (see designer.js) and its apply / applyEdit.
export function installApi({ camera, renderer, state, designer, surface, handles, loop, dragging, checks, files, framing, thickness, energy, apply, applyEdit }) {
  const tOf = (f) => state.tOf(f);
  window.phedraDesigner = {
    ready: state.info !== null,
    info: () => state.info,
    /// Hinges coloured mountain / valley at the slider's t.
    folds: () => surface.foldCounts,
    preset: () => clone(state.preset),
    presetText: () => JSON.stringify(state.preset, null, 2) + '\n',
    message: () => $('message').textContent,
    labelText: () => ($('label').hidden ? '' : $('label').textContent),
    t: () => tOf(state.fraction),
    vertex: (k) => surface.vertex(k),
    /// Every vertex at the slider's t in double precision, straight from the core.
    positions: () => Array.from(designer.evaluate(tOf(state.fraction))),
    handlePosition: (kind, index) => handles.handlePosition(kind, index)?.toArray() ?? null,
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
      const p = handles.handlePosition(kind, index);
      return p ? handles.screenOf(p) : null;
    },
    apply: (p) => apply(p),
    /// The Thick panels box: its report (null before Show plates), whether the plates show, their triangles as drawn.
    thick: () => thickness.report,
    energy: () => energy.result,
    platesShown: () => thickness.shown,
    plateTriangleCount: () => thickness.triangles().length / 9,
    /// The camera's distance from the point it orbits, and whether it is gliding to a new framing.
    cameraDistance: () => framing.distance(),
    cameraMoving: () => framing.moving,
    /// The handle under the pointer and the one selected ({key, index} or null), the highlighted panel (-1: none).
    hoveredHandle: () => handles.hovered,
    selectedHandle: () => handles.selected,
    highlightedPanel: () => surface.highlighted,
    /// The name shown next to the hovered or selected handle ('' when none).
    handleLabel: () => ($('handle-label').hidden ? '' : $('handle-label').textContent),
    /// What the last repair did to t*: {tStarBefore, tStarAfter, moved, freed} or null.
    lastRepair: () => checks.lastRepair,
    /// One drag step as the hand makes it: {key, index, value: [x, y, z] (a height: [h, 0, 0])}.
    edit: (edit) => applyEdit(edit),
    /// designer.keep's answer to the last keep-buildable step.
    lastKeep: () => checks.lastKeep,
    figures: () => state.figures,
    /// The last buildability report (null while it is computed), the panels shown
    /// red (not simple) and orange (colliding at the slider's t).
    buildability: () => state.buildability,
    invalidPanels: () => [...state.invalidPanels].sort((a, b) => a - b),
    collidingPanels: () => [...state.collidingPanels].sort((a, b) => a - b),
    /// Where the slider is: a fraction of the flexion interval in [0, 1].
    fraction: () => state.fraction,
    /// Moves the slider to t (as a user would) and waits for the colours.
    setT: (t) => {
      state.fraction = state.fractionOf(t);
      $('slider').value = String(Math.round(state.fraction * 1000));
      $('slider').dispatchEvent(new Event('input'));
      $('slider').dispatchEvent(new Event('change'));
    },
    /// The bar of the buildable part: [left, width] in % of the slider, or null.
    buildableBar: () => ($('buildable-part').hidden ? null : [parseFloat($('buildable-part').style.left), parseFloat($('buildable-part').style.width)]),
    whyText: () => ($('why').hidden ? '' : $('why-list').textContent),
    glbSize: () => files.glbBytes().byteLength,
    fold: () => designer.fold(5),
    /// The resolution a drag would use now (a fraction of the full one) and the timed full draw (ms).
    dragResolution: () => ({ ratio: loop.chooseDragRatio(), drawCost: loop.drawCost, canvas: [renderer.domElement.width, renderer.domElement.height] }),
    /// Records every animation frame (its start, the time its work took, whether it
    /// applied an edit) until stopFrames() returns the log.
    recordFrames: () => loop.recordFrames(),
    stopFrames: () => loop.stopFrames(),
    /// Times `runs` drag steps of trajectory point 1 through the code a drag runs:
    /// milliseconds (median, worst) of `core` (Designer.set, info, evaluate), `step`
    /// (the frame's applyEdit: the core, the upload of the positions, the handles and
    /// labels), `full` (the step and a draw at full resolution, waited for) and
    /// `frame` (the same at the resolution a drag uses, `ratio` of the full one);
    /// for reference `load`, an edit through the preset's text (sign toggles, mode
    /// changes, the JSON editor); `keep`, the step of a keep-buildable drag
    /// (Designer.keep: the check at t*), and `keepProjection`, such steps of a
    /// height dragged where panels would cross (the other heights projected, or
    /// the handle stopped: `projected`, `clamped` count them; `kept`: the keep
    /// steps that needed neither).
    measure(runs) {
      const start = clone(state.preset);
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
      const wasDragging = dragging.current;
      dragging.current = { kind: 'trajectory', index: 1 };  // as while the hand moves: nothing settles
      const core = time((k) => {
        designer.set('trajectory', 1, ...moved(k));
        designer.info();
        designer.evaluate(tOf(state.fraction));
      });
      const step = time((k) => applyEdit({ key: 'trajectory', index: 1, value: moved(k) }));
      // A frame waits for the rasterizer (a pixel read back): at full resolution, and
      // at the resolution a drag uses (the same unless the full one does not fit).
      const drawn = (k) => {
        applyEdit({ key: 'trajectory', index: 1, value: moved(k) });
        loop.timedDraw();
      };
      const full = time(drawn);
      loop.beginDrag();
      const ratio = loop.dragRatio;
      const frame = time(drawn);
      loop.endDrag();
      // Keep-buildable steps (issue 14): the check at t* (simple panels, no
      // collision), and the projection of the apex heights when it fails.
      $('keep').checked = true;
      let projected = 0, clamped = 0, kept = 0;
      const keep = time((k) => {
        applyEdit({ key: 'trajectory', index: 1, value: moved(k) });
        kept += checks.lastKeep?.how === 'already' ? 1 : 0;  // buildable as the hand put it
      });
      // A height dragged where its panels would cross (z1 below z2: the '+' faces
      // of that column cross): the other heights follow, or the handle stops.
      apply(start);
      const keepProjection = time((k) => {
        applyEdit({ key: 'apex_heights', index: 1, value: [start.apex_heights[2] - 0.1 - 0.01 * k, 0, 0] });
        projected += checks.lastKeep?.projected ? 1 : 0;
        clamped += checks.lastKeep?.clamped ? 1 : 0;
      });
      $('keep').checked = false;
      checks.forgetHeld();
      const load = time((k) => {
        const c = clone(start);
        c.trajectory[1] = moved(k);
        designer.load(JSON.stringify(c));
        designer.info();
        designer.evaluate(tOf(state.fraction));
      });
      dragging.current = wasDragging;
      apply(start);
      return { vertices: state.info.vertices, panels: state.info.faces, core, step, full, frame, ratio, load, keep, kept, keepProjection, projected, clamped };
    },
  };
}
