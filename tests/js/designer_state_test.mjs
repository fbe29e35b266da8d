// The designer's state, undo and redo, and its edits of presets, in plain node
// (no browser, no three.js, no WebAssembly): web/designer/state.js,
// web/designer/edits.js and the .glb reader of web/designer/files.js; and the
// pages' pure helpers: web/text.js (number formats, titles) and web/plot.js
// (the viewer's fold-angle axis).
// The core's part (does it accept a design?) is played by a `show` function
// that accepts or refuses, as the page's apply does.
// usage: node tests/js/designer_state_test.mjs
import { readFileSync } from 'node:fs';
import { DesignState, historyLimit, travelText } from '../../web/designer/state.js';
import {
  cellZ, fieldOf, fieldsInHint, gridHeights, heightRefs, modeOf, modeSwitch, pointerOf, refOfField, rowOf, setAt, switchMode,
  tStarField, withApexAdded, withApexRemoved, withGridSize, withProfileAdded, withProfileRemoved, withRowSize, withSign,
} from '../../web/designer/edits.js';
import { presetInGlb } from '../../web/designer/files.js';
import { energyPlot, foldAnglePlot, niceAxis } from '../../web/plot.js';
import { canonicalPreset, decimals4, makerHint, pageTitle, significant4, statusSummary, withArticle, withNumbers } from '../../web/text.js';

const failures = [];
let checks = 0;
const check = (ok, what) => { ++checks; if (!ok) failures.push(what); };
const same = (a, b) => JSON.stringify(a) === JSON.stringify(b);
const equal = (a, b, what) => check(same(a, b), `${what}: ${JSON.stringify(a)}, expected ${JSON.stringify(b)}`);
/// Lists of numbers equal within 1e-12.
const close = (a, b, what) => check(a.length === b.length && a.every((x, i) => Math.abs(x - b[i]) < 1e-12), `${what}: ${a}, expected ${b}`);
const section = (name, body) => {
  try { body(); } catch (error) { failures.push(`${name}: threw ${error.stack}`); }
};
const preset = (file) => JSON.parse(readFileSync(new URL(`../../presets/${file}`, import.meta.url), 'utf8'));
const open = preset('default.json');

/// A page without the core: designs are numbered ({n}); `refuse` makes show() refuse.
function page(options) {
  const state = new DesignState(options);
  let refuse = false, shown = 0, notified = 0;
  state.onHistory = () => { ++notified; };
  const show = (p) => { ++shown; if (refuse) return false; state.preset = p; return true; };
  /// An accepted edit, as apply records it: the previous design goes into the history.
  const edit = (next, what = `edit ${next.n}`) => { state.remember(state.preset, what); state.preset = next; };
  return {
    state, show, edit,
    undo: () => state.undo(show),
    redo: () => state.redo(show),
    refuse: (r) => { refuse = r; },
    get shown() { return shown; },
    get notified() { return notified; },
  };
}

section('an empty history', () => {
  const p = page();
  p.state.preset = { n: 0 };
  check(!p.state.canUndo && !p.state.canRedo && !p.state.edited, 'a new state has something to undo or redo');
  equal(p.state.undoTitle(), 'nothing to undo', 'undo title of an empty history');
  equal(p.state.redoTitle(), 'nothing to redo', 'redo title of an empty history');
  equal(p.undo(), null, 'undo with nothing to undo');
  equal(p.redo(), null, 'redo with nothing to redo');
  equal(p.state.preset, { n: 0 }, 'the design after undo and redo with nothing to do');
  check(p.shown === 0, `undo / redo with nothing to do rebuilt a design ${p.shown} times`);
  check(p.notified === 0, `undo / redo with nothing to do notified ${p.notified} times`);
  equal(historyLimit, 500, 'the default history limit');
  equal(p.state.limit, 500, 'a new state\'s history limit');
});

