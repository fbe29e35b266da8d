// The design the designer shows, what the core said of it, and the undo and redo
// history. Pure data: no DOM, no three.js, no WebAssembly (node imports it, see
// tests/js/designer_state_test.mjs). The page (designer.js) fills it from the
// core and redraws from it; undo and redo go through a `show` function it gives,
// which rebuilds the design from a preset and says whether the core accepted it.
import { clone, format } from './util.js';

/// At most this many designs are kept to undo; the oldest go first.
export const historyLimit = 500;

export class DesignState {
  constructor({ limit = historyLimit } = {}) {
    this.preset = null;                // the preset shown (always one the core accepted)
    this.info = null;                  // the core's Designer.info() of it
    this.fraction = 0.5;               // the slider's position in [0, 1] of the flexion interval
    this.faces = null;                 // Uint32Array of quads
    this.failure = null;               // the last refused edit: {field, message}
    this.figures = null;               // the core's Designer.check() of the shown design
    this.invalidPanels = new Set();    // not simple (the shape is a constant of the design)
    this.collidingPanels = new Set();  // penetrating at the slider's t
    this.buildability = null;          // the core's Designer.buildability() (null while it is computed)
    this.thick = null;                 // the Thick panels box's report while its plates show (Designer.thick), else null
    this.loadedName = null;            // the name of the preset as loaded, to say what an edited design came from
    this.fileName = null;              // the file it was loaded from ("default.json"), when known
    // Every accepted edit (a drag counts once, from press to release), repairs
    // and mode switches included: [{preset, what, origin, file}], the last the newest.
    this.history = [];
    this.future = [];                  // what undo took back, for redo
    this.limit = limit;
    this.onHistory = () => {};         // called whenever history or future changed
  }

  /// t at the fraction f of the flexion interval [t_lambda, t_mu].
  tOf(f) {
    return this.info.t_lambda + f * (this.info.t_mu - this.info.t_lambda);
  }

  /// The fraction of the flexion interval at which t lies, within [0, 1].
  fractionOf(t) {
    return Math.min(1, Math.max(0, (t - this.info.t_lambda) / (this.info.t_mu - this.info.t_lambda)));
  }

  /// The fraction of the flexion interval at which t* lies (the input configuration).
  tStarFraction() {
    return (this.info.t_star - this.info.t_lambda) / (this.info.t_mu - this.info.t_lambda);
  }

  /// Records `previous` (the design an accepted edit replaces; copied) as the
  /// one to undo to; `what` says what the edit was. A new edit forgets what was undone.
  remember(previous, what) {
    this.history.push({ preset: clone(previous), what, origin: this.loadedName, file: this.fileName });
    if (this.history.length > this.limit) this.history.shift();
    this.future.length = 0;
    this.onHistory();
  }

  /// A design opened from a file or the presets menu starts a new history:
  /// Undo and Redo stay within one design (they walked back through earlier
  /// loads: the 7th Undo after opening default.json brought grid-3x3 back).
  startHistory() {
    this.history.length = 0;
    this.future.length = 0;
    this.onHistory();
  }

  get canUndo() { return this.history.length > 0; }
  get canRedo() { return this.future.length > 0; }
  /// The design was edited since it was loaded (something to undo).
  get edited() { return this.history.length > 0; }

  /// The tooltips of the Undo and Redo buttons.
  undoTitle() {
    return this.history.length ? `undo the last ${this.history[this.history.length - 1].what} (Ctrl+Z)` : 'nothing to undo';
  }
  redoTitle() {
    return this.future.length ? `redo the ${this.future[this.future.length - 1].what} (Ctrl+Shift+Z)` : 'nothing to redo';
  }

  /// Goes back one design: `show(preset)` rebuilds it (true when the core
  /// accepted it; it sets this.preset). Returns null when there is nothing to
  /// undo, else {what, verb: 'undone', done}; when `show` refuses (done false)
  /// both stacks stay as they were.
  undo(show) { return this.#travel(this.history, this.future, 'undone', show); }
  /// The other way: {what, verb: 'redone', done}, or null with nothing to redo.
  redo(show) { return this.#travel(this.future, this.history, 'redone', show); }

  /// Moves one design from the `from` stack to the `to` stack and shows it.
  #travel(from, to, verb, show) {
    const entry = from.pop();
    if (!entry) return null;
    const now = clone(this.preset);
    const done = Boolean(show(entry.preset));
    if (done) {
      to.push({ preset: now, what: entry.what, origin: this.loadedName, file: this.fileName });
      this.loadedName = entry.origin;
      this.fileName = entry.file ?? null;
    } else {
      from.push(entry);
    }
    this.onHistory();
    return { what: entry.what, verb, done };
  }

  /// The preset as saved: its name `typed` (the name box) unless that is the
  /// loaded name or empty, then the loaded name + "-edited" once the design
  /// changed; its description what the design is now (`status()`: the status line).
  savedPreset(typed, status) {
    const p = clone(this.preset);
    const changed = this.edited, name = this.loadedName, info = this.info;
    p.name = typed && typed !== name ? typed : changed ? `${name || 'design'}-edited` : name || 'design';
    if (changed) {
      p.description = `${info.kind}, ${info.faces} panels, t* = ${format(info.t_star)} in [${format(info.t_lambda)}, ` +
        `${format(info.t_mu)}]; ${status()}. Edited in the phedra designer from "${name}".`;
    }
    return p;
  }
}

/// What the panel says after an undo or redo (`moved`: what undo() or redo() returned).
export function travelText({ what, verb }) {
  return what === 'repair' && verb === 'undone' ? 'repair undone: the previous design is back' : `${what} ${verb}`;
}
