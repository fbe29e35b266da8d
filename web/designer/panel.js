// The panel: the status line and the label next to the handle a refusal names,
// the figures of the design, the slider's labels and the t* note, the
// buildable part of the interval and its causes, the repair's result, the
// mode, sizes and signs of the preset, Undo and Redo, the title. It shows the
// DesignState; the only edit it makes itself is a sign toggle, which it hands
// to `onSign`. What varies in length (status, causes, results, figures) lives
// in #status-box, of a fixed height: the buttons never move.
import { makerHint, pageTitle, statusSummary, withArticle, withNumbers } from '../text.js';
import { fieldsInHint, modeOf } from './edits.js';
import { $, format, refusal } from './util.js';

/// `locate(field)`: where on the page the handle of a preset field is ([x, y]) or null;
/// `onSign(k, sign)`: the user set sign k to `sign`; `onCause({panel, field})`: the
/// user clicked a cause (field: the preset field of the change picked, or null).
export function createPanel({ state, locate, onSign, onCause = () => {} }) {
  /// The status when the last edit was accepted: what the buildability report
  /// says ("buildable over [a, b]", or what is wrong), never just "valid".
  /// While plates show: what they allow (their thick interval) and whether they
  /// collide at the slider's t; null otherwise.
  function plateStatus() {
    const { thick: th, info } = state;
    if (!th) return null;
    const t = state.tOf(state.fraction);
    const head = `plates ${format(th.thickness)} thick`;
    if (!th.interval) return { text: `${head}: they collide at t*: ${withNumbers(th.at_t_star, format)}`, fits: false };
    const [a, b] = th.interval;
    const whole = a <= info.t_lambda && b >= info.t_mu;
    const inside = t >= a && t <= b;
    return {
      text: `${head}: ${whole ? 'they move over the whole flexion interval' : `they move over [${format(a)}, ${format(b)}] only (their thick interval)`}` +
        (inside ? '' : `; at t = ${format(t)} they collide (move the slider into the green part)`),
      fits: inside,
    };
  }

  function statusText() {
    const { buildability, invalidPanels, info } = state;
    const plates = plateStatus();
    if (plates) return plates.text;
    if (buildability) return statusSummary(buildability.summary, format);
    if (invalidPanels.size) {
      const list = [...invalidPanels].slice(0, 8).join(', ') + (invalidPanels.size > 8 ? ', …' : '');
      return `not buildable: ${invalidPanels.size} of ${info.faces} panels cannot be cut as one plate (panels ${list})`;
    }
    return 'every panel is simple; checking the motion for collisions…';
  }

  /// The status line, or the last refusal, also next to the handle it names.
  function showMessage() {
    const message = $('message'), label = $('label');
    const { failure, buildability, invalidPanels } = state;
    if (!failure) {
      message.textContent = statusText();
      message.classList.remove('error');
      const plates = plateStatus();
      message.classList.toggle('buildable', plates ? plates.fits : Boolean(buildability && buildability.buildable));
      message.classList.toggle('unbuildable', plates ? !plates.fits : Boolean(invalidPanels.size || (buildability && !buildability.buildable)));
      label.hidden = true;
      return;
    }
    message.classList.remove('buildable', 'unbuildable');
    const text = refusal(failure);
    message.textContent = text;
    message.classList.add('error');
    const at = locate(failure.field);
    if (at) {
      const [x, y] = at;
      label.style.left = `${x + 12}px`;
      label.style.top = `${y - 10}px`;
      label.textContent = text;
      label.hidden = false;
    } else {
      label.hidden = true;
    }
  }

  /// The slider at state.fraction.
  function showFraction() {
    $('slider').value = String(Math.round(state.fraction * 1000));
  }

  /// Says when an edit moved t* and why (`before`: t* of the previous design, null
  /// for none; `why`: the reason, else the edit moved the apex t measures).
  function noteTStar(before, why = null) {
    const info = state.info;
    const moved = before !== null && Math.abs(before - info.t_star) > 1e-12 * info.model_size;
    if (moved) {
      $('tstar-note').textContent = `t* moved from ${format(before)} to ${format(info.t_star)}: ` + (why ??
        `t is the axis coordinate of the moving apex ${info.moving_apex}, and this edit moved it`);
    } else {
      $('tstar-note').textContent = '';
    }
    return moved;
  }

  /// The t shown.
  function showT(t) {
    $('t').textContent = format(t);
  }

  /// The figures of the design: name, kind, counts, the interval and t*.
  function updateLabels() {
    const info = state.info;
    showTitle();
    $('kind').textContent = `${info.kind}, ${info.vertices} vertices, ${info.faces} panels`;
    $('lo').textContent = format(info.t_lambda);
    $('hi').textContent = format(info.t_mu);
    $('tstar').textContent = format(info.t_star);
    const star = state.tStarFraction();
    $('tstarmark').style.left = `calc(8px + ${star.toFixed(4)} * (100% - 16px))`;
  }

  /// The title: the preset's name, and the file it came from when that says more
  /// ("mixed-signs" from default.json); the tab's title too.
  function showTitle() {
    const name = state.info?.name ?? state.preset?.name;
    // The file, while the design is the one loaded from it or named after it ("X-repaired").
    const file = state.fileName && (!state.loadedName || String(name ?? '').startsWith(state.loadedName)) ? state.fileName : null;
    const title = pageTitle({ name, file, page: 'phedra designer' });
    $('title').textContent = title.name;
    $('file').textContent = title.file;
    $('title').parentElement.title = `${title.name}${file ? `, from ${file}` : ''}`;
    document.title = title.document;
  }

  /// The preset's text in the JSON editor.
  function showPresetText() {
    $('json').value = JSON.stringify(state.preset, null, 2);
  }

  /// Everything the panel shows: the labels, the preset's text, mode and signs.
  function updatePanel() {
    const preset = state.preset;
    updateLabels();
    showPresetText();
    $('mode').value = modeOf(preset);
    $('grid-size').hidden = !preset.grid;
    if (preset.grid) {
      $('cells-u').value = String(preset.grid.u_heights.length - 1);
      $('cells-w').value = String(preset.grid.w_heights.length - 1);
    }
    $('row-size').hidden = !preset.row;
    if (preset.row) {
      $('row-cells').value = String(preset.row.free_heights.length);
      $('row-side').value = String(preset.row.side);
    }
    // Controls only where they act: apexes are added and removed on open designs.
    const open = Array.isArray(preset.apex_heights);
    $('add-apex').hidden = $('remove-apex').hidden = !open;
    $('remove-apex').disabled = open && preset.apex_heights.length <= 3;
    $('remove-profile').disabled = preset.trajectory.length <= 2;
    if (document.activeElement !== $('name')) $('name').value = preset.name ?? '';
    const signs = $('signs');
    signs.textContent = '';
    if (typeof preset.signs === 'string') {
      signs.append('signs ');
      [...preset.signs].forEach((s, k) => {
        const b = document.createElement('button');
        b.type = 'button';
        b.textContent = s;
        b.title = `sign of S_${k + 1}`;
        b.dataset.index = String(k);
        b.addEventListener('click', () => onSign(k, s === '+' ? '-' : '+'));
        signs.append(b);
      });
    } else {
      signs.append('signs: set by the mode');  // (the row keeps its height: nothing below it moves)
    }
  }

  /// The buildable part of the interval on the bar under the slider, and why not.
  function showBuildability() {
    const { info, buildability: b } = state;
    const bar = $('buildable-part');
    const range = info.t_mu - info.t_lambda;
    // While plates show, the green part is where they move (their thick interval).
    const part = state.thick ? state.thick.interval : b && b.interval;
    if (part && range > 0) {
      bar.hidden = false;
      bar.style.left = `${(100 * (part[0] - info.t_lambda)) / range}%`;
      bar.style.width = `${Math.max(0.5, (100 * (part[1] - part[0])) / range)}%`;
      bar.title = `${state.thick ? 'the plates move over' : 'buildable over'} [${format(part[0])}, ${format(part[1])}]`;
    } else {
      bar.hidden = true;
    }
    const why = $('why'), list = $('why-list');
    list.textContent = '';
    const invalid = b ? b.invalid : [];
    const ends = b && b.ends ? b.ends : [];
    const atStar = b && invalid.length === 0 ? b.at_t_star : null;
    why.hidden = invalid.length === 0 && ends.length === 0 && !atStar;
    if (atStar) {
      // The configuration at t* collides: its panels (orange at t*) and what frees it.
      $('why-count').textContent = 'the configuration at t* collides; what to change (click one: its handle and panels light up):';
      list.append(collisionItem(atStar));
      return;
    }
    if (invalid.length === 0 && ends.length) {
      // Simple panels, a part of the motion: say what ends it, as the command does.
      $('why-count').textContent = 'what ends the buildable part (click one: its panels light up):';
      for (const e of ends) list.append(endItem(e));
      return;
    }
    const sized = invalid.some((p) => p.shape === 'oversized' || p.shape === 'sliver');
    $('why-count').textContent = `${invalid.length} panel${invalid.length === 1 ? '' : 's'} cannot be ` +
      `${sized ? 'built' : 'cut as one plate'}; ` +
      'what to change (click one: its handle and panel light up):';
    for (const p of invalid.slice(0, 12)) list.append(causeItem(p));
    if (invalid.length > 12) {
      const more = document.createElement('li');
      more.textContent = `… and ${invalid.length - 12} more (phedra check --json lists them all)`;
      list.append(more);
    }
  }

  /// A hint as a maker reads it ("raise **trajectory point 2** by more
  /// than 0.3200 (now 1.5000)"): the nodes of a cause's button.
  function makerParts(hint) {
    const words = makerHint(hint, format);
    if (!words.verb) return [words.tail];
    const b = document.createElement('b');
    b.textContent = words.subject;
    return [`${words.verb} `, b, words.tail];
  }

  /// One button a field hint under `item` ("change: raise trajectory point 2 ...", then
  /// "or: ..."): a click selects the field's handle and highlights `panel`.
  function appendChanges(item, hints, panel) {
    hints.forEach((h, k) => {
      const change = document.createElement('button');
      change.type = 'button';
      change.className = 'change';
      const field = fieldsInHint(h)[0] ?? null;
      change.dataset.field = field ?? '';
      change.append(k ? 'or: ' : 'change: ', ...makerParts(h));
      change.title = field ? `${field}: select its handle and panel ${panel}` : `show panel ${panel}`;
      change.addEventListener('click', (e) => { e.stopPropagation(); pick(item, change, { panel, field }); });
      item.append(change);
    });
  }

  /// The collision at t*: each field hint a button (its handle selected, the
  /// first panel highlighted), the command's words behind "details".
  function collisionItem(c) {
    const item = document.createElement('li');
    item.dataset.panel = String(c.panels[0]);
    appendChanges(item, c.hints, c.panels[0]);
    const details = document.createElement('details');
    const summary = document.createElement('summary');
    summary.textContent = `panels ${c.panels.join(' and ')}: details`;
    details.append(summary, withNumbers(c.text, format));
    item.append(details);
    item.title = `show panels ${c.panels.join(' and ')}`;
    item.addEventListener('click', (e) => {
      if (e.target.closest('summary')) return;
      pick(item, null, { panel: c.panels[0], field: null });
    });
    return item;
  }

  /// What ends the buildable part on one side: "above t = 0.3133: the hinge between ...".
  function endItem(e) {
    const item = document.createElement('li');
    item.dataset.panel = String(e.panels[0]);
    item.textContent = `${e.side} t = ${format(e.t)}: ${withNumbers(e.text, format)}`;
    item.title = `show panels ${e.panels.join(' and ')}`;
    item.addEventListener('click', () => pick(item, null, { panel: e.panels[0], field: null }));
    return item;
  }

  /// One cause, for a maker first: what to change (each change a link to its
  /// handle), then which panel it mends, the construction's words behind "details".
  function causeItem(p) {
    const item = document.createElement('li');
    item.dataset.panel = String(p.panel);
    const firstField = p.hints.map((h) => fieldsInHint(h)[0]).find((f) => f && locate(f)) ?? null;
    appendChanges(item, p.hints, p.panel);
    const details = document.createElement('details');
    const summary = document.createElement('summary');
    const name = document.createElement('span');
    name.className = 'panel-name';
    name.textContent = `panel ${p.panel}`;
    summary.append(p.hints.length ? 'mends ' : 'no single number mends ', name, `, ${withArticle(p.shape)}: details`);
    details.append(summary, `${p.cause ? `${p.cause}: ` : ''}${withNumbers(p.why, format)}`);
    item.append(details);
    item.title = firstField ? `select the handle of ${firstField} and panel ${p.panel}` : `show panel ${p.panel}`;
    item.addEventListener('click', (e) => {
      if (e.target.closest('summary')) return;  // the toggle opens the details, and selects nothing
      pick(item, item.querySelector(`.change[data-field="${CSS.escape(firstField ?? '')}"]`), { panel: p.panel, field: firstField });
    });
    return item;
  }

  /// A cause clicked: marked in the list, handed to onCause.
  function pick(item, change, cause) {
    for (const e of $('why-list').querySelectorAll('.selected')) e.classList.remove('selected');
    item.classList.add('selected');
    if (change) change.classList.add('selected');
    onCause(cause);
  }

  /// The check figures over the interval (state.figures).
  function showFigures() {
    const figures = state.figures;
    const closure = figures.closed ? `, closure ${format(figures.closure)}` : '';
    $('figures').textContent = `over the interval: planarity ${format(figures.planarity)}, isometry ${format(figures.isometry)}${closure} (of the model size)` +
      (figures.warning ? ` — ${withNumbers(figures.warning, format)}` : '');
  }

  /// What a repair (or keep buildable, undo, redo) did: `text`, and the fields it changed.
  /// `offer`: {label, load} for a button under the message (the closest design
  /// when nothing was repaired), or null.
  function showRepair(text, changes = [], offer = null) {
    const result = $('repair-result'), list = $('repair-list'), button = $('load-closest');
    result.hidden = !text;
    result.textContent = text;
    button.hidden = !offer;
    button.textContent = offer ? offer.label : '';
    button.onclick = offer ? () => offer.load() : null;
    list.textContent = '';
    $('repair-changes').hidden = changes.length === 0;
    for (const c of changes) {
      const item = document.createElement('li');
      const what = c.field.startsWith('directions') ? `turned ${format(c.change)} degrees`
        : `${c.change >= 0 ? '+' : ''}${format(c.change)}, ${format(c.relative)} of the model size`;
      const value = (text) => { try { const v = JSON.parse(text); return Array.isArray(v) ? `(${v.map(format).join(', ')})` : format(v); } catch { return text; } };
      item.textContent = `${c.field}: ${value(c.before)} → ${value(c.after)} (${what})`;
      list.append(item);
    }
  }

  /// Undo and Redo enabled, and their tooltips, as the history is.
  function updateUndo() {
    $('undo').disabled = !state.canUndo;
    $('redo').disabled = !state.canRedo;
    $('undo').title = state.undoTitle();
    $('redo').title = state.redoTitle();
  }

  return {
    statusText, showMessage, showFraction, noteTStar, showT, updateLabels, showTitle, showPresetText, updatePanel,
    showBuildability, showFigures, showRepair, updateUndo,
  };
}