section('edits, undo, redo', () => {
  const p = page();
  p.state.preset = { n: 0 };
  for (let n = 1; n <= 3; ++n) p.edit({ n });
  check(p.notified === 3, `3 edits notified ${p.notified} times`);
  equal(p.state.history.map((e) => e.preset.n), [0, 1, 2], 'the history after 3 edits');
  check(p.state.canUndo && !p.state.canRedo && p.state.edited, 'after 3 edits: undo, no redo');
  equal(p.state.undoTitle(), 'undo the last edit 3 (Ctrl+Z)', 'undo title');

  equal(p.undo(), { what: 'edit 3', verb: 'undone', done: true }, 'the first undo');
  equal(p.state.preset, { n: 2 }, 'the design after one undo');
  check(p.state.canRedo, 'nothing to redo after an undo');
  equal(p.state.redoTitle(), 'redo the edit 3 (Ctrl+Shift+Z)', 'redo title after an undo');
  equal(p.state.undoTitle(), 'undo the last edit 2 (Ctrl+Z)', 'undo title after an undo');
  equal(p.undo().what, 'edit 2', 'the second undo');
  equal(p.undo().what, 'edit 1', 'the third undo');
  equal(p.state.preset, { n: 0 }, 'the design after undoing everything');
  check(!p.state.canUndo && !p.state.edited, 'something to undo after undoing everything');
  equal(p.undo(), null, 'an undo past the first design');
  equal(p.state.preset, { n: 0 }, 'the design after an undo past the first');
  equal(p.state.future.map((e) => e.preset.n), [3, 2, 1], 'the redo stack after undoing everything');

  equal(p.redo(), { what: 'edit 1', verb: 'redone', done: true }, 'the first redo');
  equal(p.state.preset, { n: 1 }, 'the design after one redo');
  p.redo();
  p.redo();
  equal(p.state.preset, { n: 3 }, 'the design after redoing everything');
  equal(p.redo(), null, 'a redo past the last design');
  equal(p.state.history.map((e) => e.preset.n), [0, 1, 2], 'the history after undoing and redoing everything');
  equal(p.state.history.map((e) => e.what), ['edit 1', 'edit 2', 'edit 3'], 'what the history says after travelling');
});

section('a design opened from a file starts a new history', () => {
  const p = page();
  p.state.preset = { n: 0 };
  for (let n = 1; n <= 3; ++n) p.edit({ n });
  p.undo();
  const before = p.notified;
  // As files.js opens a preset: shown without recording, then a new history.
  p.state.preset = { file: 'grid-3x3' };
  p.state.startHistory();
  check(p.notified === before + 1, 'a new history did not notify the page (Undo and Redo stay enabled)');
  check(!p.state.canUndo && !p.state.canRedo && !p.state.edited, 'undo or redo left after opening a design');
  equal(p.undo(), null, 'an undo right after opening a design');
  equal(p.state.preset, { file: 'grid-3x3' }, 'an undo after opening brought the previous file back');
  p.edit({ n: 7 });
  equal(p.undo().what, 'edit 7', 'an edit of the opened design');
  equal(p.state.preset, { file: 'grid-3x3' }, 'undoing the first edit gives the design as opened');
  equal(p.undo(), null, 'Undo walked back past the opened design');
});

section('a new edit forgets the redo stack', () => {
  const p = page();
  p.state.preset = { n: 0 };
  for (let n = 1; n <= 4; ++n) p.edit({ n });
  p.undo();
  p.undo();
  equal(p.state.preset, { n: 2 }, 'two undos of four edits');
  check(p.state.future.length === 2, `the redo stack holds ${p.state.future.length}`);
  p.edit({ n: 5 });
  check(!p.state.canRedo && p.state.future.length === 0, 'a new edit left something to redo');
  equal(p.redo(), null, 'redo after a new edit');
  equal(p.state.preset, { n: 5 }, 'the design after redo after a new edit');
  equal(p.state.history.map((e) => e.preset.n), [0, 1, 2], 'the history after a new edit');
  p.undo();
  equal(p.state.preset, { n: 2 }, 'undo of the new edit');
});

section('the history keeps copies', () => {
  // A drag edits the shown preset in place (setAt): the history must not follow.
  const p = page();
  p.state.preset = { n: 0, trajectory: [[0, 0, 0], [1, 0, 0]] };
  const before = p.state.preset;
  p.edit({ n: 1 });
  before.trajectory[1][0] = 99;
  equal(p.state.history[0].preset.trajectory[1], [1, 0, 0], 'the recorded design after editing the original in place');
  p.undo();
  p.state.preset.trajectory[0][0] = 42;  // the undone design is shown and edited in place again
  p.redo();
  p.undo();
  equal(p.state.preset.trajectory[0], [42, 0, 0], 'what undo gives back is the design as it was when redo took it');
  p.state.preset.trajectory[0][0] = 7;
  equal(p.state.future[0].preset, { n: 1 }, 'the redo stack after editing the shown design in place');
});

