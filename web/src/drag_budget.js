// The time budget the page proposes for a drag's update on a mesh of `vertices` vertices, in ms: 20 up to
// 20K vertices, then 1 per thousand vertices, at most 60 (issue 48, docs/performance.md "Dragging in the
// viewer"). An update runs at least one iteration whatever its budget, and its other costs (the initial
// guess's local step, sending #V positions) grow with the mesh: on the beetle (19.9K) 20 ms gave over 30
// updates a second; the armadillo (43K) needs about 3 iterations per update to stay within 1e-2 of its
// minimum, about 45 ms; beyond some 60K vertices one iteration takes longer than the budget, which then only
// lets a second iteration in where the update rate could not afford it.
export function defaultBudgetMs(vertices) {
  return Math.round(Math.min(60, Math.max(20, vertices / 1000)));
}
