// The Energy box (issue 36): the exact energy landscape of the motion for fold
// springs at rest at a chosen state (t* as the design is made, or the slider's
// t), by the same core as `phedra mechanics --energy` (Designer.energy): E
// against t with the rest state, minima and maxima marked, whether the design is
// bistable and its barrier, and a cursor at the slider's t. An edit computes it
// again for the new design when the box shows it.
import { $, format, refusal } from './util.js';
import { energyPlot } from '../plot.js';

export function createEnergy({ state, designer }) {
  const button = $('energy-show');
  const rest = $('energy-rest');
  const plot = $('energy-plot');
  const status = $('energy-status');
  let result = null;
  let curve = null;  // t -> pixel of the drawn plot
  let restT = null;

  function describe(r) {
    const others = r.equilibria.filter((q) => !q.rest);
    const lines = [`${r.folds} fold springs at rest at t = ${format(r.rest_t)}; largest energy ${format(r.largest_E)}`];
    for (const q of others) lines.push(`${q.kind} at t = ${format(q.t)}, E = ${format(q.E)}`);
    lines.push(r.bistable ? `bistable: barrier ${format(r.barrier)} from the rest state, ${format(r.reverse_barrier)} back`
                          : 'one minimum: the rest state');
    return lines.join('\n');
  }

  function compute() {
    if (!state.info) return;
    restT = rest.value === 'slider' ? state.tOf(state.fraction) : state.info.t_star;
    const r = designer.energy(JSON.stringify({ rest_t: restT, samples: 201 }));
    if (!r.ok) {
      result = null;
      plot.innerHTML = '';
      status.textContent = refusal(r);
      return;
    }
    result = r;
    const samples = r.t.map((t, k) => [t, r.E[k]]);
    const drawn = energyPlot(samples, r.equilibria, { tLambda: state.info.t_lambda, tMu: state.info.t_mu, restT: r.rest_t, format });
    plot.innerHTML = drawn.svg;
    curve = drawn.x;
    status.textContent = describe(r);
    follow(state.tOf(state.fraction));
    button.textContent = 'Compute again';
  }

  function follow(t) {
    const cursor = plot.querySelector('.cursor');
    if (!cursor || !curve) return;
    cursor.setAttribute('x1', curve(t));
    cursor.setAttribute('x2', curve(t));
  }

  button.addEventListener('click', compute);
  rest.addEventListener('change', () => { if (result) compute(); });

  return {
    follow,
    /// A new design settled: its landscape, when one is shown.
    refresh() { if (result) compute(); },
    get result() { return result; },
  };
}
