// HTTP tests of the viewer's soft handles (POST /api/solve's handle_weights) and of fitting the mesh to a
// target (POST /api/target, POST /api/fit, its frames on GET /api/frame, POST /api/cancel) on `iarap serve`.
// Run: IARAP_CLI=build/iarap node --test tests/web/soft_fit_http_test.mjs
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { after, before, describe, test } from 'node:test';
import { bottomAndTop as bunnyBottomAndTop, expectError } from './api_helpers.mjs';
import { cliPath, decodeFrame, repoRoot, startServerAt, stopServerCleanly } from './server.mjs';

let server;
let base;

const postJson = (route, body) =>
  fetch(base + route, { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(body) });
const postFile = (route, body) =>
  fetch(base + route, { method: 'POST', headers: { 'Content-Type': 'application/octet-stream' }, body });

const positions = async (method) => new Float32Array(await (await fetch(`${base}/api/positions?method=${method}`)).arrayBuffer());

const bottomAndTop = () => bunnyBottomAndTop(base);

const translation = (x) => [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, x, 0, 0, 1]; // column-major

// The frames after `after` until a fit frame says the fit ended (fit.running false); at most 120 s.
async function fitFrames(after) {
  const frames = [];
  const deadline = Date.now() + 120000;
  while (Date.now() < deadline) {
    const response = await fetch(`${base}/api/frame?after=${after}&wait_ms=2000`);
    if (response.status === 204) continue;
    const frame = decodeFrame(await response.arrayBuffer());
    after = frame.header.sequence;
    frames.push(frame);
    if (frame.header.fit && !frame.header.fit.running) return frames;
  }
  assert.fail(`the fit did not end within 120 s (${frames.length} frames)`);
}

before(async () => {
  ({ server, base } = await startServerAt([path.join(repoRoot, 'data', 'bunny.off')]));
});

after(() => stopServerCleanly(server));

describe('soft handles', () => {
  test('a soft handle lags behind its targets, less as its weight grows', async () => {
    const { X, fixed, handle, height } = await bottomAndTop();
    await postJson('/api/constraints', { fixed, handle });
    const shift = 0.2 * height;
    // The mean distance of the handle from its targets (rest + shift in x) at the solve's minimum.
    const lag = async (weight) => {
      await postJson('/api/reset', {});
      const body = { method: 'iarap', transform: translation(shift), iterations: 200, accelerator: 'newton', tolerance: 0, gradient_tolerance: 1e-9 };
      if (weight !== null) body.handle_weights = new Array(handle.length).fill(weight);
      const response = await postJson('/api/solve', body);
      assert.equal(response.status, 200, await response.clone().text());
      const { header, arrays } = decodeFrame(await response.arrayBuffer());
      assert.ok(header.iterations > 0);
      let sum = 0;
      for (const i of handle) sum += Math.hypot(arrays.positions[3 * i] - (X[3 * i] + shift), arrays.positions[3 * i + 1] - X[3 * i + 1], arrays.positions[3 * i + 2] - X[3 * i + 2]);
      return sum / handle.length;
    };
    const hard = await lag(null);
    // float32 positions of coordinates ~height: rounding ~1e-7 height; a hard handle sits on its targets.
    assert.ok(hard <= 1e-5 * height, `hard handle lag ${hard}`);
    const weights = [0.1, 1, 10];
    const lags = [];
    for (const w of weights) lags.push(await lag(w));
    for (let k = 0; k < weights.length; ++k) {
      assert.ok(lags[k] > 10 * hard && lags[k] > 1e-4 * shift, `w = ${weights[k]}: lag ${lags[k]} (hard ${hard})`);
      assert.ok(lags[k] < shift, `w = ${weights[k]}: lag ${lags[k]} not below the shift ${shift}`);
      if (k > 0) assert.ok(lags[k] < lags[k - 1], `lag ${lags[k]} at w = ${weights[k]} not below ${lags[k - 1]} at w = ${weights[k - 1]}`);
    }
    // The fixed vertices stay hard.
    const U = await positions('iarap');
    for (const i of fixed) assert.ok(Math.abs(U[3 * i] - X[3 * i]) <= 1e-6 * height);
  });

  test('bad handle weights are 400s naming the problem; a soft handle saves as soft lines', async () => {
    const { fixed, handle } = await bottomAndTop();
    await postJson('/api/constraints', { fixed, handle });
    await expectError(postJson('/api/solve', { handle_weights: [1, 2] }), 400, new RegExp(`handle_weights has 2 weights; expected one per handle vertex \\(${handle.length}\\)`));
    await expectError(postJson('/api/solve', { handle_weights: new Array(handle.length).fill(-1) }), 400, /handle_weights\[0\] = -1.* must be finite and > 0/);
    await expectError(postJson('/api/solve', { handle_weights: ['x'] }), 400, /handle_weights\[0\] must be a number/);
    await postJson('/api/constraints', { fixed, handle: [] });
    await expectError(postJson('/api/solve', { handle_weights: [] }), 400, /no handle vertex to make soft/);
    await postJson('/api/constraints', { fixed, handle });
    const saved = await postJson('/api/scenario', { method: 'iarap', transform: translation(0.01), handle_weights: new Array(handle.length).fill(5) });
    assert.equal(saved.status, 200);
    const lines = (await saved.text()).split('\n').filter((l) => /^\d/.test(l));
    assert.equal(lines.length, fixed.length + handle.length);
    assert.equal(lines.filter((l) => l.trim().split(/\s+/).length === 5 && l.trim().endsWith(' 5')).length, handle.length);
  });
});

