// The UV tab's pictures: a checkerboard texture for the 3D copies and the 2D layout of the map.
//
// Both use the same checker coordinates: the map scaled so that its bounding box's longer side spans
// `checks` squares, so a square on the mesh and in the layout is the same patch of the plane.
import * as THREE from 'three';

export const checks = 16;

// {min: [u, v], extent} of a #V x 2 Float32Array.
function bounds(uv) {
  const min = [Infinity, Infinity];
  const max = [-Infinity, -Infinity];
  for (let i = 0; i < uv.length; i += 2) {
    for (let k = 0; k < 2; ++k) {
      min[k] = Math.min(min[k], uv[i + k]);
      max[k] = Math.max(max[k], uv[i + k]);
    }
  }
  return { min, extent: Math.max(max[0] - min[0], max[1] - min[1], 1e-300) };
}

// The map in checker units: (uv - min) / extent * checks.
export function checkerCoordinates(uv) {
  const { min, extent } = bounds(uv);
  const out = new Float32Array(uv.length);
  for (let i = 0; i < uv.length; i += 2) {
    out[i] = ((uv[i] - min[0]) / extent) * checks;
    out[i + 1] = ((uv[i + 1] - min[1]) / extent) * checks;
  }
  return out;
}

// Which faces the map folds over: signed UV area <= 0 (the server's det J <= 0, faces counter-clockwise).
export function flippedFaces(faces, uv) {
  const flipped = new Uint8Array(faces.length / 3);
  for (let f = 0; f < flipped.length; ++f) {
    const [a, b, c] = [faces[3 * f], faces[3 * f + 1], faces[3 * f + 2]];
    const area = (uv[2 * b] - uv[2 * a]) * (uv[2 * c + 1] - uv[2 * a + 1]) - (uv[2 * b + 1] - uv[2 * a + 1]) * (uv[2 * c] - uv[2 * a]);
    flipped[f] = area <= 0 ? 1 : 0;
  }
  return flipped;
}

// One check of light and dark grey per texture repeat (RepeatWrapping tiles it over checker units / 2).
export function checkerTexture() {
  const size = 64;
  const canvas = Object.assign(document.createElement('canvas'), { width: size, height: size });
  const ctx = canvas.getContext('2d');
  ctx.fillStyle = '#f0f0f0';
  ctx.fillRect(0, 0, size, size);
  ctx.fillStyle = '#3a5a8c';
  ctx.fillRect(0, 0, size / 2, size / 2);
  ctx.fillRect(size / 2, size / 2, size / 2, size / 2);
  const texture = new THREE.CanvasTexture(canvas);
  texture.wrapS = texture.wrapT = THREE.RepeatWrapping;
  texture.repeat.set(0.5, 0.5); // checker units: one square per unit, two per texture
  texture.magFilter = THREE.NearestFilter;
  texture.colorSpace = THREE.SRGBColorSpace;
  return texture;
}

// The layout on a 2D canvas: the triangles filled with the checkerboard the 3D copies show (flipped ones
// red), edges drawn while they stay apart (under 20,000 faces). checker: checkerCoordinates(uv).
export function drawLayout(canvas, faces, checker, flipped) {
  const ctx = canvas.getContext('2d');
  const { width, height } = canvas;
  ctx.clearRect(0, 0, width, height);
  const margin = 6;
  const scale = (Math.min(width, height) - 2 * margin) / checks;
  const x = (i) => margin + checker[2 * i] * scale;
  const y = (i) => height - margin - checker[2 * i + 1] * scale; // v up
  // Two squares of side `scale` per pattern tile, its origin on the checker grid's corner (0, 0).
  const tile = Object.assign(document.createElement('canvas'), { width: 2 * scale, height: 2 * scale });
  const t = tile.getContext('2d');
  t.fillStyle = '#f0f0f0';
  t.fillRect(0, 0, 2 * scale, 2 * scale);
  t.fillStyle = '#3a5a8c';
  t.fillRect(0, 0, scale, scale);
  t.fillRect(scale, scale, scale, scale);
  const pattern = ctx.createPattern(tile, 'repeat');
  pattern.setTransform(new DOMMatrix().translate(margin, height - margin));
  const edges = faces.length / 3 < 20000;
  ctx.lineWidth = 0.5;
  ctx.strokeStyle = '#0005';
  for (let f = 0; f < faces.length / 3; ++f) {
    const [a, b, c] = [faces[3 * f], faces[3 * f + 1], faces[3 * f + 2]];
    ctx.fillStyle = flipped[f] ? '#e62929' : pattern;
    ctx.beginPath();
    ctx.moveTo(x(a), y(a));
    ctx.lineTo(x(b), y(b));
    ctx.lineTo(x(c), y(c));
    ctx.closePath();
    ctx.fill();
    if (edges) ctx.stroke();
  }
}

