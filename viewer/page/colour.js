// The colours of the page: the path layers and the stock's deviation scale. One
// table serves the renderer (its shader takes these colours as uniforms), the
// legend and the tests.
//
// The deviation scale is diverging around a neutral band: |d| <= tol (within
// tolerance, neither gouge nor excess) is a light neutral grey; material left
// above it runs from pale to deep blue at the range's top `hi`, cuts below the
// design (gouges) from pale to deep red at its bottom `lo`; cells beyond the range
// are marked in colours of their own (dark purple above, dark brown below), so a
// range chosen by percentiles still shows where the extremes are. The path
// layers keep clear of both blue and red: cuts are charcoal, links green, rapids
// orange, tool axes purple-grey.

// sRGB bytes.
export const COLOURS = {
  part: [170, 175, 185],
  cuts: [45, 45, 50],
  links: [30, 150, 70],
  rapids: [235, 130, 20],
  'tool axes': [150, 110, 170],
  cutter: [200, 170, 60],
  neutral: [222, 222, 214],
  excessPale: [200, 222, 240],
  excessDeep: [33, 102, 172],
  excessBeyond: [64, 0, 90],
  gougePale: [250, 210, 190],
  gougeDeep: [190, 24, 43],
  gougeBeyond: [84, 48, 5],
  unmeasured: [245, 220, 120],
  offPart: [200, 200, 200],
  measure: [230, 0, 160],
  axes: [[210, 40, 40], [40, 160, 40], [40, 80, 220]],
};

export const css = ([r, g, b]) => `rgb(${r}, ${g}, ${b})`;
const mix = (a, b, t) => a.map((x, k) => Math.round(x + (b[k] - x) * t));

// The sRGB colour of deviation `d` (mm) on the range [lo, hi] (lo < -tol < tol < hi)
// for a measured cell; the renderer's shader computes the same.
export function deviationColour(d, { lo, hi, tol }) {
  if (Math.abs(d) <= tol) return COLOURS.neutral;
  if (d > hi) return COLOURS.excessBeyond;
  if (d < lo) return COLOURS.gougeBeyond;
  if (d > 0) return mix(COLOURS.excessPale, COLOURS.excessDeep, (d - tol) / Math.max(hi - tol, 1e-12));
  return mix(COLOURS.gougePale, COLOURS.gougeDeep, (-d - tol) / Math.max(-lo - tol, 1e-12));
}

// The colour of a stock vertex of `state` (0 measured, 1 no stock measured, 2 off
// the part) and deviation `d`.
export function cellColour(d, state, scale) {
  if (state === 1) return COLOURS.unmeasured;
  if (state === 2) return COLOURS.offPart;
  return deviationColour(d, scale);
}

// The `p`-quantile (0..1) of the sorted array `sorted`.
function quantile(sorted, p) {
  if (sorted.length === 0) return NaN;
  const x = p * (sorted.length - 1);
  const k = Math.floor(x);
  return sorted[k] + (sorted[Math.min(k + 1, sorted.length - 1)] - sorted[k]) * (x - k);
}

// Rounds a range end away from zero to two significant digits.
function round2(x) {
  if (x === 0) return 0;
  const e = 10 ** (Math.floor(Math.log10(Math.abs(x))) - 1);
  return Math.sign(x) * Math.ceil(Math.abs(x) / e - 1e-9) * e;
}

// The robust range of the deviations of measured cells (`dev`, `state` per
// vertex): each side's end is the 98th percentile of the cells beyond the
// tolerance on that side, at least twice the tolerance, so that one deep spot does
// not wash out the rest.
export function robustRange(dev, state, tol) {
  const above = [];
  const below = [];
  for (let k = 0; k < dev.length; k += 1) {
    if (state[k] !== 0) continue;
    if (dev[k] > tol) above.push(dev[k]);
    else if (dev[k] < -tol) below.push(-dev[k]);
  }
  above.sort((a, b) => a - b);
  below.sort((a, b) => a - b);
  const end = (xs) => Math.max(2 * tol, xs.length ? quantile(xs, 0.98) : 0);
  return {
    lo: -round2(end(below)),
    hi: round2(end(above)),
    tol,
    beyond: { below: below.filter((x) => x > end(below)).length, above: above.filter((x) => x > end(above)).length },
  };
}

// Share of the legend's bar given to the neutral band, and the least share of
// each side: the bar is a key, linear on each side, so that a tolerance far
// smaller than the range still shows.
const BAND = 0.16;
const SIDE = 0.14;

// Where the legend's bar puts -tol and +tol (fractions of its width).
export function barLayout({ lo, hi, tol }) {
  const below = Math.max(-tol - lo, 0);
  const above = Math.max(hi - tol, 0);
  const share = (1 - BAND) * (below / Math.max(below + above, 1e-12));
  const left = Math.min(Math.max(share, SIDE), 1 - BAND - SIDE);
  return { band: [left, left + BAND] };
}

// How many measured vertices lie below `lo` and above `hi`.
export function countBeyond(dev, state, lo, hi) {
  let [below, above] = [0, 0];
  for (let k = 0; k < dev.length; k += 1) {
    if (state[k] !== 0) continue;
    if (dev[k] < lo) below += 1;
    else if (dev[k] > hi) above += 1;
  }
  return { below, above };
}

// The legend's gradient (CSS) over [lo, hi]: red side, neutral band, blue side.
export function gradient(scale) {
  const [a, b] = barLayout(scale).band.map((x) => `${(100 * x).toFixed(2)}%`);
  const stops = [
    `${css(COLOURS.gougeDeep)} 0%`,
    `${css(COLOURS.gougePale)} ${a}`,
    `${css(COLOURS.neutral)} ${a}`,
    `${css(COLOURS.neutral)} ${b}`,
    `${css(COLOURS.excessPale)} ${b}`,
    `${css(COLOURS.excessDeep)} 100%`,
  ];
  return `linear-gradient(to right, ${stops.join(', ')})`;
}