describe('fitting to a target', () => {
  test('bad targets are 400s naming the problem; a fit needs a target', async () => {
    assert.equal((await postJson('/api/load', { mesh: 'bunny.off' })).status, 200);
    await expectError(postJson('/api/fit', {}), 409, /no fit target loaded/);
    await expectError(postFile('/api/target?name=scan.txt', '0 0 0\n'), 400, /must end in \.xyz, \.ply, \.obj/);
    await expectError(postFile('/api/target?name=scan.xyz', ''), 400, /upload body is empty; send the target file's bytes/);
    await expectError(postFile('/api/target?name=scan.xyz', '0 0 0\n1 0 0\n0 1 nan\n0 0 1\n'), 400, /scan\.xyz:3: non-finite z coordinate 'nan'/);
    await expectError(postFile('/api/target?name=scan.xyz', '0 0 0\n1 0\n'), 400, /scan\.xyz:2: expected 'x y z' or 'x y z nx ny nz', found 2/);
    await expectError(postFile('/api/target?name=scan.xyz', '1 1 1\n1 1 1\n1 1 1\n'), 400, /scan\.xyz: all 3 target points coincide/);
    await expectError(postFile('/api/target?name=scan.xyz', '0 0 0\n'), 400, /scan\.xyz/);
    const s = await (await fetch(`${base}/api/state`)).json();
    assert.equal(s.target, null);
    await expectError(fetch(`${base}/api/target`), 409, /no fit target loaded/);
  });

  test('the bunny fits samples of its own deformed shape; every round comes as a frame', async () => {
    const { X, fixed, handle, height } = await bottomAndTop();
    // The target: the bunny bent by ARAP (handle 15% of its height sideways), sampled at its vertices and its
    // face centroids.
    await postJson('/api/constraints', { fixed, handle });
    const bent = decodeFrame(await (await postJson('/api/solve', { transform: translation(0.06 * height), iterations: 100, accelerator: 'newton' })).arrayBuffer()).arrays.positions;
    const faces = new Uint32Array(await (await fetch(`${base}/api/faces`)).arrayBuffer());
    const lines = [];
    for (let i = 0; i < bent.length; i += 3) lines.push(`${bent[i]} ${bent[i + 1]} ${bent[i + 2]}`);
    for (let f = 0; f < faces.length; f += 3) {
      const c = [0, 1, 2].map((k) => (bent[3 * faces[f] + k] + bent[3 * faces[f + 1] + k] + bent[3 * faces[f + 2] + k]) / 3);
      lines.push(c.join(' '));
    }
    await postJson('/api/reset', {});
    const scan = lines.join('\n') + '\n';
    const loaded = await postFile('/api/target?name=bent.xyz', scan);
    assert.equal(loaded.status, 200, await loaded.clone().text());
    const { target } = await loaded.json();
    assert.equal(target.name, 'bent.xyz');
    assert.equal(target.points, X.length / 3 + faces.length / 3);
    const drawn = decodeFrame(await (await fetch(`${base}/api/target`)).arrayBuffer());
    assert.equal(drawn.arrays.points.length, 3 * target.points);

    await expectError(postJson('/api/fit', { stages: 0 }), 400, /stages/);
    await expectError(postJson('/api/fit', { prealign: 'sideways' }), 400, /prealign must be 'none', 'rigid' or 'similarity'/);
    await expectError(postJson('/api/fit', { speed: 1 }), 400, /unknown field "speed"/);
    const started = await (await postJson('/api/fit', { method: 'iarap', stages: 4, rounds_per_stage: 15 })).json();
    assert.equal(started.max_rounds, 60);
    const frames = await fitFrames(started.after);
    const fit = frames.map((f) => f.header.fit).filter(Boolean);
    const last = frames.at(-1).header;
    assert.equal(last.error, undefined, last.error);
    assert.equal(last.generation, started.generation);
    assert.ok(last.fit.committed && !last.fit.cancelled);
    assert.ok(last.fit.round >= 4 && last.fit.round <= 60, `rounds ${last.fit.round}`);
    // The target holds every vertex of the bent bunny (moved by 6% of its height at the ears): most vertices
    // end on it (median 0.0004 of the target's diagonal), a tail at the ears stays off (90th percentile
    // 0.009), the mean 0.0026 after 31 rounds, from 0.0048 after the rigid pre-alignment.
    console.log(`fit: ${last.fit.round} rounds, mean distance ${last.fit.initial_mean} after the pre-alignment -> ${last.fit.final_mean}, p90 ${last.fit.final_p90}`);
    assert.ok(last.fit.final_mean < 0.004, `final mean distance ${last.fit.final_mean}`);
    assert.ok(last.fit.final_mean < 0.6 * last.fit.initial_mean, `final ${last.fit.final_mean} against ${last.fit.initial_mean} after the pre-alignment`);
    // Rounds in order, each frame with the shape of its round (a poller may skip some); the last frame
    // repeats the last round's number.
    fit.forEach((f, k) => assert.ok(k === 0 || f.round >= fit[k - 1].round + (k + 1 < fit.length ? 1 : 0)));
    assert.ok(frames.every((f) => f.arrays.positions.length === X.length));
    // The same fit as `iarap register` with the same stages and rounds on the same file: the same
    // registration (one round's solve runs the same plain iterations), up to the threads' summation order.
    const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'iarap-fit-'));
    try {
      fs.writeFileSync(path.join(dir, 'bent.xyz'), scan);
      execFileSync(cliPath, ['register', path.join(repoRoot, 'data', 'bunny.off'), path.join(dir, 'bent.xyz'), '--stages', '4', '--rounds', '15',
        '--out', path.join(dir, 'fit.obj'), '--report', path.join(dir, 'report.json'), '--quiet']);
      const report = JSON.parse(fs.readFileSync(path.join(dir, 'report.json'), 'utf8'));
      assert.ok(Math.abs(report.final_distance.mean - last.fit.final_mean) <= 1e-6 * report.final_distance.mean, `CLI ${report.final_distance.mean}, server ${last.fit.final_mean}`);
      assert.equal(report.rounds.length, last.fit.round);
    } finally {
      fs.rmSync(dir, { recursive: true, force: true });
    }
    // The fitted shape is the session's.
    assert.deepEqual(Array.from(await positions('iarap')), Array.from(frames.at(-1).arrays.positions));
  });

  test('a fit is cancelled at a round boundary; one fit at a time', async () => {
    const started = await (await postJson('/api/fit', { stages: 50, rounds_per_stage: 200 })).json();
    await expectError(postJson('/api/fit', {}), 409, /a fit is running/);
    let response = await fetch(`${base}/api/frame?after=${started.after}&wait_ms=10000`);
    for (let k = 0; k < 5 && response.status === 204; ++k) response = await fetch(`${base}/api/frame?after=${started.after}&wait_ms=10000`);
    assert.equal(response.status, 200);
    const cancel = await (await postJson('/api/cancel', {})).json();
    assert.equal(cancel.fit_cancelled, true);
    const frames = await fitFrames(started.after);
    const last = frames.at(-1).header.fit;
    assert.ok(last.cancelled, JSON.stringify(last));
    assert.ok(last.round < 50 * 200);
    assert.equal((await (await postJson('/api/cancel', {})).json()).fit_cancelled, false);
  });
});

