// Sampled time: which two frames surround a time, and how far between them (pure, tested in
// web/test/timeline.test.mjs).

/** Index i and weight w with times[i] <= t <= times[i+1], w in [0, 1]; clamps outside. */
export function bracket(times, t) {
  const n = times.length;
  if (n === 0) return { i: 0, w: 0 };
  if (n === 1 || t <= times[0]) return { i: 0, w: 0 };
  if (t >= times[n - 1]) return { i: n - 2, w: 1 };
  let lo = 0;
  let hi = n - 1;
  while (hi - lo > 1) {
    const mid = (lo + hi) >> 1;
    if (times[mid] <= t) lo = mid;
    else hi = mid;
  }
  const span = times[hi] - times[lo];
  return { i: lo, w: span > 0 ? (t - times[lo]) / span : 0 };
}

/** Linear interpolation of entries [offset, offset + count) of frames i and i + 1 of `flat`. */
export function interpolate(flat, stride, offset, count, i, w, out) {
  const a = i * stride + offset;
  const b = Math.min(i + 1, flat.length / stride - 1) * stride + offset;
  for (let k = 0; k < count; ++k) out[k] = flat[a + k] * (1 - w) + flat[b + k] * w;
  return out;
}

/** Playback: advances real time × speed, wrapping at the end. */
export function advance(t, dt, speed, t0, t1) {
  if (!(t1 > t0)) return t0;
  let next = t + dt * speed;
  if (next > t1) next = t0 + ((next - t0) % (t1 - t0));
  return next;
}
