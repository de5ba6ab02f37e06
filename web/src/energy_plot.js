// The energy curve of the last solve (initial energy, then one value per iteration) on a log axis, one
// line per method.
export const methodColors = { arap: '#ff7b72', 'spokes-rims': '#79c0ff', iarap: '#7ee787' };

export function drawEnergyPlot(canvas, curves) {
  const ctx = canvas.getContext('2d');
  const { width, height } = canvas;
  ctx.clearRect(0, 0, width, height);
  const values = Object.values(curves).flat().filter((e) => e > 0);
  if (values.length === 0) return;
  const lo = Math.log10(Math.min(...values));
  const hi = Math.log10(Math.max(...values));
  const span = hi - lo > 1e-9 ? hi - lo : 1;
  const pad = 18;
  const maxLength = Math.max(...Object.values(curves).map((c) => c.length));
  const x = (k) => pad + (k / Math.max(maxLength - 1, 1)) * (width - 2 * pad);
  const y = (e) => height - pad - ((Math.log10(Math.max(e, 1e-300)) - lo) / span) * (height - 2 * pad);
  ctx.font = '10px sans-serif';
  ctx.fillStyle = '#9aa3b0';
  ctx.fillText(`${Math.max(...values).toExponential(2)}`, 2, 10);
  ctx.fillText(`${Math.min(...values).toExponential(2)}  (log scale, per iteration)`, 2, height - 4);
  for (const [method, curve] of Object.entries(curves)) {
    ctx.strokeStyle = methodColors[method] ?? '#ddd';
    ctx.beginPath();
    curve.forEach((e, k) => (k === 0 ? ctx.moveTo(x(k), y(e)) : ctx.lineTo(x(k), y(e))));
    ctx.stroke();
  }
}
