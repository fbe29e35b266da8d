// What the WebAssembly core says of a design beyond its shape: the
// buildability report and the check figures once an edit settles, Repair (the
// nearest buildable design, issue 14) and keep buildable (each drag step
// projected onto buildable designs, the motion repaired when the hand stops).
// A repair keeps t* (the configuration the handles show: the field that
// defines it is held fixed), unless no buildable design keeps it; then it says so.
import { pointerOf, setAt, tStarField } from './edits.js';
import { withNumbers } from '../text.js';
import { $, format, refusal } from './util.js';

// The nearest buildable design is found by the same core as `phedra repair`
// (NLopt compiled to WebAssembly). The search runs on this thread: the status
// says so first. Its result replaces the design; Undo brings the previous back.
const repairSeconds = 10;

// Keep buildable (issue 14): each drag step projects the rest of the design
// (the apex heights) onto the designs whose panels are simple and whose t* is
// free of collisions, within this budget of the frame; the handle stops where
// that is impossible. When the hand stops, the motion over the whole interval
// is repaired too (the held field fixed), undoably.
const keepBudget = 7;  // ms: with the stop at the wall (5 designs) and the redraw, within a 60 Hz frame

/// `designer`: the core's Designer; `apply(preset, options)`: shows a design (undoably).
/// `onFigures`: called once the figures of a settled design are shown.
export function createBuildability({ state, designer, panel, surface, apply, onFigures = () => {} }) {
  let keepHeld = null;    // the JSON pointer of the field the last keep-buildable drag held
  let lastKeep = null;    // designer.keep's answer to the last step
  let lastRepair = null;  // t* before and after the last repair shown: {tStarBefore, tStarAfter, moved, freed}
  let figuresTimer = null;
  const keepBuildable = () => $('keep').checked;

  /// The buildability report and the figures of the shown design, a moment after
  /// the last edit (they cost more than a drag step on a large model).
  function scheduleFigures() {
    clearTimeout(figuresTimer);
    state.buildability = null;
    panel.showBuildability();
    panel.showMessage();
    figuresTimer = setTimeout(() => {
      // The sweep's samples a side: the command's (0: 200 up to 2000 panels), fewer on
      // larger models (the summary says when it was coarser than 200).
      const faces = state.info.faces;
      state.buildability = designer.buildability(true, faces <= 2000 ? 0 : Math.max(8, Math.round(200000 / faces)), 8);
      if (state.buildability.ok === false) state.buildability = null;
      if (keepHeld && state.buildability && !state.buildability.buildable && keepBuildable()) {
        const fixed = [keepHeld];
        keepHeld = null;
        repairDesign({ fixed });  // the motion too, the held handle where the hand left it
      }
      keepHeld = null;
      panel.showBuildability();
      panel.showMessage();
      surface.scheduleCollisions();
      state.figures = designer.check(41);
      panel.showFigures();
      onFigures();
    }, 150);
  }

  /// Runs `body` once the page has painted what was just written (the search holds the thread).
  const afterPaint = (body) => requestAnimationFrame(() => requestAnimationFrame(body));

  /// `fixed`: preset fields (JSON pointers) that stay, e.g. the handle a keep-buildable
  /// drag held. The field that defines t* stays too; when no design found that way
  /// is buildable over the whole interval, a second search lets t* move, and the
  /// wider of the two results is shown (saying that t* moved).
  function repairDesign({ fixed = [] } = {}) {
    $('repair').disabled = true;
    const star = tStarField(state.preset, state.info);
    const holding = star && !fixed.includes(star.pointer) ? [...fixed, star.pointer] : fixed;
    const tStar = format(state.info.t_star);
    panel.showRepair(`repairing: searching the nearest buildable design that keeps t* = ${tStar} (up to ${repairSeconds} s)…`);
    afterPaint(() => {
      const kept = designer.repair(JSON.stringify({ max_seconds: repairSeconds, fixed: holding }));
      if (!kept.ok || kept.already_buildable || kept.found || holding === fixed) {
        finish(kept, false);
        return;
      }
      panel.showRepair(`no design keeping t* = ${tStar} is buildable over the whole interval: searching with t* free (up to ${repairSeconds} s)…`);
      afterPaint(() => {
        const free = designer.repair(JSON.stringify({ max_seconds: repairSeconds, fixed }));
        // A repair (buildable over the whole interval) with t* free, else the failure that came closer.
        const better = free.ok && (free.found || (free.closest_fraction ?? 0) > (kept.closest_fraction ?? 0));
        finish(better ? free : kept, better);
      });
    });
  }

  /// Shows a repair's result `r` (`freed`: found with t* free to move).
  function finish(r, freed) {
    $('repair').disabled = false;
    if (!r.ok) {
      panel.showRepair(`repair refused: ${refusal(r)}`);
    } else if (r.already_buildable) {
      panel.showRepair('already buildable over the whole flexion interval: nothing to repair');
    } else if (!r.found) {
      const text = `not repaired: no design buildable over the whole flexion interval found in ${format(r.seconds)} s: ${withNumbers(r.closest, format)}`;
      const part = Math.round(100 * (r.closest_fraction ?? 0));
      // The widest part reached is not a repair: offered, saying what it is.
      const offer = r.closest_preset ? {
        label: `Load the closest design (buildable over ${part} % of the way from t* to the limits)`,
        load: () => {
          if (apply(JSON.parse(r.closest_preset), { what: 'closest design', keepT: true })) {
            panel.showRepair(`loaded the closest design: buildable over ${part} % of the way from t* to the limits only, not the whole interval. Undo brings the previous design back.`);
          }
        },
      } : null;
      panel.showRepair(text, [], offer);
    } else {
      const before = state.info.t_star, moving = state.info.moving_apex;
      const why = freed ? `no buildable design keeps it, so the repair moved the apex ${moving} that t measures`
        : 'the repair changed which apex t measures';
      if (apply(JSON.parse(r.preset), { what: 'repair', keepT: true, tStarWhy: why })) {
        const after = state.info.t_star;
        const moved = Math.abs(after - before) > 1e-12 * state.info.model_size;
        const star = moved ? `t* moved from ${format(before)} to ${format(after)} (${why})` : `t* kept at ${format(after)}`;
        panel.showRepair(`repaired: ${r.changes.length} field${r.changes.length === 1 ? '' : 's'} changed, distance ` +
          `${format(r.distance)} of the model size, ${star}; ${r.evaluations} designs in ${format(r.seconds)} s. Undo brings the previous design back.`, r.changes);
        lastRepair = { tStarBefore: before, tStarAfter: after, moved, freed };
      }
    }
  }
  $('repair').addEventListener('click', () => repairDesign());
  // Keep buildable switched off: its "the handle stops here" no longer applies.
  $('keep').addEventListener('change', () => {
    if (!keepBuildable() && $('repair-result').textContent.startsWith('keep buildable')) panel.showRepair('');
  });

  /// One drag step through the core without the round trip through JSON text
  /// (the hot path while dragging; the topology does not change): Designer.set,
  /// or with keep buildable Designer.keep (the other heights may follow, or the
  /// handle stop). Returns the core's answer; when it accepted, state.preset follows.
  function step(edit) {
    const keep = keepBuildable();
    // A keep-buildable step holds t* too (unless its own field is the one dragged).
    const star = keep ? tStarField(state.preset, state.info) : null;
    const result = keep
      ? designer.keep(edit.key, edit.index, ...edit.value, keepBudget, star ? JSON.stringify([star.pointer]) : '')
      : designer.set(edit.key, edit.index, ...edit.value);
    if (!result.ok) return result;
    if (keep) {
      keepHeld = pointerOf(edit);
      lastKeep = result;
      state.preset = JSON.parse(designer.presetText());  // projected or stopped at the wall
      panel.showRepair(result.clamped ? 'keep buildable: the handle stops here; further, a panel would not be simple or t* would collide'
        : result.projected ? 'keep buildable: the other apex heights follow the handle' : '');
    } else {
      setAt(state.preset, edit, edit.key === 'trajectory' || edit.key === 'directions' ? edit.value : edit.value[0]);
    }
    return result;
  }

  return {
    scheduleFigures,
    repairDesign,
    step,
    /// designer.keep's answer to the last keep-buildable step.
    get lastKeep() { return lastKeep; },
    /// What the last repair did to t*.
    get lastRepair() { return lastRepair; },
    /// Forgets the field a keep-buildable drag held (no repair when the design settles).
    forgetHeld: () => { keepHeld = null; },
  };
}
