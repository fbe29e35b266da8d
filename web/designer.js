// phedra designer: edit a preset's control polylines in 3D and see the P-hedron
// fold, live. The geometry comes from the phedra core itself, compiled to
// WebAssembly (wasm/phedra.mjs, scripts/build-wasm.sh): every edit rebuilds the
// design from the preset exactly as `phedra` does, so the messages are the
// CLI's, and a saved preset gives the same `phedra sample` result.
//
// This file wires the page's modules (designer/) and holds the two ways an
// edit reaches the core: apply (a whole preset: Designer.load) and applyEdit
// (one drag step: Designer.set or keep).
//   state.js         the design shown, what the core said of it, undo and redo (pure data)
//   edits.js         presets as data: heights, fields, modes, structural edits (pure)
//   render.js        the render loop and the drag-resolution budget
//   surface.js       the panels, outlines and mountain / valley hinges in the scene
//   handles.js       the handles: placing them, finding them, on screen, hovered and selected
//   drag.js          dragging a handle with the pointer
//   camera.js        Fit view, Fit t, the ground grid, a (gliding) refit when the design left the view
//   panel.js         the title, status, causes, figures, slider labels, signs, Undo / Redo state
//   buildability.js  the buildability report and figures, Repair, keep buildable
//   targets.js       the Targets box: the figures phedra optimize targets, live, and Optimize
//   thickness.js     the Thick panels box: the plates, their thick interval, drawn at t
//   energy.js        the Energy box: the energy landscape of the motion from a rest state
//   modes.js         mode, grid and row sizes, profiles and apexes
//   files.js         save, open, drop, shipped presets, .glb / FOLD / PNG, the first preset
//   api.js           window.phedraDesigner, for tests and measurements
import { createStage } from './scene.js';
import createPhedra from './wasm/phedra.mjs';
import { installApi } from './designer/api.js';
import { createBuildability } from './designer/buildability.js';
import { createFraming } from './designer/camera.js';
import { createDragging } from './designer/drag.js';
import { refOfField, tStarField, withSign } from './designer/edits.js';
import { createFiles } from './designer/files.js';
import { createHandles } from './designer/handles.js';
import { createModeControls } from './designer/modes.js';
import { createPanel } from './designer/panel.js';
import { createRenderLoop } from './designer/render.js';
import { DesignState, travelText } from './designer/state.js';
import { createSurface } from './designer/surface.js';
import { createTargets } from './designer/targets.js';
import { createThickness } from './designer/thickness.js';
import { createEnergy } from './designer/energy.js';
import { $, refusal } from './designer/util.js';

// --- the stage (before the core loads) ---------------------------------------
// No MSAA: it costs more than the whole motion update in a software-rendered browser.
const stage = createStage({ antialias: false });
stage.camera.up.set(0, 0, 1);  // presets are z-up
const loop = createRenderLoop(stage);
const { requestRender } = loop;

// --- the core and the modules --------------------------------------------------
const core = await createPhedra();
const designer = new core.Designer();
const state = new DesignState();

const handles = createHandles({ ...stage, state, designer, requestRender });
const surface = createSurface({ scene: stage.scene, state, designer, requestRender, showT: (t) => panel.showT(t), screenOf: (p) => handles.screenOf(p),
                                onPositions: (t) => { thickness?.follow(t); energy?.follow(t); } });
const panel = createPanel({
  state,
  locate: (field) => { const p = handles.handleOf(field); return p ? handles.screenOf(p) : null; },
  onSign: (k, sign) => apply(withSign(state.preset, k, sign)),
  onCause: showCause,
});
state.onHistory = () => { panel.updateUndo(); panel.showTitle(); };
const dragging = createDragging({ ...stage, state, handles, loop, applyEdit, settle });
const framing = createFraming({ ...stage, state, designer, handles, surface, isDragging: () => dragging.current !== null, requestRender });
const checks = createBuildability({ state, designer, panel, surface, apply, onFigures: () => targets.refresh() });
const targets = createTargets({ state, designer, apply });
const thickness = createThickness({ scene: stage.scene, state, designer, surface, requestRender,
                                    onChange: () => { panel.showBuildability(); panel.showMessage(); } });
