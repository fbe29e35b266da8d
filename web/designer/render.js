// The render loop and the drag-resolution budget. A frame is drawn only after
// something changed (an edit, the slider, the camera, the window), so an idle
// page costs nothing.
//
// A renderer too slow to redraw the model at full resolution within a 60 Hz
// frame (software WebGL, weak GPUs) draws it at a lower resolution while a
// handle is dragged, sharp again when the hand stops. The full-resolution draw
// is timed once a model (a pixel read back waits for the rasterizer); a GPU
// that draws the model within the frame never sees a lower resolution.

const frameBudget = 1000 / 60;
const minimumDragRatio = 0.35;

/// The loop of the stage {renderer, scene, camera, controls}; start() runs it.
export function createRenderLoop({ renderer, scene, camera, controls }) {
  let needsRender = true;
  let drawCost = null;      // ms of a draw at resolution fraction r: {fixed, fill} with cost = fixed + fill r^2; null until timed
  let calibrate = true;     // time the next draws
  let stepCost = 2;         // ms: the main-thread work of a drag step (running estimate)
  let dragRatio = 1;        // the fraction of the resolution while dragging
  let frameLog = null;      // while recording (bench/designer.mjs): [{start, work, edit}] a frame
  const pixel = new Uint8Array(4);

  const requestRender = () => { needsRender = true; };
  controls.addEventListener('change', requestRender);
  window.addEventListener('resize', requestRender);

  /// Renders and waits for the rasterizer (reads a pixel back): milliseconds.
  function timedDraw() {
    const gl = renderer.getContext();
    const t0 = performance.now();
    renderer.render(scene, camera);
    gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
    return performance.now() - t0;
  }

  /// Times a draw at full and at half resolution: what goes with the pixels (fill)
  /// and what does not (vertices, the pipeline).
  function calibrateDraw() {
    const full = timedDraw();
    renderer.setPixelRatio(window.devicePixelRatio * 0.5);
    timedDraw();  // the first draw at a new size allocates
    const half = timedDraw();
    renderer.setPixelRatio(window.devicePixelRatio);
    renderer.render(scene, camera);  // resizing cleared the canvas
    const fill = Math.max(0, (full - half) / 0.75);
    drawCost = { fixed: Math.max(0, full - fill), fill };
  }

  /// The fraction of the resolution at which a drag frame fits in a 60 Hz frame.
  function chooseDragRatio() {
    const budget = frameBudget - stepCost - 2;  // 2 ms for the browser's own work
    if (drawCost === null || drawCost.fixed + drawCost.fill <= budget) return 1;
    const room = budget - drawCost.fixed;
    return room <= 0 || drawCost.fill === 0 ? minimumDragRatio : Math.min(1, Math.max(minimumDragRatio, Math.sqrt(room / drawCost.fill)));
  }

  function beginDrag() {
    dragRatio = chooseDragRatio();
    if (dragRatio < 1) renderer.setPixelRatio(window.devicePixelRatio * dragRatio);
    requestRender();
  }

  function endDrag() {
    if (dragRatio < 1) renderer.setPixelRatio(window.devicePixelRatio);
    dragRatio = 1;
    requestRender();
  }
  window.addEventListener('resize', () => { calibrate = true; });

  /// Runs the loop: each frame first calls `step()` (true when it applied a
  /// drag step: its time feeds the budget), then draws if needed and calls
  /// `drawn()` (what follows the camera on the page); the draw is timed again
  /// after a new design, unless `dragging()`.
  function start({ step, dragging, drawn = () => {} }) {
    function frame() {
      const start = performance.now();
      const edited = step();
      if (edited) stepCost = 0.8 * stepCost + 0.2 * (performance.now() - start);
      controls.update();
      if (needsRender) {
        needsRender = false;
        renderer.render(scene, camera);
        drawn();
        if (calibrate && !dragging()) {
          // The draw above uploaded what changed; time the next ones.
          calibrate = false;
          calibrateDraw();
        }
        if (frameLog) frameLog.push({ start, work: performance.now() - start, edit: edited });
      }
      requestAnimationFrame(frame);
    }
    requestAnimationFrame(frame);
  }

  return {
    requestRender,
    /// Time the draw again (a new model).
    recalibrate: () => { calibrate = true; },
    timedDraw,
    chooseDragRatio,
    beginDrag,
    endDrag,
    get drawCost() { return drawCost; },
    get dragRatio() { return dragRatio; },
    start,
    /// Records every drawn frame (its start, the time its work took, whether it
    /// applied an edit) until stopFrames() returns the log.
    recordFrames: () => { frameLog = []; },
    stopFrames: () => { const log = frameLog; frameLog = null; return log; },
  };
}
