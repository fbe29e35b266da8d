// The Targets box (issue 26, item 2): the figures `phedra optimize` targets,
// live (recomputed by the core when an edit settles), a target per figure (=, ≥
// or ≤ a value) and Optimize: the nearest buildable design that meets them, by
// the same core as the command (NLopt in WebAssembly, on this thread: the status
// says so first). The result replaces the design; Undo brings the previous back.
import { withNumbers } from '../text.js';
import { $, format, refusal } from './util.js';

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

/// Each figure's name in words, for the table and the messages (the command's
/// name on hover: `phedra optimize --target` takes it).
const words = {
  'poisson.nu_12': "Poisson's ratio ν₁₂",
  'poisson.nu_13': "Poisson's ratio ν₁₃",
  'poisson.nu_23': "Poisson's ratio ν₂₃",
  'extent_deployment.0': 'deployment along 1',
  'extent_deployment.1': 'deployment along 2',
  'extent_deployment.2': 'deployment along 3',
  flexion_width: 'flexion width',
  volume_ratio: 'volume ratio',
};

/// A figure's name in words (its own name when it has none).
export const figureWords = (name) => words[name] ?? name;

/// "poisson.nu_13>=-1" as people read it: "Poisson's ratio ν₁₃ ≥ -1".
export function targetWords(target) {
  const m = /^([A-Za-z0-9_.]+)(<=|>=|=)(.*)$/.exec(target);
  return m ? `${figureWords(m[1])} ${{ '<=': '≤', '>=': '≥', '=': '=' }[m[2]]} ${m[3]}` : target;
}

/// The figures other than `targeted` that an edit changed by more than a tenth
/// (or whose sign flipped), as "Poisson's ratio ν₂₃ -1.86 → 11.63".
export function otherChanges(before, after, targeted, format) {
  const out = [];
  for (const [name, a] of Object.entries(after ?? {})) {
    const b = before?.[name];
    if (targeted.includes(name) || b === null || b === undefined || a === null) continue;
    if (Math.abs(a - b) > 0.1 * Math.abs(b) || Math.sign(a) !== Math.sign(b)) out.push(`${figureWords(name)} ${format(b)} → ${format(a)}`);
  }
  return out;
}

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
      tr.title = `${meaning[name] ?? name} (phedra optimize --target ${name})`;
      tr.dataset.figure = name;
      const label = document.createElement('td');
      label.textContent = figureWords(name);
      const value = document.createElement('td');
      value.className = 'figure-value';
      const relation = document.createElement('select');
      relation.setAttribute('aria-label', `${figureWords(name)}: relation`);
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
      goal.setAttribute('aria-label', `${figureWords(name)}: target value`);
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
        show(`optimize refused: ${refusal(r)}`);
        return;
      }
      const outcome = Array.from(r.targets).map((t) =>
        `${targetWords(t.target)}: ${t.before === null ? 'undefined' : format(t.before)} → ${t.after === null ? 'undefined' : format(t.after)}${t.met ? '' : ' (not met)'}`).join('; ');
      if (!r.reached) {
        show(`not reached in ${format(r.seconds)} s (${outcome}); ${r.binding}. The design is unchanged.`);
        return;
      }
      const before = state.info.t_star, figuresBefore = state.targetFigures;
      // The slider follows t* (the surface passes through the handles there), said when it moved.
      if (apply(JSON.parse(r.preset), { what: 'optimize', tStarWhy: 'the optimization moved the apex that t measures' })) {
        const after = state.info.t_star;
        const star = Math.abs(after - before) > 1e-12 * state.info.model_size
          ? `t* moved from ${format(before)} to ${format(after)}, the slider with it` : `t* kept at ${format(after)}`;
        const now = designer.figures();
        const targeted = wanted.map((t) => /^[A-Za-z0-9_.]+/.exec(t)[0]);
        const others = now.ok ? otherChanges(figuresBefore, now.figures, targeted, format) : [];
        show(`reached: ${outcome}; ${r.changes.length} field${r.changes.length === 1 ? '' : 's'} changed, ` +
          `${withNumbers(r.buildability, format)}; ${star}; ` + (others.length ? `other figures changed: ${others.join('; ')}; ` : '') +
          `${r.evaluations} designs in ${format(r.seconds)} s. Undo brings the previous design back.`);
      }
    });
  }
  $('optimize').addEventListener('click', optimize);

  return { refresh, optimize, targets, show };
}
