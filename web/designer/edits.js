// Edits of a preset as data: where its heights are, the field a handle edits,
// the modes (open P-hedron, tube, grid, row) and the structural edits of the
// panel's buttons. Pure: every function returns a new preset (or reads one);
// the core decides whether the result is a valid design. Node imports it.
import { clone } from './util.js';

/// The apex heights of the base member (open P-hedron or tube), or null (grid).
export function baseHeights(p) {
  if (Array.isArray(p.apex_heights)) return p.apex_heights;
  if (p.tube && Array.isArray(p.tube.apex_heights)) return p.tube.apex_heights;
  return null;
}

/// Every height of the preset, an axis coordinate each: [{key, index, value, base}]
/// (`key` a dotted path for Designer.set; index -1: the number itself).
export function heightRefs(p) {
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
export const fieldOf = (ref) => ref.key.replace(/\.(\d+)/g, '[$1]') + (ref.index >= 0 ? `[${ref.index}]` : '');

/// The JSON pointer of what an edit {key, index} changes: "/grid/u_heights/2".
export const pointerOf = (edit) => `/${edit.key.replaceAll('.', '/')}${edit.index >= 0 ? `/${edit.index}` : ''}`;

/// Sets what handle `ref` edits in preset `p` (the value the core accepted), in place.
export function setAt(p, ref, value) {
  const parts = ref.key.split('.');
  if (ref.index < 0) {
    const last = parts.pop();
    parts.reduce((o, k) => o[k], p)[last] = value;
  } else {
    parts.reduce((o, k) => o[k], p)[ref.index] = value;
  }
}

/// The mode a preset is in (the mode selector's value).
export const modeOf = (p) => (p.grid ? 'grid' : p.row ? 'row' : p.tube ? p.tube.type : 'open');

/// A row of `cells` face-coupled cells on `side` of the tube with apexes z: the
/// new cell shares the tube's line z[side + 1]; the far lines keep the spacing
/// of that family (z[side + 1] - z[side + 3]).
export function rowOf(z, cells, side) {
  const near = z[(side + 1) % 4], step = near - z[(side + 3) % 4];
  return { side, free_heights: Array.from({ length: cells }, (_, k) => near + (k + 1) * step) };
}

/// Grid heights: cell (0, 0) has apexes (z0, z1, z2, z3); every further line of a
/// family keeps the spacing of the first two.
export function gridHeights(z, cellsU, cellsW) {
  const line = (a, b, count) => Array.from({ length: count + 1 }, (_, k) => a + k * (b - a));
  return { u_heights: line(z[0], z[2], cellsU), w_heights: line(z[1], z[3], cellsW) };
}

/// The apex heights of the first cell (or of the open P-hedron), to carry over to another mode.
export function cellZ(p) {
  if (p.grid) return [p.grid.u_heights[0], p.grid.w_heights[0], p.grid.u_heights[1], p.grid.w_heights[1]];
  const heights = baseHeights(p);
  return heights ? heights.slice() : [-1.5, 1.0, -0.5, 2.0];
}

/// `p` turned into `mode` ('open', 'parallelogram', 'anti-parallelogram',
/// 'grid', 'row'), its first cell's heights kept; `sizes` {cellsU, cellsW,
/// rowCells, rowSide}: the grid's and the row's size.
export function switchMode(p, mode, { cellsU, cellsW, rowCells, rowSide }) {
  const c = clone(p);
  const z = cellZ(c);
  delete c.grid;
  delete c.row;
  if (mode === 'grid') {
    delete c.apex_heights;
    delete c.signs;
    delete c.tube;
    c.grid = gridHeights(z, cellsU, cellsW);
  } else if (mode === 'open') {
    delete c.tube;
    delete c.couplings;  // they attach to tubes
    c.apex_heights = z.length >= 5 ? z : [...z.slice(0, 4), z[0] + 1.3];
    c.signs = '+'.repeat(c.apex_heights.length - 2);
  } else {
    delete c.apex_heights;
    delete c.signs;
    const q = z.slice(0, 4);
    while (q.length < 4) q.push(q[q.length - 1] + 1);
    if (mode === 'anti-parallelogram') q[3] = q[0] + q[2] - q[1];  // its symmetry condition
    const row = mode === 'row';
    c.tube = { type: row ? 'parallelogram' : mode, apex_heights: q };
    if (row) c.row = rowOf(q, rowCells, rowSide);
  }
  return c;
}

/// The design to show on switching `p` to `mode`: each mode keeps the design it
/// last had (`memory`: mode -> preset, updated with `p`), else `p` switched.
export function modeSwitch(memory, p, mode, sizes) {
  memory[modeOf(p)] = clone(p);
  if (memory[mode]) return clone(memory[mode]);
  return switchMode(p, mode, sizes);
}

/// A grid of cellsU x cellsW cells (null: `p` is no grid).
export function withGridSize(p, cellsU, cellsW) {
  if (!p.grid) return null;
  const c = clone(p);
  c.grid = gridHeights(cellZ(c), cellsU, cellsW);
  return c;
}

/// A row of `cells` cells on `side` of the tube (null: `p` is no row).
export function withRowSize(p, cells, side) {
  if (!p.row || !p.tube) return null;
  const c = clone(p);
  c.row = rowOf(c.tube.apex_heights, cells, side);
  return c;
}

/// Sign k of the apexes set to `sign` ('+' or '-').
export function withSign(p, k, sign) {
  const c = clone(p);
  c.signs = c.signs.slice(0, k) + sign + c.signs.slice(k + 1);
  return c;
}

/// One more profile, continuing the last trajectory segment, with the last direction.
export function withProfileAdded(p) {
  const c = clone(p);
  const n = c.trajectory.length;
  const last = c.trajectory[n - 1], prev = c.trajectory[n - 2];
  c.trajectory.push([0, 1, 2].map((i) => last[i] + (last[i] - prev[i])));
  c.directions.push(c.directions[n - 1].slice());
  return c;
}

/// The last profile removed (null: two are the fewest).
export function withProfileRemoved(p) {
  const c = clone(p);
  if (c.trajectory.length <= 2) return null;
  c.trajectory.pop();
  c.directions.pop();
  return c;
}

/// One more apex on an open P-hedron, sign '+' (null: not open).
export function withApexAdded(p) {
  const c = clone(p);
  if (!Array.isArray(c.apex_heights)) return null;
  const h = c.apex_heights, n = h.length;
  h.push(h[n - 2] + 0.6 * (h[n - 2] - h[n - 3]));
  c.signs += '+';
  return c;
}

/// The last apex removed from an open P-hedron (null: not open, or three are the fewest).
export function withApexRemoved(p) {
  const c = clone(p);
  if (!Array.isArray(c.apex_heights) || c.apex_heights.length <= 3) return null;
  c.apex_heights.pop();
  c.signs = c.signs.slice(0, -1);
  return c;
}

/// The preset field that defines t*: t is the axis coordinate of the moving
/// apex of the base (info.moving_apex, S_0 or S_1), so t* is the height of that
/// apex as the preset gives it: apex_heights[k], tube.apex_heights[k], or for a
/// grid u_heights[0] (S_0) or w_heights[0] (S_1). Returns {key, index, pointer}
/// (a JSON pointer, as Designer.repair's fixed takes), or null when no field
/// holds t* (checked: its value is t*).
export function tStarField(p, info) {
  if (!p || !info) return null;
  const k = info.moving_apex === 'S_0' ? 0 : 1;
  let ref = null;
  if (Array.isArray(p.apex_heights)) ref = { key: 'apex_heights', index: k };
  else if (p.tube && Array.isArray(p.tube.apex_heights)) ref = { key: 'tube.apex_heights', index: k };
  else if (p.grid) ref = k === 0 ? { key: 'grid.u_heights', index: 0 } : { key: 'grid.w_heights', index: 0 };
  if (!ref) return null;
  const value = ref.key.split('.').reduce((o, part) => o?.[part], p)?.[ref.index];
  const scale = Math.max(1, Math.abs(info.t_star), info.model_size ?? 0);
  if (typeof value !== 'number' || Math.abs(value - info.t_star) > 1e-9 * scale) return null;
  return { ...ref, pointer: pointerOf(ref) };
}

/// The handle a field of the core's messages names, as {key, index} for
/// Designer.set: "apex_heights[4]" -> {key: 'apex_heights', index: 4},
/// "trajectory[2][2]" -> trajectory 2 (the point, whatever its coordinate),
/// "couplings[1].free_heights[0]" -> {key: 'couplings.1.free_heights', index: 0},
/// "couplings[0].free_height" -> index -1. Null for what no handle edits.
export function refOfField(field) {
  const m = /^([a-z_]+(?:\[\d+\]\.[a-z_]+|\.[a-z_]+)*)(?:\[(\d+)\])?/.exec(String(field ?? ''));
  if (!m) return null;
  const key = m[1].replace(/\[(\d+)\]/g, '.$1');
  const index = m[2] === undefined ? -1 : Number(m[2]);
  if (key === 'trajectory' || key === 'directions') return index >= 0 ? { key, index } : null;
  return { key, index };
}

/// The fields a hint of the core names, in order: "increase trajectory[0][2] (now
/// 0.05) by more than about 0.2299" -> ["trajectory[0][2]"].
export function fieldsInHint(hint) {
  return (String(hint).match(/\b[a-z_][a-z_\d]*(?:\[\d+\]|\.[a-z_]+)*/g) ?? []).filter((w) => w.includes('['));
}
