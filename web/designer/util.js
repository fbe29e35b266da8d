// Small helpers the designer's modules share. Pure: importing this file touches
// no DOM (`$` looks an element up only when called), so node can import it.

/// The page's element of id `id`.
export const $ = (id) => document.getElementById(id);

/// A number for the panel: 4 decimals, or 3 significant digits when it is tiny
/// (the designer's one number format, text.js).
export { decimals4 as format } from '../text.js';

/// A deep copy of a preset (plain JSON data).
export const clone = (o) => JSON.parse(JSON.stringify(o));
