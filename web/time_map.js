// How a phedra glTF's animation time maps to the motion parameter t
// (extras.phedra.time_map, docs/formats.md "Time and t"; the C++ is
// exporters/src/time_map.cpp): time is linear in t but within ease seconds of
// an end that is a flexion limit, where t's distance from the limit grows as
// the square of time's distance from it.

/// The fraction of a segment's t-range reached at the fraction phi of its time.
export function easedFraction(phi, e0, e1) {
  phi = Math.min(Math.max(phi, 0), 1);
  const k = 1 / (1 - 0.5 * e0 - 0.5 * e1);
  if (phi < e0) return k * phi * phi / (2 * e0);
  if (phi > 1 - e1) return 1 - k * (1 - phi) * (1 - phi) / (2 * e1);
  return k * (phi - 0.5 * e0);
}

/// The inverse: the fraction of time at which the fraction g of the t-range is reached.
export function easedTimeFraction(g, e0, e1) {
  g = Math.min(Math.max(g, 0), 1);
  const k = 1 / (1 - 0.5 * e0 - 0.5 * e1);
  if (e0 > 0 && g < 0.5 * k * e0) return Math.sqrt(2 * e0 * g / k);
  if (e1 > 0 && g > 1 - 0.5 * k * e1) return 1 - Math.sqrt(2 * e1 * (1 - g) / k);
  return g / k + 0.5 * e0;
}

/// t at animation time `seconds` (a ping-pong file plays its segments back after the last).
export function tAtTime(map, seconds) {
  const segments = map.segments;
  const forward = segments[segments.length - 1].seconds[1];
  if (map.ping_pong && seconds > forward) seconds = 2 * forward - seconds;
  seconds = Math.min(Math.max(seconds, 0), forward);
  for (const s of segments) {
    const [start, end] = s.seconds, [t0, t1] = s.t, d = end - start;
    if (seconds > end) continue;
    if (d <= 0) return t1;
    const g = easedFraction((seconds - start) / d, s.ease_seconds[0] / d, s.ease_seconds[1] / d);
    return g >= 1 ? t1 : t0 + g * (t1 - t0);
  }
  return segments[segments.length - 1].t[1];
}

/// The first animation time showing t (null when no segment reaches it).
export function timeOfT(map, t) {
  for (const s of map.segments) {
    const [start, end] = s.seconds, [t0, t1] = s.t, d = end - start;
    if ((t - t0) * (t - t1) > 0) continue;
    if (t1 === t0 || d <= 0) return start;
    return start + d * easedTimeFraction((t - t0) / (t1 - t0), s.ease_seconds[0] / d, s.ease_seconds[1] / d);
  }
  return null;
}
