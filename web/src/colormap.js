// Colours of the per-vertex ARAP energy, one scale shared by every shown method so that copies side by
// side compare. Cell energies span orders of magnitude, so the scale is logarithmic between the 2nd and
// 98th percentiles of the free vertices of all methods (the nearly rigid constrained regions would
// otherwise set the low end), on a perceptually ordered ramp from dark blue to yellow. Original ARAP keeps
// negative cotan weights and its cells can have negative energies: then the scale is a symmetric log
// (linear within a band around 0) on a diverging ramp, purple below 0, white at 0, green above.
const sequential = [
  [0.267, 0.005, 0.329], [0.229, 0.322, 0.546], [0.128, 0.567, 0.551], [0.369, 0.789, 0.383], [0.993, 0.906, 0.144],
];
const diverging = [
  [0.251, 0.0, 0.294], [0.6, 0.439, 0.671], [0.969, 0.969, 0.969], [0.353, 0.682, 0.38], [0.0, 0.267, 0.106],
];

function rampColor(ramp, s, out, offset) {
  const x = Math.min(Math.max(s, 0), 1) * (ramp.length - 1);
  const i = Math.min(Math.floor(x), ramp.length - 2);
  const f = x - i;
  for (let k = 0; k < 3; ++k) out[offset + k] = ramp[i][k] * (1 - f) + ramp[i + 1][k] * f;
}

const percentile = (sorted, p) => sorted[Math.floor(p * (sorted.length - 1))];

// energies: [Float32Array per method] (#V each); labels: 0 for free vertices. Returns the shared scale
// {kind: 'log' | 'symlog', lo, hi, linear?} or null without values.
export function energyScale(energies, labels) {
  const values = [];
  for (const energy of energies) for (let i = 0; i < energy.length; ++i) if (labels[i] === 0) values.push(energy[i]);
  if (values.length === 0) for (const energy of energies) values.push(...energy);
  if (values.length === 0) return null;
  const sorted = Float64Array.from(values).sort();
  const lo = percentile(sorted, 0.02);
  const hi = percentile(sorted, 0.98);
  if (lo < 0) {
    // Symmetric in the magnitudes: their 98th percentile ends the scale, their 2nd percentile ends the
    // linear band around 0, so the typical magnitudes spread over the log part of both halves.
    const magnitudes = sorted.map(Math.abs).sort();
    const top = Math.max(percentile(magnitudes, 0.98), 1e-300);
    return { kind: 'symlog', lo: -top, hi: top, linear: Math.max(percentile(magnitudes, 0.02), 1e-6 * top) };
  }
  const floor = Math.max(lo, 1e-30);
  return { kind: 'log', lo: floor, hi: Math.max(hi, floor * (1 + 1e-12)) };
}

// The position of value e on the scale, 0 at lo and 1 at hi (clamped when drawn).
export function scalePosition(scale, e) {
  if (scale.kind === 'symlog') {
    const f = (x) => Math.sign(x) * Math.log10(1 + Math.abs(x) / scale.linear);
    return 0.5 + (0.5 * f(e)) / f(scale.hi);
  }
  return (Math.log10(Math.max(e, 1e-300)) - Math.log10(scale.lo)) / (Math.log10(scale.hi) - Math.log10(scale.lo));
}

export function scaleColor(scale, s, out, offset) {
  rampColor(scale.kind === 'symlog' ? diverging : sequential, s, out, offset);
}

// Writes RGB triples of energy on scale into colors.
export function energyColors(energy, scale, colors) {
  for (let i = 0; i < energy.length; ++i) scaleColor(scale, scalePosition(scale, energy[i]), colors, 3 * i);
}

// The colour bar: the ramp left to right with the range (and 0 for a signed scale) under it.
export function drawColorBar(canvas, scale) {
  const ctx = canvas.getContext('2d');
  const { width, height } = canvas;
  ctx.clearRect(0, 0, width, height);
  if (!scale) return;
  const rgb = [0, 0, 0];
  const barHeight = height - 16;
  for (let x = 0; x < width; ++x) {
    scaleColor(scale, x / (width - 1), rgb, 0);
    ctx.fillStyle = `rgb(${rgb.map((c) => Math.round(255 * c)).join(',')})`;
    ctx.fillRect(x, 0, 1, barHeight);
  }
  ctx.font = '10px sans-serif';
  ctx.fillStyle = '#ddd';
  ctx.textBaseline = 'bottom';
  ctx.textAlign = 'left';
  ctx.fillText(scale.lo.toExponential(2), 0, height);
  ctx.textAlign = 'right';
  ctx.fillText(scale.hi.toExponential(2), width, height);
  ctx.textAlign = 'center';
  ctx.fillText(scale.kind === 'symlog' ? '0 (symlog)' : 'log', width / 2, height);
}
