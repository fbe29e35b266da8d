// What the pages write: one number format a page (the designer 4 decimals, the
// viewer 4 significant digits), the core's texts rewritten in it, the status
// line without the interval the page shows already, and the page title from the
// preset's name and the file it came from. Pure: node imports it
// (tests/js/designer_state_test.mjs).

/// The designer's numbers: 4 decimals (t, heights and the limits line up), or 3
/// significant digits in exponent form when tiny or huge (an oversized panel's
/// 1.398e+08 stays readable, not 139800000.0000).
export const decimals4 = (x) => (x === undefined || x === null || !Number.isFinite(x) ? '–'
  : (Math.abs(x) < 1e-3 && x !== 0) || Math.abs(x) >= 1e6 ? x.toExponential(2) : x.toFixed(4));

/// The viewer's numbers: 4 significant digits (no 16-digit noise on screen).
export const significant4 = (x) => (x === undefined || x === null || !Number.isFinite(x) ? '–'
  : (Math.abs(x) < 1e-3 && x !== 0) || Math.abs(x) >= 1e6 ? x.toExponential(2) : Number(x.toPrecision(4)).toString());

/// "a bow-tie", "an oversized panel": the article a shape's name takes.
export const withArticle = (word) => `${/^[aeiou]/i.test(String(word)) ? 'an' : 'a'} ${word}`;

// A decimal number in running text: not part of a name ("S_3", "trajectory[2][2]" are
// integers and stay), with an optional exponent; not a percentage (those keep
// their one decimal, as the pages write shares).
const decimal = /(?<![\w.])-?\d+\.\d+(?:e[-+]?\d+)?(?![\w.]|\s*%)/g;

/// `text` with every decimal number written by `format` (a number -> text).
export function withNumbers(text, format) {
  return String(text).replace(decimal, (s) => format(Number(s)));
}

/// A field hint of the core ("increase trajectory[2][2] (now 1.5) by more than
/// about 0.32") as a maker reads it, in the handles' names (handles.js
/// handleName): {verb: 'raise', subject: 'trajectory point 2', tail: ' by more than 0.3200 (now 1.5000)', field:
/// 'trajectory[2][2]'}; numbers by `format`. A text it does not know: verb ''
/// and the text as the tail.
export function makerHint(hint, format) {
  const m = /^(increase|decrease) (\S+) \(now ([^)]*)\) by more than about (\S+)(.*)$/.exec(String(hint));
  if (!m) return { verb: '', subject: '', tail: withNumbers(hint, format), field: null };
  const [, direction, field, now, by, rest] = m;
  const up = direction === 'increase';
  const amount = format(Number(by)), was = `(now ${format(Number(now))})${withNumbers(rest, format)}`;
  const height = (subject) => ({ verb: up ? 'raise' : 'lower', subject, tail: ` by more than ${amount} ${was}`, field });
  let k;
  if ((k = /^apex_heights\[(\d+)\]$/.exec(field))) return height(`apex S_${k[1]}`);
  if ((k = /^tube\.apex_heights\[(\d+)\]$/.exec(field))) return height(`apex S_${k[1]}`);
  if ((k = /^grid\.([uw])_heights\[(\d+)\]$/.exec(field))) return height(`${k[1]} line ${k[2]} of the grid`);
  if ((k = /^row\.free_heights\[(\d+)\]$/.exec(field))) return height(`height of row cell ${Number(k[1]) + 1}`);
  if ((k = /^couplings\[(\d+)\]\.free_heights\[(\d+)\]$/.exec(field))) return height(`free height ${k[2]} of coupling ${k[1]}`);
  if ((k = /^couplings\[(\d+)\]\.free_height$/.exec(field))) return height(`free height of coupling ${k[1]}`);
  if ((k = /^trajectory\[(\d+)\]\[2\]$/.exec(field))) return height(`trajectory point ${k[1]}`);
  const axis = (c) => 'xyz'[Number(c)];
  if ((k = /^trajectory\[(\d+)\]\[([01])\]$/.exec(field))) {
    return { verb: 'move', subject: `trajectory point ${k[1]}`, tail: ` ${up ? '+' : '−'}${axis(k[2])} by more than ${amount} ${was}`, field };
  }
  if ((k = /^directions\[(\d+)\]\[([012])\]$/.exec(field))) {
    return { verb: 'turn', subject: `direction of profile ${k[1]}`, tail: ` (its ${axis(k[2])} ${up ? 'up' : 'down'} by more than ${amount}) ${was}`, field };
  }
  return { verb: direction, subject: field, tail: ` by more than ${amount} ${was}`, field };
}

/// The core's buildability summary for a page that shows the flexion interval
/// already (its limits under the slider, or on their own line): numbers in the
/// page's format, the interval itself left out.
export function statusSummary(summary, format) {
  const text = String(summary)
    .replace(/^(buildable over the whole flexion interval) \[[^\]]*\]/, '$1')
    .replace(/( % of the flexion interval) \[[^\]]*\]/, '$1');
  return withNumbers(text, format);
}

/// The file name of a path or URL ("presets/default.json" -> "default.json").
export const baseName = (path) => String(path ?? '').split(/[\\/]/).pop();

/// The title of a page: the preset's name, and the file when it says more
/// ("mixed-signs" from default.json: both; grid-3x3 from grid-3x3.json: the
/// name only). Returns {name, file (the text after the name, '' for none), document (the tab's title)}.
export function pageTitle({ name, file, edited = false, page = 'phedra' }) {
  const shownName = name || baseName(file).replace(/\.(json|glb|gltf)$/i, '') || 'unnamed';
  const stem = baseName(file).replace(/\.(json|glb|gltf)$/i, '');
  const parts = [];
  if (file && stem !== shownName) parts.push(baseName(file));
  if (edited) parts.push('edited');
  const fileText = parts.join(', ');
  return { name: shownName, file: fileText, document: `${shownName}${fileText ? ` (${fileText})` : ''} · ${page}` };
}

/// A preset as data, comparable whatever the key order and the "$schema" line.
export function canonicalPreset(p) {
  const sort = (v) => (Array.isArray(v) ? v.map(sort) : v && typeof v === 'object'
    ? Object.fromEntries(Object.keys(v).filter((k) => k !== '$schema').sort().map((k) => [k, sort(v[k])])) : v);
  return JSON.stringify(sort(p));
}
