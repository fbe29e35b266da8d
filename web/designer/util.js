// Small helpers the designer's modules share. Pure: importing this file touches
// no DOM (`$` looks an element up only when called), so node can import it.

/// The page's element of id `id`.
export const $ = (id) => document.getElementById(id);

/// A number for the panel: 4 decimals, or 3 significant digits when it is tiny
/// (the designer's one number format, text.js).
import { decimals4, withNumbers } from '../text.js';
export { decimals4 as format };

/// The core's refusal {field, message} as the page says it: "field: message",
/// its numbers in the page's format (the core writes round-trip digits).
export const refusal = (r) => `${r.field ? `${r.field}: ` : ''}${withNumbers(r.message, decimals4)}`;

/// A deep copy of a preset (plain JSON data).
export const clone = (o) => JSON.parse(JSON.stringify(o));
