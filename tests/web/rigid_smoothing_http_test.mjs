// HTTP tests of issue 45's viewer items: rotation smoothing sent with a solve (and its refusal with rigid
// groups), and rigid groups set with POST /api/constraints: kept in the state and the undo revisions,
// moved rigidly by every method, bad lists refused naming the position.
// Run: IARAP_CLI=build/iarap node --test tests/web/rigid_smoothing_http_test.mjs
import assert from 'node:assert/strict';
import path from 'node:path';
import { after, before, describe, test } from 'node:test';
import { bottomAndTop as bunnyBottomAndTop, expectError } from './api_helpers.mjs';
import { decodeFrame, repoRoot, startServerAt, stopServerCleanly } from './server.mjs';

let server;
let base;

const postJson = (route, body) =>
  fetch(base + route, { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: typeof body === 'string' ? body : JSON.stringify(body) });

const state = async () => (await fetch(base + '/api/state')).json();

async function solve(body) {
  const response = await postJson('/api/solve', body);
  assert.equal(response.status, 200, await response.clone().text());
  return decodeFrame(await response.arrayBuffer());
}

// A translation by shift along x, column-major as the page sends it.
const translation = (shift) => [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, shift, 0, 0, 1];

const distance = (P, i, j) => Math.hypot(P[3 * i] - P[3 * j], P[3 * i + 1] - P[3 * j + 1], P[3 * i + 2] - P[3 * j + 2]);

// The largest change of a pairwise distance within group between the positions A and B.
function largestDistanceChange(A, B, group) {
  let worst = 0;
  for (let a = 0; a < group.length; ++a)
    for (let b = a + 1; b < group.length; ++b) worst = Math.max(worst, Math.abs(distance(A, group[a], group[b]) - distance(B, group[a], group[b])));
  return worst;
}

// The vertices in a band of heights (fractions of the height from the bottom), in the left half by x.
function band(X, height, from, to) {
  let lo = Infinity, xs = 0;
  for (let i = 0; i < X.length; i += 3) {
    lo = Math.min(lo, X[i + 1]);
    xs += X[i];
  }
  const meanX = xs / (X.length / 3);
  const out = [];
  for (let i = 0; i < X.length / 3; ++i) {
    const h = (X[3 * i + 1] - lo) / height;
    if (h >= from && h < to && X[3 * i] < meanX) out.push(i);
  }
  return out;
}

before(async () => {
  ({ server, base } = await startServerAt([path.join(repoRoot, 'data', 'bunny.off')]));
});

after(() => stopServerCleanly(server));

describe('rotation smoothing', () => {
  test('a solve with rotation_smoothing > 0 gives another shape, and reports the smoothed energy', async () => {
    const { X, fixed, handle, height } = await bunnyBottomAndTop(base);
    assert.equal((await postJson('/api/constraints', { fixed, handle })).status, 200);
    const transform = translation(0.2 * height);
    const results = {};
    for (const alpha of [0, 0.1]) {
      assert.equal((await postJson('/api/reset', {})).status, 200); // both from the rest shape
      results[alpha] = await solve({ method: 'iarap', accelerator: 'none', iterations: 40, tolerance: -1, transform, rotation_smoothing: alpha });
    }
    const plain = results[0], smooth = results[0.1];
    // The plain local and global steps are exact block minimizations of the smoothed energy too (the
    // rotations' coupled fit to a relative residual of 1e-12, docs/smoothing.md): no increase beyond
    // rounding, a relative 1e-9 as the other energy tests.
    const energies = [smooth.header.initial_energy, ...smooth.header.energies];
    for (let k = 1; k < energies.length; ++k) assert.ok(energies[k] <= energies[k - 1] * (1 + 1e-9), `${energies}`);
    // The reported energy is E_method + the smoothing term (>= 0, > 0 once neighbouring rotations differ),
    // so at the smoothed shape it exceeds what the plain solve reached minimizing E_method alone.
    assert.ok(smooth.header.energies.at(-1) > plain.header.energies.at(-1), `${smooth.header.energies.at(-1)} vs ${plain.header.energies.at(-1)}`);
    // The shapes differ well above float32 rounding (1e-7 of the height): alpha = 0.1 is a strong coupling
    // (CGAL's default is 0.02); measured 3.3e-2 of the height on the bunny, asserted > 1e-3.
    let moved = 0;
    for (let k = 0; k < X.length; ++k) moved = Math.max(moved, Math.abs(smooth.arrays.positions[k] - plain.arrays.positions[k]));
    console.log(`smoothing 0.1: E ${smooth.header.energies.at(-1).toExponential(4)} (plain ${plain.header.energies.at(-1).toExponential(4)}), shapes differ by up to ${(moved / height).toExponential(2)} x height`);
    assert.ok(moved > 1e-3 * height, `largest difference ${moved} of a height ${height}`);
    // Constrained rows keep their targets either way (float32 rounding, 1e-5 of the height).
    for (const i of handle) assert.ok(Math.abs(smooth.arrays.positions[3 * i] - (X[3 * i] + 0.2 * height)) <= 1e-5 * height);
  });

  test('bad values are 400s naming the field', async () => {
    await expectError(postJson('/api/solve', { method: 'iarap', rotation_smoothing: -1 }), 400, /rotation_smoothing/);
    await expectError(postJson('/api/solve', { method: 'iarap', rotation_smoothing: 'a' }), 400, /rotation_smoothing/);
  });
});

