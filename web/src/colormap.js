// Colours of the per-vertex ARAP energy: log scale between the 5th and 99th percentiles of the free
// vertices (cell energies span orders of magnitude, and the nearly rigid constrained regions would
// otherwise set the low end), mapped on a perceptually ordered ramp from dark blue to yellow.
const ramp = [
  [0.267, 0.005, 0.329], [0.229, 0.322, 0.546], [0.128, 0.567, 0.551], [0.369, 0.789, 0.383], [0.993, 0.906, 0.144],
];

function rampColor(s, out, offset) {
  const x = Math.min(Math.max(s, 0), 1) * (ramp.length - 1);
  const i = Math.min(Math.floor(x), ramp.length - 2);
  const f = x - i;
  for (let k = 0; k < 3; ++k) out[offset + k] = ramp[i][k] * (1 - f) + ramp[i + 1][k] * f;
}

// energy: per-vertex values (>= 0); labels: 0 for free vertices; writes RGB triples into colors.
export function energyColors(energy, labels, colors) {
  const logs = Array.from(energy, (e) => Math.log10(Math.max(e, 1e-30)));
  const free = logs.filter((_, i) => labels[i] === 0);
  const sorted = (free.length > 0 ? free : [...logs]).sort((a, b) => a - b);
  const lo = sorted[Math.floor(0.05 * (sorted.length - 1))];
  const hi = sorted[Math.floor(0.99 * (sorted.length - 1))];
  const span = hi - lo > 1e-12 ? hi - lo : 1;
  for (let i = 0; i < logs.length; ++i) rampColor((logs[i] - lo) / span, colors, 3 * i);
}
