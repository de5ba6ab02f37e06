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
