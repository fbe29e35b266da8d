// The viewer's fold-angle plot: a hinge's angle against t, on an axis scaled to
// the data (a hinge moving between -7.8 and -5 degrees is not a flat line on a
// +-180 axis), with marks at t* and the limits. Pure (SVG text): node imports it.

/// 1, 2 or 5 times a power of ten, at least x.
function roundUp125(x) {
  const p = Math.pow(10, Math.floor(Math.log10(x)));
  for (const k of [1, 2, 5, 10]) if (k * p >= x * (1 - 1e-12)) return k * p;
  return 10 * p;
}

/// A value axis for data in [min, max]: round ticks (1, 2, 5 steps, about five)
/// around the data, at least `minimumSpan` wide (a nearly constant angle: a
/// degree, not a hair-thin band of noise), never wider than `limit` ([-180, 180]).
/// The axis is at most twice the data's range once that exceeds the minimum.
/// Returns {lo, hi, step, ticks}.
export function niceAxis(min, max, { minimumSpan = 1, limit = [-180, 180] } = {}) {
  let a = Math.min(min, max), b = Math.max(min, max);
  if (!Number.isFinite(a) || !Number.isFinite(b)) return { lo: limit[0], hi: limit[1], step: 90, ticks: [-180, -90, 0, 90, 180] };
  if (b - a < minimumSpan) {
    const middle = 0.5 * (a + b);
    a = middle - 0.5 * minimumSpan;
    b = middle + 0.5 * minimumSpan;
  }
  const step = roundUp125((b - a) / 5);
  let lo = Math.floor(a / step + 1e-9) * step, hi = Math.ceil(b / step - 1e-9) * step;
  lo = Math.max(lo, limit[0]);
  hi = Math.min(hi, limit[1]);
  const ticks = [];
  for (let k = Math.ceil(lo / step - 1e-9); k * step <= hi + 1e-9 * step; ++k) ticks.push(Number((k * step).toPrecision(12)));
  return { lo, hi, step, ticks };
}

const escape = (s) => String(s).replace(/&/g, '&amp;').replace(/</g, '&lt;').replace(/>/g, '&gt;');

/// The plot's geometry (pixels).
export const plotBox = { width: 330, height: 132, left: 40, right: 8, top: 18, bottom: 30 };

/// The SVG of `samples` ([t, angle] pairs) against t over [tLambda, tMu] with a
/// mark at tStar; `format` writes numbers. Returns {svg, axis, x (t -> pixel)}.
export function foldAnglePlot(samples, { tLambda, tMu, tStar, format, colour = '#ffeb3b' }) {
  const box = plotBox;
  const angles = samples.map(([, a]) => a);
  const min = Math.min(...angles), max = Math.max(...angles);
  const axis = niceAxis(min, max);
  const x = (t) => box.left + (t - tLambda) / (tMu - tLambda) * (box.width - box.left - box.right);
  const y = (a) => box.top + (axis.hi - a) / (axis.hi - axis.lo) * (box.height - box.top - box.bottom);
  const bottom = box.height - box.bottom;
  const label = (tx, ty, text, anchor = 'start', fill = '#9fb3c8') =>
    `<text x="${tx.toFixed(1)}" y="${ty.toFixed(1)}" text-anchor="${anchor}" font-size="10" fill="${fill}">${escape(text)}</text>`;
  const svg = [`<svg xmlns="http://www.w3.org/2000/svg" width="${box.width}" height="${box.height}" role="img" ` +
               `aria-label="fold angle over the motion" data-lo="${axis.lo}" data-hi="${axis.hi}" data-min="${min}" data-max="${max}">`,
               label(box.left, 10, `fold angle (degrees, valley > 0) from ${format(min)} to ${format(max)}`)];
  for (const a of axis.ticks) {
    svg.push(`<line x1="${box.left}" x2="${box.width - box.right}" y1="${y(a).toFixed(1)}" y2="${y(a).toFixed(1)}" stroke="${a === 0 ? '#5a6675' : '#333b45'}"/>`,
             label(box.left - 4, y(a) + 3.5, format(a), 'end'));
  }
  // t*: where the design's configuration is.
  if (tStar >= Math.min(tLambda, tMu) && tStar <= Math.max(tLambda, tMu)) {
    svg.push(`<line x1="${x(tStar).toFixed(1)}" x2="${x(tStar).toFixed(1)}" y1="${box.top}" y2="${bottom}" stroke="#66bb6a" stroke-dasharray="2 3"/>`,
             label(x(tStar), bottom + 11, 't*', 'middle', '#a5d6a7'));
  }
  svg.push(`<polyline fill="none" stroke="${colour}" stroke-width="1.5" points="${samples.map(([t, a]) => `${x(t).toFixed(1)},${y(a).toFixed(1)}`).join(' ')}"/>`,
           `<line class="cursor" y1="${box.top}" y2="${bottom}" stroke="#e8e8e8" stroke-dasharray="3 2"/>`,
           label(box.left, box.height - 4, `t\u03bb ${format(tLambda)}`),
           label(box.width - box.right, box.height - 4, `${format(tMu)} t\u03bc`, 'end'),
           '</svg>');
  return { svg: svg.join(''), axis: { ...axis, min, max }, x };
}

