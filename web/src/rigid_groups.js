// Rigid groups painted on the mesh (issue 45): the group of each vertex (-1: none), each stroke in the
// "Rigid group" paint mode a new group. The server gets them as lists of vertex indices
// (POST /api/constraints rigid_groups), and moves each group as one rigid body.

export const NO_GROUP = -1;

// A group needs at least 2 vertices (one vertex is rigid anyway): smaller ones are not sent.
const minGroupSize = 2;

// Distinct colours for the groups (cycled), away from the fixed red and the handle yellow.
const palette = [
  [0.27, 0.55, 0.95], [0.2, 0.78, 0.45], [0.7, 0.4, 0.95], [0.1, 0.8, 0.85],
  [0.95, 0.45, 0.75], [0.55, 0.75, 0.2], [0.45, 0.45, 0.95], [0.95, 0.55, 0.3],
];

export function groupColor(group) {
  return palette[group % palette.length];
}

// The per-vertex groups of a vertex count, none in a group.
export function emptyGroups(vertexCount) {
  return new Int32Array(vertexCount).fill(NO_GROUP);
}

// A group id no vertex uses yet (one past the largest).
export function nextGroup(groups) {
  let top = NO_GROUP;
  for (const g of groups) top = Math.max(top, g);
  return top + 1;
}

// The groups as the server takes them: lists of vertex indices in id order, the ones under minGroupSize
// left out. Also returns how many vertices were left out, to tell the user.
export function groupLists(groups) {
  const byId = new Map();
  groups.forEach((g, i) => {
    if (g === NO_GROUP) return;
    if (!byId.has(g)) byId.set(g, []);
    byId.get(g).push(i);
  });
  const lists = [];
  let leftOut = 0;
  for (const id of [...byId.keys()].sort((a, b) => a - b)) {
    const members = byId.get(id);
    if (members.length >= minGroupSize) lists.push(members);
    else leftOut += members.length;
  }
  return { lists, leftOut };
}

// Per-vertex groups from the server's lists (GET /api/state rigid_groups): list k is group k.
export function groupsFromLists(vertexCount, lists) {
  const groups = emptyGroups(vertexCount);
  (lists ?? []).forEach((members, k) => {
    for (const i of members) groups[i] = k;
  });
  return groups;
}