const energy = createEnergy({ state, designer });
// One section open at a time (Targets, Thick panels, Energy): the panel stays within a 768 px window.
const sections = ['targets', 'thickness', 'energy'].map((id) => $(id));
// An opened section is brought up to just under the design line, slider and status (which stay).
for (const d of sections) {
  d.addEventListener('toggle', () => {
    if (!d.open) return;
    for (const o of sections) if (o !== d) o.open = false;
    const below = $('panel-head').getBoundingClientRect().bottom;
    $('panel').scrollTop += d.getBoundingClientRect().top - below - 4;
  });
}

/// The slider at t* (the input configuration: the surface passes through the
/// handles); `before`: t* of the previous design, to say when an edit moved it
/// and `why` (else: the edit moved the apex t measures).
function followTStar(before, why = null) {
  state.fraction = state.tStarFraction();
  panel.showFraction();
  panel.noteTStar(before, why);
}

/// A cause of the list clicked: its panel highlighted in 3D, the handle of the
/// field it says to change selected (named, larger, yellow).
function showCause({ panel: k, field }) {
  surface.highlightPanel(k);
  handles.select(field ? refOfField(field) : null);
}

/// Rebuilds the design from `candidate`; on refusal keeps the shown design and
/// reports. An accepted edit goes into the undo history (`what` says what it
/// was) and the slider moves to the new t*, where the surface passes through the
/// handles; with `keepT` (a repair) it stays at the t shown, when the new
/// interval holds it (`tStarWhy`: why t* moved, if it did).
function apply(candidate, { keepFigures = false, what = 'edit', record = true, keepT = false, tStarWhy = null } = {}) {
  const result = designer.load(JSON.stringify(candidate));
  if (!result.ok) {
    state.failure = { field: result.field, message: result.message };
    panel.showMessage();
    return false;
  }
  state.failure = null;
  if (record && state.preset) state.remember(state.preset, what);
  const before = state.info ? state.info.t_star : null;
  const shownT = state.info ? state.tOf(state.fraction) : null;
  state.preset = candidate;
  panel.showRepair('');  // a new design: an earlier repair's message no longer applies (Repair and Undo say theirs after)
  if (what !== 'optimize') targets.show('');  // nor an earlier optimization's
  state.info = designer.info();
  state.faces = Uint32Array.from(designer.faces());
  state.invalidPanels = new Set(Array.from(designer.invalidPanels()));
  state.collidingPanels = new Set();
  // (another design loaded: its t* is its own, nothing moved it)
  followTStar(what.startsWith('load of') ? null : before, tStarWhy);
  if (keepT && shownT !== null && shownT >= state.info.t_lambda && shownT <= state.info.t_mu) {
    state.fraction = state.fractionOf(shownT);
    panel.showFraction();
  }
  handles.select(null);
  handles.size();
  surface.rebuild();
  handles.place();
  panel.updatePanel();
  loop.recalibrate();
  if (!keepFigures) checks.scheduleFigures();
  thickness.refresh();
  energy.refresh();
  panel.showMessage();
  if (framing.framed) framing.refitIfOutside();
  return true;
}

/// Applies one drag step through the core without the round trip through JSON
/// text (the hot path while dragging); the topology does not change.
function applyEdit(edit) {
  const held = tStarHeld(edit);
  const result = checks.step(edit);
  if (!result.ok) {
    state.failure = { field: result.field, message: result.message };
    panel.showMessage();
    return false;
  }
  state.failure = null;
  const before = state.info.t_star;
  state.info = designer.info();
  followTStar(before, result.projected && !held
    ? `keep buildable moved the apex ${state.info.moving_apex} that t measures, to keep every panel simple` : null);
  state.buildability = null;  // the sweep follows when the drag ends (settle)
  surface.updateInvalidPanels();
  surface.clearCollisions();
  surface.updatePositions();
  handles.place();
  panel.updateLabels();
  panel.showMessage();
  return true;
}