section('a refused undo or redo changes nothing', () => {
  const p = page();
  p.state.preset = { n: 0 };
  p.edit({ n: 1 });
  p.edit({ n: 2 });
  const notified = p.notified;
  p.refuse(true);
  equal(p.undo(), { what: 'edit 2', verb: 'undone', done: false }, 'a refused undo');
  equal(p.state.preset, { n: 2 }, 'the design after a refused undo');
  equal(p.state.history.map((e) => e.preset.n), [0, 1], 'the history after a refused undo');
  check(p.state.future.length === 0, 'a refused undo left something to redo');
  check(p.notified === notified + 1, 'a refused undo did not notify (the buttons stay as they are)');
  p.refuse(false);
  p.undo();
  p.refuse(true);
  equal(p.redo(), { what: 'edit 2', verb: 'redone', done: false }, 'a refused redo');
  equal(p.state.preset, { n: 1 }, 'the design after a refused redo');
  equal(p.state.future.map((e) => e.preset.n), [2], 'the redo stack after a refused redo');
  p.refuse(false);
  p.redo();
  equal(p.state.preset, { n: 2 }, 'redo once the design is accepted again');
});

section('where a design came from', () => {
  // The page names a saved edit after the preset it was loaded as; undo and redo across a load follow.
  const p = page();
  p.state.preset = { n: 0 };
  p.state.loadedName = 'first';
  p.edit({ n: 1 }, 'drag of trajectory[3]');
  p.edit({ n: 2 }, 'load of second.json');
  p.state.loadedName = 'second';
  p.edit({ n: 3 }, 'rename');
  equal(p.state.history.map((e) => e.origin), ['first', 'first', 'second'], 'the origins recorded');
  p.undo();
  equal(p.state.loadedName, 'second', 'the name after undoing an edit of the loaded design');
  p.undo();
  equal(p.state.loadedName, 'first', 'the name after undoing the load');
  p.redo();
  equal(p.state.loadedName, 'second', 'the name after redoing the load');
  p.undo();
  p.undo();
  equal([p.state.preset, p.state.loadedName], [{ n: 0 }, 'first'], 'back at the start');
});

section('the history limit', () => {
  const p = page({ limit: 5 });
  p.state.preset = { n: 0 };
  for (let n = 1; n <= 8; ++n) p.edit({ n });
  check(p.state.history.length === 5, `a history of limit 5 holds ${p.state.history.length}`);
  equal(p.state.history.map((e) => e.preset.n), [3, 4, 5, 6, 7], 'the oldest designs go first');
  let undone = 0;
  while (p.undo()) ++undone;
  check(undone === 5, `${undone} undos with a history of 5`);
  equal(p.state.preset, { n: 3 }, 'the oldest design kept');
  let redone = 0;
  while (p.redo()) ++redone;
  check(redone === 5 && same(p.state.preset, { n: 8 }), `${redone} redos back to ${JSON.stringify(p.state.preset)}`);
  // The default limit with a real preset.
  const q = page();
  q.state.preset = open;
  for (let n = 0; n <= historyLimit; ++n) q.edit({ ...open, apex_heights: [...open.apex_heights.slice(0, -1), n] });
  check(q.state.history.length === historyLimit, `${historyLimit + 1} edits kept ${q.state.history.length}`);
  check(q.state.history[0].preset.apex_heights.at(-1) === 0, 'the default limit dropped the wrong design');
});

section('what the panel says after travelling', () => {
  equal(travelText({ what: 'repair', verb: 'undone' }), 'repair undone: the previous design is back', 'repair undone');
  equal(travelText({ what: 'repair', verb: 'redone' }), 'repair redone', 'repair redone');
  equal(travelText({ what: 'drag of trajectory[3]', verb: 'undone' }), 'drag of trajectory[3] undone', 'drag undone');
});