describe('rigid groups', () => {
  test('kept in the state and the undo revisions, moved rigidly by every method', async () => {
    const { X, fixed, handle, height } = await bunnyBottomAndTop(base);
    const free = band(X, height, 0.45, 0.55); // a group with no constrained member: it floats as one body
    const held = band(X, height, 0.85, 1.01); // handle vertices and free ones below them: it follows the handle
    assert.ok(free.length >= 10 && held.length >= 10, `${free.length} ${held.length}`);
    const answer = await (await postJson('/api/constraints', { fixed, handle, rigid_groups: [free, held] })).json();
    assert.deepEqual(answer.rigid_groups, [free, held]);
    assert.deepEqual((await state()).rigid_groups, [free, held]);
    const shift = 0.2 * height;
    for (const method of ['arap', 'spokes-rims', 'iarap']) {
      await postJson('/api/reset', {});
      const { header, arrays } = await solve({ method, iterations: 20, tolerance: -1, transform: translation(shift) });
      const P = arrays.positions;
      // The solver keeps each group rigid to rounding (1e-9 of the diagonal in double); the frame's float32
      // coordinates round at 6e-8 of their size, so a distance between two of them is good to ~2e-7 of the
      // mesh's extent: 1e-6 of the height bounds that.
      console.log(`${method}: rigid groups of ${free.length} and ${held.length} vertices, largest change of a pairwise distance ${[free, held].map((g) => (largestDistanceChange(P, X, g) / height).toExponential(2))} x height`);
      for (const group of [free, held]) assert.ok(largestDistanceChange(P, X, group) <= 1e-6 * height, `${method}: ${largestDistanceChange(P, X, group)}`);
      // The group with handle members follows the handle's translation.
      for (const i of held) assert.ok(Math.abs(P[3 * i] - X[3 * i] - shift) <= 1e-5 * height, method);
      // The free group did move: the groups are not simply pinned.
      let moved = 0;
      for (const i of free) moved = Math.max(moved, Math.abs(P[3 * i] - X[3 * i]));
      assert.ok(moved > 0.01 * shift, `${method}: the free group moved ${moved}`);
      assert.ok(Number.isFinite(header.energies.at(-1)));
    }
    // Rotation smoothing with rigid groups is the solver's refusal, in its words.
    await expectError(postJson('/api/solve', { method: 'iarap', rotation_smoothing: 0.1 }), 400, /rotation smoothing is not supported with rigid groups/);
    // A revision without groups, then undo: the groups come back with the revision.
    const withGroups = answer.revision;
    const without = await (await postJson('/api/constraints', { fixed, handle })).json();
    assert.deepEqual(without.rigid_groups, []);
    const restored = await (await postJson('/api/constraints', { revision: withGroups })).json();
    assert.deepEqual(restored.rigid_groups, [free, held]);
    await postJson('/api/constraints', { fixed, handle, rigid_groups: [] });
  });

  test('held members that do not move rigidly are the solver\'s 400, in its words', async () => {
    const { X, fixed, handle, height } = await bunnyBottomAndTop(base);
    // One group spanning fixed and handle vertices: translating the handle stretches it.
    const group = [...fixed.slice(0, 3), ...handle.slice(0, 3), ...band(X, height, 0.45, 0.55).slice(0, 3)];
    assert.equal((await postJson('/api/constraints', { fixed, handle, rigid_groups: [group] })).status, 200);
    await expectError(postJson('/api/solve', { method: 'iarap', iterations: 2, transform: translation(0.2 * height) }), 400, /not a rigid motion of their rest positions/);
    await postJson('/api/constraints', { fixed, handle, rigid_groups: [] });
  });

  test('bad lists are 400s naming the position; the state is unchanged', async () => {
    const { fixed, handle } = await bunnyBottomAndTop(base);
    await postJson('/api/constraints', { fixed, handle, rigid_groups: [[0, 1]] });
    const before = await state();
    const n = before.mesh.vertices;
    const cases = [
      [[[0, 1], [2, 'a']], /^rigid_groups\[1\]\[1\] must be an integer vertex index/],
      [[[0, 1], [2, 1.5]], /^rigid_groups\[1\]\[1\] must be an integer vertex index/],
      [[[0, 1], [2, n]], new RegExp(`^rigid_groups\\[1\\]\\[1\\] = ${n} is out of range; the mesh has ${n} vertices`)],
      [[[0, 1], [2, -1]], /^rigid_groups\[1\]\[1\] = -1 is out of range/],
      [[[0, 1], [2, 3, 1]], /^rigid_groups\[1\]\[2\] = 1 repeats rigid_groups\[0\]\[1\]/],
      [[[0, 1, 0]], /^rigid_groups\[0\]\[2\] = 0 repeats rigid_groups\[0\]\[0\]/],
      [[[0, 1], [7]], /^rigid_groups\[1\] has 1 vertices; a rigid group needs at least 2/],
      [[[0, 1], []], /^rigid_groups\[1\] has 0 vertices/],
      [[[0, 1], 5], /^rigid_groups\[1\] must be an array of vertex indices, got 5/],
      ['x', /^rigid_groups must be an array/],
      [[[0, 1], [2, 2 ** 40]], /^rigid_groups\[1\]\[1\] = 1099511627776 is too large/],
    ];
    for (const [groups, pattern] of cases) await expectError(postJson('/api/constraints', { fixed, handle, rigid_groups: groups }), 400, pattern);
    const afterwards = await state();
    assert.deepEqual(afterwards.rigid_groups, [[0, 1]]);
    assert.equal(afterwards.revision, before.revision);
    await postJson('/api/constraints', { fixed, handle, rigid_groups: [] });
  });
});
