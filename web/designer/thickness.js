// The Thick panels box (issue 27): plates of a thickness offset to one side of
// the panels and bevelled at the hinges, by the same core as `phedra check
// --thickness` (Designer.thick): the thick interval, what ends it, and the
// plates drawn as solids at the slider's t (Designer.plateTriangles) in place of
// the zero-thickness panels. An edit drops the plates (they belong to the design
// they were cut for); they follow when the edit settles.
import * as THREE from 'three';
import { withNumbers } from '../text.js';
import { $, format, refusal } from './util.js';

/// `designer`: the core's Designer; `surface`: the panels (hidden while plates show).
/// `onChange`: the plates were shown, hidden or moved to another t (the status
/// and the buildable bar follow the plates' thick interval while they show).
export function createThickness({ scene, state, designer, surface, requestRender, onChange = () => {} }) {
  const plates = new THREE.Mesh(new THREE.BufferGeometry(), new THREE.MeshLambertMaterial({ color: 0xc9a36b, flatShading: true }));
  plates.visible = false;
  scene.add(plates);
  const button = $('thick-show');
  const input = $('thick-value');
  const side = $('thick-side');
  const status = $('thick-status');
  let shown = false;
  let report = null;

  const say = (text) => { status.textContent = text; };

  /// The plates' triangles at t into the mesh; false when the core has none (an edit dropped them).
  function upload(t) {
    const triangles = designer.plateTriangles(t);
    if (triangles.ok === false || triangles.length === 0) return false;
    const geometry = plates.geometry;
    const attribute = geometry.getAttribute('position');
    if (!attribute || attribute.array.length !== triangles.length) {
      geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(triangles), 3));
    } else {
      attribute.array.set(triangles);
      attribute.needsUpdate = true;
    }
    geometry.computeBoundingSphere();
    return true;
  }

  function describe(r) {
    const lines = [`${r.plates} plates ${format(r.thickness)} thick on the ${r.side} side (smallest bevel ${format(r.smallest_bevel_degrees)}°), ` +
                   `volume ${format(r.volume)} of ${format(r.thickness * r.panel_area)} (thickness × panel area)`];
    if (!r.interval) {
      lines.push(`the plates collide at t*: ${r.at_t_star}`);
    } else {
      const whole = r.ends.length === 0 && r.interval[0] === state.info.t_lambda && r.interval[1] === state.info.t_mu;
      lines.push(`thick interval [${format(r.interval[0])}, ${format(r.interval[1])}]` +
                 (whole ? ': the whole flexion interval' : ` of [${format(state.info.t_lambda)}, ${format(state.info.t_mu)}]`));
      for (const e of r.ends) lines.push(`${e.side} t = ${format(e.t)}: ${e.text}`);
    }
    return lines.join('\n');
  }

  /// Cuts the plates for the design shown (the box's thickness and side).
  function compute() {
    if (!state.info) return;
    if (input.value === '') input.value = format(0.01 * state.info.model_size);
    const thickness = Number(input.value);
    if (!(thickness > 0)) {
      say('the thickness must be a positive number (model units)');
      return hide();
    }
    say('cutting the plates…');
    const r = designer.thick(JSON.stringify({ thickness, side: side.value }));
    if (!r.ok) {
      report = null;
      if (r.field === 'thickness') {
        // Too thick for a panel: in the page's words, the thickest that fits, the panel shown.
        // The core says "a plate T thick does not fit on panel K (strip i, column j): WHY (a thinner plate, or a wider panel)".
        const m = /does not fit on panel (\d+)( \(([^)]*)\))?: (.*?)( \(a thinner plate, or a wider panel\))?$/.exec(r.message);
        if (m) surface.highlightPanel(Number(m[1]));
        const what = m ? `on panel ${m[1]} (${m[3] ? `${m[3]}, ` : ''}highlighted): ${withNumbers(m[4], format)}` : `: ${withNumbers(r.message, format)}`;
        say(`plates ${format(thickness)} thick do not fit ${what}.` +
            (r.thickest ? ` The thickest plates that fit at t* are ${format(r.thickest)} thick${side.value === r.thickest_side ? '' : ` (on the ${r.thickest_side} side${side.value === 'auto' ? ', which auto then takes' : ': choose it'})`}: type that or less above.` : ''));
      } else {
        say(refusal(r));
      }
      return hide();
    }
    report = r;
    say(describe(r));
    show();
  }

  function show() {
    shown = upload(state.tOf(state.fraction));
    plates.visible = shown;
    surface.showPanels(!shown);
    button.textContent = shown ? 'Hide plates' : 'Show plates';
    state.thick = shown ? report : null;
    onChange();
    requestRender();
  }

  function hide() {
    shown = false;
    plates.visible = false;
    surface.showPanels(true);
    button.textContent = 'Show plates';
    state.thick = null;
    onChange();
    requestRender();
  }

  button.addEventListener('click', () => (shown ? hide() : compute()));
  for (const control of [input, side]) control.addEventListener('change', () => { if (shown) compute(); });

  return {
    /// The slider moved (the positions at t are shown): the plates follow.
    follow(t) {
      if (!shown) return;
      if (!upload(t)) {  // an edit dropped them: the panels until it settles
        plates.visible = false;
        surface.showPanels(true);
      }
      onChange();
    },
    /// A new design settled: cut its plates again when they are shown.
    refresh() { if (shown) compute(); },
    get shown() { return shown; },
    get report() { return report; },
    /// The plates' triangles as drawn.
    triangles: () => plates.geometry.getAttribute('position')?.array ?? new Float32Array(0),
  };
}
