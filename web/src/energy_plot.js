// The energy curve of the last solve (initial energy, then one value per iteration), one line per method.
// The axis is logarithmic while every energy is positive, and a symmetric log (linear within 0.1% of the
// largest magnitude around 0, with the 0 line drawn) once one is not: original ARAP's energy can go below 0.
export const methodColors = { arap: '#ff7b72', 'spokes-rims': '#79c0ff', iarap: '#7ee787' };

// unit: what one step of the curves is (the x axis).
export function drawEnergyPlot(canvas, curves, unit = 'iteration') {
  const ctx = canvas.getContext('2d');
  const { width, height } = canvas;
  ctx.clearRect(0, 0, width, height);
  const values = Object.values(curves).flat().filter(Number.isFinite);
  if (values.length === 0) return;
  const signed = values.some((e) => e <= 0);
  const top = Math.max(...values.map(Math.abs), 1e-300);
  const linear = 1e-3 * top;
  const f = signed ? (e) => Math.sign(e) * Math.log10(1 + Math.abs(e) / linear) : (e) => Math.log10(e);
  const lo = f(Math.min(...values));
  const hi = f(Math.max(...values));
  const span = hi - lo > 1e-9 ? hi - lo : 1;
  const pad = 18;
  const maxLength = Math.max(...Object.values(curves).map((c) => c.length));
  const x = (k) => pad + (k / Math.max(maxLength - 1, 1)) * (width - 2 * pad);
  const y = (e) => height - pad - ((f(e) - lo) / span) * (height - 2 * pad);
  ctx.font = '10px sans-serif';
  ctx.fillStyle = '#9aa3b0';
  ctx.fillText(`${Math.max(...values).toExponential(2)}`, 2, 10);
  ctx.fillText(`${Math.min(...values).toExponential(2)}  (${signed ? 'symlog' : 'log'} scale, per ${unit})`, 2, height - 4);
  if (signed && lo < 0 && hi > 0) {
    ctx.strokeStyle = '#555';
    ctx.setLineDash([3, 3]);
    ctx.beginPath();
    ctx.moveTo(pad, y(0));
    ctx.lineTo(width - pad, y(0));
    ctx.stroke();
    ctx.setLineDash([]);
    ctx.fillText('0', width - pad + 2, y(0) + 3);
  }
  for (const [method, curve] of Object.entries(curves)) {
    ctx.strokeStyle = methodColors[method] ?? '#ddd';
    ctx.beginPath();
    curve.forEach((e, k) => (k === 0 ? ctx.moveTo(x(k), y(e)) : ctx.lineTo(x(k), y(e))));
    ctx.stroke();
  }
}
