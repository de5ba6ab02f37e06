// Meshes for bench/drag_bench.mjs: a triangle OBJ read (v and f lines, f entries' vertex index before any
// slash; polygons fanned), one 1-to-4 midpoint subdivision (each edge's midpoint shared by its faces), and
// an OBJ writer, so that the benchmark can upload a 173K-vertex armadillo made from the 43K one.

// {V: Float64Array #V x 3, F: Uint32Array #F x 3} of an OBJ text; name labels errors.
export function readObj(text, name) {
  const V = [], F = [];
  text.split('\n').forEach((line, at) => {
    const words = line.trim().split(/\s+/);
    if (words[0] === 'v') {
      V.push(Number(words[1]), Number(words[2]), Number(words[3]));
    } else if (words[0] === 'f') {
      const corners = words.slice(1).map((w) => Number(w.split('/')[0]) - 1);
      if (corners.some((c) => !Number.isInteger(c) || c < 0)) throw new Error(`${name}:${at + 1}: face index not a positive whole number`);
      for (let k = 1; k + 1 < corners.length; ++k) F.push(corners[0], corners[k], corners[k + 1]);
    }
  });
  return { V: Float64Array.from(V), F: Uint32Array.from(F) };
}

export function subdivideMidpoint({ V, F }) {
  const vertexCount = V.length / 3;
  const midpoint = new Map();
  const extra = [];
  const middle = (a, b) => {
    const key = a < b ? a * vertexCount + b : b * vertexCount + a;
    let index = midpoint.get(key);
    if (index === undefined) {
      index = vertexCount + extra.length / 3;
      midpoint.set(key, index);
      for (let k = 0; k < 3; ++k) extra.push(0.5 * (V[3 * a + k] + V[3 * b + k]));
    }
    return index;
  };
  const faces = new Uint32Array(4 * F.length);
  for (let f = 0; f < F.length / 3; ++f) {
    const [a, b, c] = [F[3 * f], F[3 * f + 1], F[3 * f + 2]];
    const ab = middle(a, b), bc = middle(b, c), ca = middle(c, a);
    faces.set([a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca], 12 * f);
  }
  const positions = new Float64Array(V.length + extra.length);
  positions.set(V);
  positions.set(extra, V.length);
  return { V: positions, F: faces };
}

export function writeObj({ V, F }) {
  const lines = [];
  for (let i = 0; i < V.length; i += 3) lines.push(`v ${V[i]} ${V[i + 1]} ${V[i + 2]}`);
  for (let f = 0; f < F.length; f += 3) lines.push(`f ${F[f] + 1} ${F[f + 1] + 1} ${F[f + 2] + 1}`);
  return `${lines.join('\n')}\n`;
}