// A bar of n unit cubes along x, each split into 6 tetrahedra around its diagonal (Kuhn), as MEDIT text
// (1-based), every tetrahedron positive (the readers refuse mixed signs).
function tetBarMedit(n) {
  const index = (i, j, k) => i + (n + 1) * (j + 2 * k);
  const vertices = [];
  for (let k = 0; k <= 1; ++k) for (let j = 0; j <= 1; ++j) for (let i = 0; i <= n; ++i) vertices.push([i, j, k]);
  const orders = [[0, 1, 2], [0, 2, 1], [1, 0, 2], [1, 2, 0], [2, 0, 1], [2, 1, 0]];
  const tets = [];
  for (let i = 0; i < n; ++i) {
    for (const order of orders) {
      const at = [i, 0, 0];
      const corners = [index(...at)];
      for (const axis of order) {
        at[axis] += 1;
        corners.push(index(...at));
      }
      const [a, b, c, d] = corners.map((v) => vertices[v]);
      const e = [b, c, d].map((p) => p.map((x, r) => x - a[r]));
      const det = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) - e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) + e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
      if (det < 0) [corners[2], corners[3]] = [corners[3], corners[2]];
      tets.push(corners);
    }
  }
  return { vertices, text: ['MeshVersionFormatted 1', 'Dimension 3', `Vertices ${vertices.length}`, ...vertices.map((v) => `${v.join(' ')} 0`),
    `Tetrahedra ${tets.length}`, ...tets.map((t) => `${t.map((c) => c + 1).join(' ')} 0`), 'End'].join('\n') + '\n' };
}