section('t and the slider', () => {
  const s = new DesignState();
  s.info = { t_lambda: -1, t_mu: 3, t_star: 0 };
  equal([s.tOf(0), s.tOf(0.5), s.tOf(1)], [-1, 1, 3], 'tOf');
  equal([s.fractionOf(1), s.fractionOf(-5), s.fractionOf(7)], [0.5, 0, 1], 'fractionOf (clamped)');
  equal(s.tStarFraction(), 0.25, 'tStarFraction');
  equal(s.fraction, 0.5, 'the first slider position');
});

section('the saved preset', () => {
  const p = page();
  p.state.preset = { ...open };
  p.state.loadedName = 'mixed-signs';
  p.state.info = { kind: 'open P-hedron', faces: 56, t_star: 0.25, t_lambda: 0, t_mu: 1.5 };
  let asked = 0;
  const status = () => { ++asked; return 'buildable over the whole flexion interval'; };
  let saved = p.state.savedPreset('', status);
  check(saved.name === 'mixed-signs' && saved.description === open.description && asked === 0,
    `an unchanged design saved as "${saved.name}" (description changed: ${saved.description !== open.description}, status asked ${asked})`);
  check(saved !== p.state.preset && same({ ...saved, name: open.name }, open), 'the saved preset is not a copy of the shown one');
  check(p.state.savedPreset('mine', status).name === 'mine', 'a typed name is not used');
  p.edit({ ...open, signs: '-----' });
  saved = p.state.savedPreset('mixed-signs', status);
  equal(saved.name, 'mixed-signs-edited', 'an edited design with the loaded name typed');
  equal(saved.signs, '-----', 'the saved preset is the shown one');
  equal(saved.description, 'open P-hedron, 56 panels, t* = 0.2500 in [0.0000, 1.5000]; buildable over the whole flexion ' +
    'interval. Edited in the phedra designer from "mixed-signs".', 'the description of an edited design');
  equal(p.state.savedPreset('spiral', status).name, 'spiral', 'an edited design with a name typed');
  p.state.loadedName = null;
  equal(p.state.savedPreset('', status).name, 'design-edited', 'an edited design that came without a name');
  p.undo();  // the name it was loaded under comes back with the design
  equal(p.state.loadedName, 'mixed-signs', 'the loaded name after undoing the edit');
  saved = p.state.savedPreset('', status);
  check(saved.name === 'mixed-signs' && saved.description === open.description, `after undoing the edit saved as "${saved.name}"`);
});

section('heights and fields', () => {
  const refs = heightRefs(open);
  equal(refs.map((r) => [r.key, r.index, r.value, r.base]), open.apex_heights.map((h, k) => ['apex_heights', k, h, true]), 'heights of the default preset');
  const pair = preset('edge-sharing-pair.json');
  pair.couplings.push({ type: 'face', free_height: 0.7 }, null);
  equal(heightRefs(pair).map((r) => `${fieldOf(r)}=${r.value}${r.base ? ' base' : ''}`),
    ['tube.apex_heights[0]=-2 base', 'tube.apex_heights[1]=3 base', 'tube.apex_heights[2]=-1.4 base', 'tube.apex_heights[3]=2.4 base',
     'couplings[0].free_heights[0]=-0.8', 'couplings[0].free_heights[1]=1.8', 'couplings[1].free_height=0.7'], 'heights of a coupled tube');
  equal(heightRefs(preset('grid-3x3.json')).map(fieldOf).slice(3, 5), ['grid.u_heights[3]', 'grid.w_heights[0]'], 'grid height fields');
  equal(pointerOf({ key: 'couplings.0.free_heights', index: 1 }), '/couplings/0/free_heights/1', 'a JSON pointer');
  equal(pointerOf({ key: 'couplings.1.free_height', index: -1 }), '/couplings/1/free_height', 'a JSON pointer to a number');
  setAt(pair, { key: 'couplings.0.free_heights', index: 1 }, 2.5);
  setAt(pair, { key: 'couplings.1.free_height', index: -1 }, -0.25);
  setAt(pair, { key: 'trajectory', index: 0 }, [9, 8, 7]);
  check(pair.couplings[0].free_heights[1] === 2.5 && pair.couplings[1].free_height === -0.25 && same(pair.trajectory[0], [9, 8, 7]),
    `setAt: ${JSON.stringify([pair.couplings, pair.trajectory[0]])}`);
});