// An atlas (corner UVs in [0,1]^2, #F x 3 x 2, and a chart per face) shows `atlasChecks` squares across the
// unit square, as `iarap param --picture` draws it.
export const atlasChecks = 64;

// A distinct, mid-bright colour per chart (hues a golden angle apart, as sRGB HSL); grey for no chart (-1).
// A THREE.Color: toArray() gives linear RGB for vertex colours, getStyle() the canvas's sRGB.
export function chartColor(chart) {
  if (chart < 0) return new THREE.Color().setHSL(0, 0, 0.5, THREE.SRGBColorSpace);
  return new THREE.Color().setHSL((chart * 0.618033988749895) % 1, 0.6, 0.62, THREE.SRGBColorSpace);
}

// Per-corner arrays of an atlas for the 3D copies: checker coordinates (#F x 3 x 2: corner uv * atlasChecks)
// and the chart's colour (#F x 3 x 3), which tints the checkerboard.
export function atlasCornerArrays(cornerUv, chart) {
  const checker = new Float32Array(cornerUv.length);
  for (let i = 0; i < cornerUv.length; ++i) checker[i] = cornerUv[i] * atlasChecks;
  const colors = new Float32Array((cornerUv.length / 2) * 3);
  for (let f = 0; f < chart.length; ++f) {
    const c = chartColor(chart[f]).toArray();
    for (let k = 0; k < 3; ++k) colors.set(c, 9 * f + 3 * k);
  }
  return { checker, colors };
}

// Faces whose corner UVs fold over (signed area <= 0), as flippedFaces does for a map per vertex; faces of
// no chart (-1: no area, their corners on one point) are not counted.
export function flippedAtlasFaces(cornerUv, chart) {
  const flipped = new Uint8Array(chart.length);
  for (let f = 0; f < chart.length; ++f) {
    const u = (k, d) => cornerUv[6 * f + 2 * k + d];
    const area = (u(1, 0) - u(0, 0)) * (u(2, 1) - u(0, 1)) - (u(1, 1) - u(0, 1)) * (u(2, 0) - u(0, 0));
    flipped[f] = chart[f] >= 0 && area <= 0 ? 1 : 0;
  }
  return flipped;
}

// The atlas on a 2D canvas: the unit square's outline, each chart's triangles filled in its colour (flipped
// ones red), edges drawn while they stay apart (under 20,000 faces).
export function drawAtlas(canvas, cornerUv, chart, flipped) {
  const ctx = canvas.getContext('2d');
  const { width, height } = canvas;
  ctx.clearRect(0, 0, width, height);
  const margin = 6;
  const side = Math.min(width, height) - 2 * margin;
  const x = (f, k) => margin + cornerUv[6 * f + 2 * k] * side;
  const y = (f, k) => height - margin - cornerUv[6 * f + 2 * k + 1] * side; // v up
  ctx.strokeStyle = '#fff8';
  ctx.lineWidth = 1;
  ctx.strokeRect(margin - 0.5, height - margin - side - 0.5, side + 1, side + 1);
  const edges = chart.length < 20000;
  ctx.lineWidth = 0.3;
  ctx.strokeStyle = '#0006';
  for (let f = 0; f < chart.length; ++f) {
    ctx.fillStyle = flipped[f] ? '#e62929' : chartColor(chart[f]).getStyle();
    ctx.beginPath();
    ctx.moveTo(x(f, 0), y(f, 0));
    ctx.lineTo(x(f, 1), y(f, 1));
    ctx.lineTo(x(f, 2), y(f, 2));
    ctx.closePath();
    ctx.fill();
    if (edges) ctx.stroke();
  }
}
