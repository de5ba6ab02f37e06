// Selection tools over the displayed mesh: a brush (vertices within a radius of the picked surface point)
// and a box (vertices whose projection falls in a screen rectangle, through the mesh). Labels per vertex:
// 0 free, 1 fixed, 2 handle.
import * as THREE from 'three';

export const FREE = 0;
export const FIXED = 1;
export const HANDLE = 2;

const paintLabels = { fixed: FIXED, handle: HANDLE, erase: FREE };

export function paintLabel(paint) {
  return paintLabels[paint];
}

// Sets label on every vertex of positions (#V x 3) within radius of center; returns whether any changed.
export function brush(labels, positions, center, radius, label) {
  const r2 = radius * radius;
  let changed = false;
  for (let i = 0; i < labels.length; ++i) {
    const dx = positions[3 * i] - center.x;
    const dy = positions[3 * i + 1] - center.y;
    const dz = positions[3 * i + 2] - center.z;
    if (dx * dx + dy * dy + dz * dz <= r2 && labels[i] !== label) {
      labels[i] = label;
      changed = true;
    }
  }
  return changed;
}

// Sets label on every vertex of view `index` whose screen projection lies in the client rectangle.
export function box(labels, viewer, index, rect, label) {
  const positions = viewer.views[index].positions();
  const p = new THREE.Vector3();
  let changed = false;
  for (let i = 0; i < labels.length; ++i) {
    p.set(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]);
    const s = viewer.toScreen(p, index);
    if (s.z < 1 && s.x >= rect.x0 && s.x <= rect.x1 && s.y >= rect.y0 && s.y <= rect.y1 && labels[i] !== label) {
      labels[i] = label;
      changed = true;
    }
  }
  return changed;
}

export function indicesWith(labels, label) {
  const out = [];
  for (let i = 0; i < labels.length; ++i) if (labels[i] === label) out.push(i);
  return out;
}
