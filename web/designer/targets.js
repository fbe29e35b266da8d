// The Targets box (issue 26, item 2): the figures `phedra optimize` targets,
// live (recomputed by the core when an edit settles), a target per figure (=, ≥
// or ≤ a value) and Optimize: the nearest buildable design that meets them, by
// the same core as the command (NLopt in WebAssembly, on this thread: the status
// says so first). The result replaces the design; Undo brings the previous back.
import { $, format } from './util.js';

const optimizeSeconds = 10;

/// What each figure is, for people (the names are the command's).
const meaning = {
  'poisson.nu_12': "Poisson's ratio ν₁₂ at t* (axis 1 along the trajectory, 2 across)",
  'poisson.nu_13': "Poisson's ratio ν₁₃ at t*",
  'poisson.nu_23': "Poisson's ratio ν₂₃ at t*",
  'extent_deployment.0': 'deployment ratio of the length along axis 1 (largest / smallest over the interval)',
  'extent_deployment.1': 'deployment ratio along axis 2',
  'extent_deployment.2': 'deployment ratio along axis 3',
  flexion_width: 'width of the flexion interval, t_μ − t_λ',
  volume_ratio: 'largest / smallest enclosed volume over the interval',
};

/// The target text `phedra optimize --target` takes, or null when the row has none.
export function targetText(name, relation, value) {
  if (!relation || value === '' || value === null || !Number.isFinite(Number(value))) return null;
  return `${name}${relation}${Number(value)}`;
}

/// `designer`: the core's Designer; `apply(preset, options)`: shows a design (undoably).
export function createTargets({ state, designer, apply }) {
  const rows = new Map();  // name -> {value, relation, goal}
  const table = $('targets-table');
  let names = [];

  function build(list) {
    names = list;
    table.textContent = '';
    for (const name of names) {
      const tr = document.createElement('tr');
      tr.title = meaning[name] ?? name;
      const label = document.createElement('td');
      label.textContent = name;
      const value = document.createElement('td');
      value.className = 'figure-value';
      const relation = document.createElement('select');
      relation.setAttribute('aria-label', `${name}: relation`);
      for (const [text, v] of [['–', ''], ['=', '='], ['≥', '>='], ['≤', '<=']]) {
        const o = document.createElement('option');
        o.textContent = text;
        o.value = v;
        relation.append(o);
      }
      const goal = document.createElement('input');
      goal.type = 'number';
      goal.step = 'any';
      goal.size = 7;
      goal.setAttribute('aria-label', `${name}: target value`);
      // Typing a value sets '=' when no relation was chosen: one step less.
      goal.addEventListener('input', () => { if (!relation.value && goal.value !== '') relation.value = '='; updateButton(); });
      relation.addEventListener('change', updateButton);
      const cells = [label, value, document.createElement('td'), document.createElement('td')];
      cells[2].append(relation);
      cells[3].append(goal);
      tr.append(...cells);
      table.append(tr);
      rows.set(name, { value, relation, goal });
    }
  }

  function targets() {
    const out = [];
    for (const name of names) {
      const r = rows.get(name);
      const t = targetText(name, r.relation.value, r.goal.value);
      if (t) out.push(t);
    }
    return out;
  }

  function updateButton() {
    $('optimize').disabled = targets().length === 0;
  }

  /// The figures of the shown design (after an edit settles).
  function refresh() {
    const f = designer.figures();
    if (!f.ok) return;
    if (names.length === 0) build(Array.from(f.names));
    for (const name of names) rows.get(name).value.textContent = f.figures[name] === null ? 'undefined' : format(f.figures[name]);
    state.targetFigures = f.figures;
    updateButton();
  }

  const afterPaint = (body) => requestAnimationFrame(() => requestAnimationFrame(body));

  function show(text) {
    const box = $('optimize-result');
    box.hidden = !text;
    box.textContent = text;
  }

  function optimize() {
    const wanted = targets();
    if (wanted.length === 0) return;
    $('optimize').disabled = true;
    show(`optimizing: searching the nearest buildable design with ${wanted.join(', ')} (up to ${optimizeSeconds} s)…`);
    afterPaint(() => {
      const r = designer.optimize(JSON.stringify({ targets: wanted, max_seconds: optimizeSeconds }));
      updateButton();
      if (!r.ok) {
        show(`optimize refused: ${r.field ? `${r.field}: ` : ''}${r.message}`);
        return;
      }
      const outcome = Array.from(r.targets).map((t) =>
        `${t.target}: ${t.before === null ? 'undefined' : format(t.before)} → ${t.after === null ? 'undefined' : format(t.after)}${t.met ? '' : ' (not met)'}`).join('; ');
      if (!r.reached) {
        show(`not reached in ${format(r.seconds)} s (${outcome}); ${r.binding}. The design is unchanged.`);
        return;
      }
      if (apply(JSON.parse(r.preset), { what: 'optimize', keepT: true })) {
        show(`reached: ${outcome}; ${r.changes.length} field${r.changes.length === 1 ? '' : 's'} changed, ` +
          `${r.buildability}; ${r.evaluations} designs in ${format(r.seconds)} s. Undo brings the previous design back.`);
      }
    });
  }
  $('optimize').addEventListener('click', optimize);

  return { refresh, optimize, targets, show };
}