/// The designer's energy plot (phedra mechanics --energy): E against t over
/// [tLambda, tMu], the rest state marked (a diamond and a dashed line), minima
/// (circles) and maxima (triangles), a cursor at the slider's t. `samples`:
/// [t, E] pairs; `equilibria`: [{t, kind, E, rest}]. Returns {svg, x}.
export function energyPlot(samples, equilibria, { tLambda, tMu, restT, format }) {
  const box = { ...plotBox, height: 150 };
  const energies = samples.map(([, e]) => e);
  const max = Math.max(...energies, 0);
  const axis = niceAxis(0, max > 0 ? max : 1, { minimumSpan: max > 0 ? max * 1e-6 : 1, limit: [0, Infinity] });
  const x = (t) => box.left + (t - tLambda) / (tMu - tLambda) * (box.width - box.left - box.right);
  const y = (e) => box.top + (axis.hi - e) / (axis.hi - axis.lo) * (box.height - box.top - box.bottom);
  const bottom = box.height - box.bottom;
  const label = (tx, ty, text, anchor = 'start', fill = '#9fb3c8') =>
    `<text x="${tx.toFixed(1)}" y="${ty.toFixed(1)}" text-anchor="${anchor}" font-size="10" fill="${fill}">${escape(text)}</text>`;
  const minima = equilibria.filter((q) => q.kind === 'minimum').length;
  const svg = [`<svg xmlns="http://www.w3.org/2000/svg" width="${box.width}" height="${box.height}" role="img" ` +
               `aria-label="energy over the motion" data-minima="${minima}" data-max="${max}">`,
               label(box.left, 10, `energy of the folds at rest at t = ${format(restT)} (largest ${format(max)})`)];
  for (const e of axis.ticks) {
    svg.push(`<line x1="${box.left}" x2="${box.width - box.right}" y1="${y(e).toFixed(1)}" y2="${y(e).toFixed(1)}" stroke="#333b45"/>`,
             label(box.left - 4, y(e) + 3.5, format(e), 'end'));
  }
  svg.push(`<line x1="${x(restT).toFixed(1)}" x2="${x(restT).toFixed(1)}" y1="${box.top}" y2="${bottom}" stroke="#ffb74d" stroke-dasharray="2 3"/>`,
           `<polyline fill="none" stroke="#4fc3f7" stroke-width="1.5" points="${samples.map(([t, e]) => `${x(t).toFixed(1)},${y(e).toFixed(1)}`).join(' ')}"/>`);
  for (const q of equilibria) {
    const cx = x(q.t), cy = y(q.E);
    if (q.rest) {
      svg.push(`<path class="rest" d="M${cx.toFixed(1)} ${(cy - 6).toFixed(1)} l5 6 l-5 6 l-5 -6 z" fill="#ffb74d" stroke="#222"/>`);
    } else if (q.kind === 'minimum') {
      svg.push(`<circle class="minimum" cx="${cx.toFixed(1)}" cy="${cy.toFixed(1)}" r="4.5" fill="#66bb6a" stroke="#222"/>`);
    } else {
      svg.push(`<path class="maximum" d="M${cx.toFixed(1)} ${(cy - 6).toFixed(1)} l5 9 l-10 0 z" fill="#ef5350" stroke="#222"/>`);
    }
  }
  svg.push(`<line class="cursor" y1="${box.top}" y2="${bottom}" stroke="#e8e8e8" stroke-dasharray="3 2"/>`,
           label(box.left, box.height - 4, `t\u03bb ${format(tLambda)}`),
           label(box.width - box.right, box.height - 4, `${format(tMu)} t\u03bc`, 'end'),
           '</svg>');
  return { svg: svg.join(''), x };
}