section('modes', () => {
  equal(['default.json', 'grid-3x3.json', 'row-of-cells.json', 'parallelogram-tube.json', 'anti-parallelogram-tube.json'].map((f) => modeOf(preset(f))),
    ['open', 'grid', 'row', 'parallelogram', 'anti-parallelogram'], 'modeOf');
  equal(cellZ(open), open.apex_heights, 'cellZ of an open design');
  equal(cellZ(preset('grid-3x3.json')), [-2, 3, -1.4, 2.4], 'cellZ of a grid');
  equal(cellZ({ trajectory: [] }), [-1.5, 1.0, -0.5, 2.0], 'cellZ of a design without heights');
  equal(gridHeights([0, 10, 1, 12], 3, 1), { u_heights: [0, 1, 2, 3], w_heights: [10, 12] }, 'grid heights keep the first spacing');
  const row1 = rowOf([-2, 3, -1.4, 2.4], 3, 1);
  check(row1.side === 1, `a row on side 1 is on side ${row1.side}`);
  close(row1.free_heights, [-0.8, -0.2, 0.4], 'a row on side 1 (from line 2, spacing 0.6)');
  close(rowOf([-2, 3, -1.4, 2.4], 2, 0).free_heights, [3 + 0.6, 3 + 1.2], 'a row on side 0 (from line 1, spacing 3 - 2.4)');
  const sizes = { cellsU: 2, cellsW: 3, rowCells: 2, rowSide: 1 };
  const grid = switchMode(open, 'grid', sizes);
  check(!('apex_heights' in grid) && !('signs' in grid) && !('tube' in grid) && grid.grid.u_heights.length === 3 && grid.grid.w_heights.length === 4,
    `open -> grid: ${JSON.stringify(grid.grid)}`);
  equal(grid.trajectory, open.trajectory, 'the trajectory kept by a mode switch');
  const anti = switchMode(open, 'anti-parallelogram', sizes);
  const q = anti.tube.apex_heights;
  check(anti.tube.type === 'anti-parallelogram' && q[3] === q[0] + q[2] - q[1], `anti-parallelogram heights ${q}`);
  const row = switchMode(open, 'row', sizes);
  check(row.tube.type === 'parallelogram' && row.row.free_heights.length === 2 && row.row.side === 1, `open -> row: ${JSON.stringify([row.tube, row.row])}`);
  const back = switchMode(preset('parallelogram-tube.json'), 'open', sizes);
  check(back.apex_heights.length === 5 && back.signs === '+++' && !('tube' in back), `tube -> open: ${back.apex_heights} ${back.signs}`);
  // The page's mode memory: open -> grid -> open gives the open design back.
  const memory = {};
  const g = modeSwitch(memory, open, 'grid', sizes);
  const o = modeSwitch(memory, g, 'open', sizes);
  equal(o, open, 'open -> grid -> open');
  check(o !== memory.open, 'the remembered design is handed out, not a copy');
  equal(modeSwitch(memory, o, 'grid', sizes), g, 'grid again: as it was left');
  equal(open.apex_heights, preset('default.json').apex_heights, 'a mode switch changed its input');
  const small = withGridSize(preset('grid-3x3.json'), 1, 2).grid;
  close(small.u_heights, [-2, -1.4], 'the u lines of a 1 x 2 grid');
  close(small.w_heights, [3, 2.4, 1.8], 'the w lines of a 1 x 2 grid');
  equal(withGridSize(open, 2, 2), null, 'a grid size for an open design');
  const row2 = withRowSize(preset('row-of-cells.json'), 1, 2).row;
  check(row2.side === 2, `a row on side 2 is on side ${row2.side}`);
  close(row2.free_heights, [1.8], 'a row of 1 cell on side 2 (from line 3 = 2.4, spacing 2.4 - 3)');
  equal(withRowSize(open, 2, 1), null, 'a row size for an open design');
});

