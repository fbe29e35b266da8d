// The controls that change a design's structure: the mode (open P-hedron,
// parallelogram or anti-parallelogram tube, grid of cells, row of face-coupled
// cells), the grid's and the row's size, profiles and apexes added or removed.
// Each makes a new preset (edits.js) and hands it to `apply`, which the core
// may refuse.
import { modeOf, modeSwitch, withApexAdded, withApexRemoved, withGridSize, withProfileAdded, withProfileRemoved,
         withRowSize } from './edits.js';
import { $ } from './util.js';

/// `apply(preset, options)`: shows a design (undoably); false when the core refused it.
export function createModeControls({ state, apply }) {
  const gridCells = () => [Math.max(1, Number($('cells-u').value)), Math.max(1, Number($('cells-w').value))];
  const rowCells = () => [Math.max(1, Number($('row-cells').value)), Number($('row-side').value)];

  for (const id of ['cells-u', 'cells-w']) {
    $(id).addEventListener('change', () => {
      const c = withGridSize(state.preset, ...gridCells());
      if (c) apply(c);
    });
  }

  for (const id of ['row-cells', 'row-side']) {
    $(id).addEventListener('change', () => {
      const c = withRowSize(state.preset, ...rowCells());
      if (c) apply(c);
    });
  }

  // Each mode keeps the design it last had: switching back restores it.
  const modeMemory = {};
  $('mode').addEventListener('change', (e) => {
    const [cellsU, cellsW] = gridCells(), [cells, side] = rowCells();
    const c = modeSwitch(modeMemory, state.preset, e.target.value, { cellsU, cellsW, rowCells: cells, rowSide: side });
    if (!apply(c, { what: 'mode switch' })) e.target.value = modeOf(state.preset);
  });

  const button = (id, edit) => $(id).addEventListener('click', () => {
    const c = edit(state.preset);
    if (c) apply(c);
  });
  button('add-profile', withProfileAdded);
  button('remove-profile', withProfileRemoved);
  button('add-apex', withApexAdded);
  button('remove-apex', withApexRemoved);
}