describe('tetrahedral meshes', () => {
  test('a .mesh upload is shown by its boundary and deformed by the volume energy, iarap only', async () => {
    const { vertices, text } = tetBarMedit(4);
    const response = await postFile('/api/upload?name=bar.mesh', text);
    assert.equal(response.status, 200, await response.clone().text());
    const { mesh } = await response.json();
    // 5 x 2 x 2 vertices, 24 tetrahedra; the boundary: 2 triangles per unit square, 4 x 4 + 2 squares.
    assert.deepEqual([mesh.vertices, mesh.tetrahedra, mesh.faces], [20, 24, 36]);
    assert.equal(new Uint32Array(await (await fetch(`${base}/api/faces`)).arrayBuffer()).length, 3 * 36);
    const fixed = [], handle = [];
    vertices.forEach(([x], i) => { if (x === 0) fixed.push(i); else if (x === 4) handle.push(i); });
    await postJson('/api/constraints', { fixed, handle });
    const lifted = handle.flatMap((i) => [vertices[i][0], vertices[i][1], vertices[i][2] + 1]);
    const solved = await postJson('/api/solve', { handle_targets: lifted, iterations: 50, accelerator: 'newton' });
    assert.equal(solved.status, 200, await solved.clone().text());
    const { header, arrays } = decodeFrame(await solved.arrayBuffer());
    assert.equal(arrays.positions.length, 3 * 20);
    assert.equal(header.planar, false);
    handle.forEach((v, k) => assert.ok(Math.abs(arrays.positions[3 * v + 2] - lifted[3 * k + 2]) <= 1e-6));
    // The middle of the bar rises by a fraction of the end's lift (a bent bar), the fixed end stays.
    const middle = vertices.findIndex(([x, y, z]) => x === 2 && y === 0 && z === 0);
    assert.ok(arrays.positions[3 * middle + 2] > 0.1 && arrays.positions[3 * middle + 2] < 0.9, `middle at z = ${arrays.positions[3 * middle + 2]}`);
    await expectError(postJson('/api/solve', { method: 'arap' }), 400, /method arap: bar\.mesh is a tetrahedral mesh, deformed by the volumetric ARAP energy only/);
    await expectError(postJson('/api/solve', { cell_energy: true }), 400, /cell_energy .* works on triangle meshes; bar\.mesh is a tetrahedral mesh/);
    await expectError(fetch(`${base}/api/intrinsic_edges`), 400, /intrinsic edge overlay works on triangle meshes/);
    await expectError(postFile('/api/upload?name=bad.mesh', 'MeshVersionFormatted 1\nDimension 3\nVertices 1\n0 0 0 0\nEnd\n'), 400, /bad\.mesh/);
    assert.equal((await postJson('/api/load', { mesh: 'bunny.off' })).status, 200);
  });
});