section('structural edits', () => {
  const plus = withProfileAdded(open);
  const n = open.trajectory.length;
  check(plus.trajectory.length === n + 1 && plus.directions.length === n + 1, 'a profile added');
  equal(plus.trajectory[n], open.trajectory[n - 1].map((x, i) => x + (x - open.trajectory[n - 2][i])), 'the new profile continues the last segment');
  equal(plus.directions[n], open.directions[n - 1], 'the new profile\'s direction');
  check(open.trajectory.length === n, 'adding a profile changed its input');
  equal(withProfileRemoved(plus), open, 'a profile added and removed');
  equal(withProfileRemoved({ trajectory: [[0, 0, 0], [1, 0, 0]], directions: [[1, 0, 0], [1, 0, 0]] }), null, 'two profiles removed to one');
  const apex = withApexAdded(open);
  const h = open.apex_heights, k = h.length;
  equal(apex.apex_heights, [...h, h[k - 2] + 0.6 * (h[k - 2] - h[k - 3])], 'an apex added');
  equal(apex.signs, `${open.signs}+`, 'the sign of the new apex');
  equal(withApexRemoved(apex), open, 'an apex added and removed');
  equal(withApexAdded(preset('grid-3x3.json')), null, 'an apex added to a grid');
  equal(withApexRemoved({ ...open, apex_heights: [0, 1, 2], signs: '+' }), null, 'three apexes removed to two');
  equal(withSign(open, 1, '+').signs, '+++-+', 'sign 1 set');
  equal(withSign(open, 4, '-').signs, '+-+--', 'the last sign set');
  equal(open.signs, '+-+-+', 'a sign toggle changed its input');
});

section('the preset in a .glb', () => {
  const glb = (json, magic = 0x46546c67) => {
    const text = Buffer.from(JSON.stringify(json).padEnd(4 * Math.ceil(JSON.stringify(json).length / 4), ' '));
    const bytes = new ArrayBuffer(20 + text.length), view = new DataView(bytes);
    view.setUint32(0, magic, true);
    view.setUint32(4, 2, true);
    view.setUint32(8, bytes.byteLength, true);
    view.setUint32(12, text.length, true);
    view.setUint32(16, 0x4e4f534a, true);  // 'JSON'
    new Uint8Array(bytes, 20).set(text);
    return bytes;
  };
  const text = JSON.stringify(open);
  equal(presetInGlb(glb({ asset: { version: '2.0', extras: { phedra: { preset: text } } } })), text, 'the preset a .glb carries');
  equal(presetInGlb(glb({ asset: { version: '2.0' } })), null, 'a .glb without a preset');
  equal(presetInGlb(glb({ asset: {} }, 0x12345678)), null, 'not a .glb');
  equal(presetInGlb(new ArrayBuffer(8)), null, 'a file too short for a .glb');
});

section('the field that defines t*', () => {
  // t is the axis coordinate of the moving apex: S_1 (index 1) for the default preset.
  const info = { moving_apex: 'S_1', t_star: 1, model_size: 6 };
  equal(tStarField(open, info), { key: 'apex_heights', index: 1, pointer: '/apex_heights/1' }, 'the open P-hedron');
  equal(tStarField(open, { ...info, moving_apex: 'S_0', t_star: -1.5 }), { key: 'apex_heights', index: 0, pointer: '/apex_heights/0' }, 'S_0 moving');
  equal(tStarField(open, { ...info, t_star: 1.4443 }), null, 'a t* no field holds');
  const tube = preset('helix-tube.json');
  equal(tStarField(tube, { moving_apex: 'S_1', t_star: tube.tube.apex_heights[1], model_size: 5 })?.pointer, '/tube/apex_heights/1', 'a tube');
  const grid = preset('grid-3x3.json');
  equal(tStarField(grid, { moving_apex: 'S_0', t_star: grid.grid.u_heights[0], model_size: 5 })?.pointer, '/grid/u_heights/0', 'a grid, S_0');
  equal(tStarField(grid, { moving_apex: 'S_1', t_star: grid.grid.w_heights[0], model_size: 5 })?.pointer, '/grid/w_heights/0', 'a grid, S_1');
});