/// The edit moves the field that defines t* itself (the user's hand moves t*).
function tStarHeld(edit) {
  const star = tStarField(state.preset, state.info);
  return star !== null && star.key === edit.key && star.index === edit.index;
}

/// Once a drag ends: the preset's text and the check figures follow (both cost
/// more than a drag step on a large model, so they wait for the hand to stop).
function settle() {
  panel.showPresetText();
  framing.refitIfOutside();
  checks.scheduleFigures();
  thickness.refresh();
  energy.refresh();
}

// --- undo and redo ---------------------------------------------------------------
/// Undo or redo (`which`) through apply, and says which it was.
function travel(which) {
  const show = (p) => apply(p, { record: false });
  const moved = which === 'undo' ? state.undo(show) : state.redo(show);
  if (moved?.done) panel.showRepair(travelText(moved));
}
const undo = () => travel('undo');
const redo = () => travel('redo');
$('undo').addEventListener('click', undo);
$('redo').addEventListener('click', redo);
window.addEventListener('keydown', (e) => {
  if (!(e.ctrlKey || e.metaKey) || e.target instanceof HTMLTextAreaElement || e.target instanceof HTMLInputElement) return;
  const key = e.key.toLowerCase();
  if (key === 'z' && !e.shiftKey) { e.preventDefault(); undo(); }
  else if ((key === 'z' && e.shiftKey) || key === 'y') { e.preventDefault(); redo(); }
});

// --- the slider and the preset's text ------------------------------------------
// Large models: the colliding panels follow when the slider is let go, not at
// every pause of the hand (their search then takes longer than a frame).
const largeModel = () => state.info.faces > 3000;
$('slider').addEventListener('input', (e) => {
  state.fraction = Number(e.target.value) / 1000;
  surface.updatePositions();
  if (!largeModel()) surface.scheduleCollisions();
});
$('slider').addEventListener('change', () => { if (largeModel()) surface.scheduleCollisions(); });
$('json').addEventListener('input', (e) => {
  try {
    apply(JSON.parse(e.target.value));
  } catch (error) {
    state.failure = { field: '', message: `preset JSON: ${error.message}` };
    panel.showMessage();
  }
});
createModeControls({ state, apply });
const files = createFiles({ ...stage, state, designer, panel, apply });

// --- start -----------------------------------------------------------------
const initial = await files.initialPreset();
state.loadedName = initial.preset.name ?? null;
state.fileName = initial.file ?? null;
if (!apply(initial.preset, { record: false })) {
  $('message').textContent = `the preset is refused: ${refusal(state.failure)}`;
}
if (state.info) {
  // Start at t*, where the handles (the input) lie on the surface.
  state.fraction = state.tStarFraction();
  panel.showFraction();
  surface.updatePositions();
  stage.camera.position.set(1.6, -2.2, 1.2);  // the direction fitView looks from at first
  framing.fitView({ animate: false });
}
window.addEventListener('keydown', (e) => {
  if (e.key === 'Escape') {
    handles.select(null);
    surface.highlightPanel(-1);
    for (const item of document.querySelectorAll('#why-list .selected')) item.classList.remove('selected');
  }
});
loop.start({
  // The newest drag step, once a frame; when the hand has stopped meanwhile, the design settles.
  step: () => {
    const edit = dragging.takePending();
    if (!edit) return false;
    if (applyEdit(edit) && !dragging.current) settle();
    return true;
  },
  dragging: () => dragging.current !== null,
  // The names on the page follow the camera.
  drawn: () => { handles.updateLabels(); surface.updatePanelLabel(); },
});

installApi({ ...stage, state, designer, surface, handles, loop, dragging, checks, files, framing, thickness, energy, apply, applyEdit });