section('the fields a cause names', () => {
  equal(fieldsInHint('increase trajectory[0][2] (now 0.05) by more than about 0.2299'), ['trajectory[0][2]'], 'a trajectory coordinate');
  equal(fieldsInHint('decrease grid.u_heights[2] (now 1.5) by more than about 0.3'), ['grid.u_heights[2]'], 'a grid height');
  equal(fieldsInHint('raise couplings[0].free_height (now 2)'), ['couplings[0].free_height'], 'a coupling height');
  equal(fieldsInHint('make it the highest or the lowest of the three'), [], 'no field');
  equal(refOfField('trajectory[2][2]'), { key: 'trajectory', index: 2 }, 'the trajectory point of a coordinate');
  equal(refOfField('apex_heights[4]'), { key: 'apex_heights', index: 4 }, 'an apex height');
  equal(refOfField('tube.apex_heights[1]'), { key: 'tube.apex_heights', index: 1 }, 'a tube height');
  equal(refOfField('couplings[1].free_heights[0]'), { key: 'couplings.1.free_heights', index: 0 }, 'a coupling height of a list');
  equal(refOfField('couplings[0].free_height'), { key: 'couplings.0.free_height', index: -1 }, 'a coupling height');
  equal(refOfField('directions'), null, 'a list without an entry');
});

section('one number format a page', () => {
  equal([decimals4(1), decimals4(-1.038229), decimals4(6.75e-16), decimals4(0)], ['1.0000', '-1.0382', '6.75e-16', '0.0000'], 'the designer');
  equal([significant4(-2), significant4(-2.1908197), significant4(9.49e-4), significant4(1347.34)], ['-2', '-2.191', '9.49e-4', '1347'], 'the viewer');
  equal(withNumbers('its transversal edge V_{7,2} V_{8,2} is 1.398e+08 long, 8.477e+07 times the median panel', decimals4),
    'its transversal edge V_{7,2} V_{8,2} is 1.40e+8 long, 8.48e+7 times the median panel', 'an oversized panel\'s numbers stay readable');
  equal([withArticle('bow-tie'), withArticle('oversized'), withArticle('sliver')], ['a bow-tie', 'an oversized', 'a sliver'], 'a shape with its article');
  equal(withNumbers('S_3 (2.2) in profiles 0 and 1 (ratios -0.11111, -0.4655); trajectory[2][2] (now 0.1444)', decimals4),
    'S_3 (2.2000) in profiles 0 and 1 (ratios -0.1111, -0.4655); trajectory[2][2] (now 0.1444)', 'numbers in a text, names kept');
  equal(statusSummary('buildable over the whole flexion interval [-2.19082, -1.06203]', significant4), 'buildable over the whole flexion interval',
    'the whole interval left out (the page shows it)');
  equal(statusSummary('buildable over [0.270226, 1.34734] only (70.3 % of the flexion interval [-1.03823, 1.34734])', decimals4),
    'buildable over [0.2702, 1.3473] only (70.3 % of the flexion interval)', 'a part of it (shares keep their one decimal)');
  equal(statusSummary('buildable over the whole flexion interval [0.1, 0.2] (swept at 40 samples a side)', significant4),
    'buildable over the whole flexion interval (swept at 40 samples a side)', 'a coarse sweep');
});

section('causes in a maker\'s words', () => {
  const said = (h) => { const r = makerHint(h, decimals4); return `${r.verb} ${r.subject}${r.tail}`; };
  equal(said('increase trajectory[2][2] (now 1.5) by more than about 0.32'), 'raise trajectory point 2 by more than 0.3200 (now 1.5000)', 'a trajectory point up');
  equal(said('decrease trajectory[0][1] (now 0) by more than about 1.547e-05'), 'move trajectory point 0 −y by more than 1.55e-5 (now 0.0000)', 'a trajectory point sideways');
  equal(said('decrease apex_heights[3] (now -0.5) by more than about 0.2'), 'lower apex S_3 by more than 0.2000 (now -0.5000)', 'an apex');
  equal(said('increase grid.u_heights[1] (now -1.4) by more than about 0.05'), 'raise u line 1 of the grid by more than 0.0500 (now -1.4000)', 'a grid line');
  equal(said('increase tube.apex_heights[0] (now 2) by more than about 0.1'), 'raise apex S_0 by more than 0.1000 (now 2.0000)', 'a tube apex');
  equal(said('increase couplings[1].free_height (now 2) by more than about 0.1'), 'raise free height of coupling 1 by more than 0.1000 (now 2.0000)', 'a coupling');
  equal(said('increase directions[0][1] (now 0) by more than about 2.803e-06'), 'turn direction of profile 0 (its y up by more than 2.80e-6) (now 0.0000)', 'a direction');
  equal(makerHint('increase trajectory[2][2] (now 1.5) by more than about 0.32', decimals4).field, 'trajectory[2][2]', 'the field kept for the handle');
  equal(makerHint('no single number', decimals4), { verb: '', subject: '', tail: 'no single number', field: null }, 'a text it does not know');
});

section('page titles', () => {
  equal(pageTitle({ name: 'mixed-signs', file: 'default.json', page: 'phedra designer' }),
    { name: 'mixed-signs', file: 'default.json', document: 'mixed-signs (default.json) · phedra designer' }, 'a name and another file name');
  equal(pageTitle({ name: 'grid-3x3', file: 'presets/grid-3x3.json' }).file, '', 'a file named as the preset');
  equal(pageTitle({ name: 'grid-3x3', file: 'grid.glb' }).file, 'grid.glb', 'a .glb of another name');
  equal(pageTitle({ name: null, file: 'x/spiral.json' }).name, 'spiral', 'no name: the file\'s');
  equal(pageTitle({ name: 'mine', file: null }), { name: 'mine', file: '', document: 'mine · phedra' }, 'no file');
  check(canonicalPreset({ b: [1, { d: 2, c: 3 }], a: 1, $schema: 'x' }) === canonicalPreset({ a: 1, b: [1, { c: 3, d: 2 }] }),
    'presets equal but for key order and $schema');
  check(canonicalPreset({ a: [1, 2] }) !== canonicalPreset({ a: [2, 1] }), 'presets that differ');
});

section('the fold-angle axis', () => {
  // The hinge: between -7.8 and -5 degrees, not a flat line on +-180.
  const a = niceAxis(-7.8, -5);
  check(a.lo <= -7.8 && a.hi >= -5 && a.hi - a.lo <= 3 * 2.8, `axis [${a.lo}, ${a.hi}] for [-7.8, -5]`);
  check(a.ticks.length >= 3 && a.ticks.every((t) => t >= a.lo - 1e-9 && t <= a.hi + 1e-9), `ticks ${a.ticks}`);
  for (const [min, max] of [[-180, 180], [0.2, 0.3], [64.06, 126.5], [-35.76, -3.746], [179.2, 179.9], [-1e-9, 1e-9]]) {
    const x = niceAxis(min, max);
    const span = Math.max(max - min, 1);
    check(x.lo <= min && x.hi >= max && x.hi - x.lo <= 3 * span && x.lo >= -180 && x.hi <= 180, `axis [${x.lo}, ${x.hi}] for [${min}, ${max}]`);
  }
  const plot = foldAnglePlot([[0, -7.8], [0.5, -6], [1, -5]], { tLambda: 0, tMu: 1, tStar: 0.25, format: significant4 });
  check(plot.svg.includes('<polyline') && plot.svg.includes('t*') && plot.axis.min === -7.8 && plot.axis.max === -5, 'the plot of three samples');
  check(Math.abs(plot.x(0.25) - (plot.x(0) + 0.25 * (plot.x(1) - plot.x(0)))) < 1e-9, 'the plot\'s t axis');
  // The Energy box's plot: the curve, the rest state, a minimum and a maximum marked.
  const energy = energyPlot([[0, 0.3], [0.3, 0.5], [0.6, 0.2], [0.8, 0], [1, 0.4]],
    [{ t: 0.2, kind: 'maximum', E: 0.5 }, { t: 0.6, kind: 'minimum', E: 0.2 }, { t: 0.8, kind: 'minimum', E: 0, rest: true }],
    { tLambda: 0, tMu: 1, restT: 0.8, format: significant4 });
  check(energy.svg.includes('data-minima="2"') && energy.svg.includes('class="maximum"') &&
        energy.svg.includes('class="rest"') && energy.svg.includes('class="minimum"'), 'the energy plot\'s marks');
});

if (failures.length) {
  for (const f of failures) console.error(`FAIL: ${f}`);
  console.error(`designer state: ${failures.length} of ${checks} checks failed`);
  process.exit(1);
}
console.log(`designer state: ${checks} checks passed`);
