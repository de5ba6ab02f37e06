// HTTP test of the UV tab's atlas: POST /api/param on the closed bunny (not a disk) answers per-corner UVs
// and chart ids whose figures are checked from the arrays, the same charts as `iarap param`, and bad atlas
// fields refused with 400s naming them. One atlas each way at texture size 512 (the bunny's takes about
// 0.7 s in Release, 10-30x that under the sanitizers).
// Run: IARAP_CLI=build/iarap node --test tests/web/atlas_http_test.mjs
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { after, before, describe, test } from 'node:test';
import { expectError } from './api_helpers.mjs';
import { cliPath, decodeFrame, repoRoot, startServerAt, stopServerCleanly } from './server.mjs';

const bunnyPath = path.join(repoRoot, 'data', 'bunny.off');
let server;
let base;

const postJson = (route, body) =>
  fetch(base + route, { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(body) });

before(async () => {
  ({ server, base } = await startServerAt([bunnyPath]));
});

after(() => stopServerCleanly(server));

// The bunny's faces and positions as the server holds them.
async function restMesh() {
  const X = new Float32Array(await (await fetch(base + '/api/positions?method=rest')).arrayBuffer());
  const F = new Uint32Array(await (await fetch(base + '/api/faces')).arrayBuffer());
  return { X, F };
}

function surfaceArea(X, F) {
  let area = 0;
  for (let f = 0; f < F.length / 3; ++f) {
    const [a, b, c] = [F[3 * f], F[3 * f + 1], F[3 * f + 2]];
    const u = [0, 1, 2].map((k) => X[3 * b + k] - X[3 * a + k]);
    const v = [0, 1, 2].map((k) => X[3 * c + k] - X[3 * a + k]);
    area += 0.5 * Math.hypot(u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]);
  }
  return area;
}

describe('UV atlas', () => {
  test('the closed bunny becomes an atlas: charts, per-corner UVs in the unit square, no flips', async () => {
    const { X, F } = await restMesh();
    const faces = F.length / 3;
    const response = await postJson('/api/param', { texture_size: 512 });
    assert.equal(response.status, 200, await response.clone().text());
    const { header, arrays } = decodeFrame(await response.arrayBuffer());
    assert.equal(header.atlas, true);
    assert.equal(header.mesh, 'bunny.off');
    assert.deepEqual([header.components, header.boundary_loops, header.genus], [1, 0, 0]);
    assert.equal(header.faces, faces);
    assert.equal(arrays.corner_uv.length, 6 * faces);
    assert.equal(arrays.chart.length, faces);
    // Chart ids 0..charts-1, each chart's face count the report's.
    const charts = header.charts;
    assert.ok(charts >= 2, `a closed surface is no disk: ${charts} charts`);
    assert.equal(header.chart_list.length, charts);
    const counts = new Array(charts).fill(0);
    for (const c of arrays.chart) counts[c] += 1; // an id outside 0..charts-1 would make NaN below
    assert.deepEqual(counts, header.chart_list.map((c) => c.faces));
    // Every uv in [0,1]^2 (float32 keeps a double in [0, 1] there), and no triangle folded over: its
    // signed UV area is > 0. The smallest is 2.9e-6 at 512 texels (measured in double); float32 rounding
    // of the corners (6e-8 in [0, 1]) moves an area by about 6e-8 x its edges (< 1e-1), under 1e-8.
    assert.ok(arrays.corner_uv.every((x) => x >= 0 && x <= 1));
    let uvArea = 0;
    let folded = 0;
    for (let f = 0; f < faces; ++f) {
      const u = (k, d) => arrays.corner_uv[6 * f + 2 * k + d];
      const a = 0.5 * ((u(1, 0) - u(0, 0)) * (u(2, 1) - u(0, 1)) - (u(1, 1) - u(0, 1)) * (u(2, 0) - u(0, 0)));
      if (!(a > 0)) folded += 1;
      uvArea += a;
    }
    assert.equal(folded, 0);
    assert.equal(header.flipped, 0);
    // The report's figures: the bounds, and the UV area they claim (float32 corners: 1e-5 relative).
    assert.ok(header.packing_efficiency >= 0.5, `packing ${header.packing_efficiency}`);
    assert.ok(Math.abs(header.packing_efficiency - uvArea) <= 1e-5 * uvArea, `${header.packing_efficiency} vs ${uvArea}`);
    assert.ok(header.overlap_ratio <= 1e-4 && header.boundary_overlaps === 0);
    assert.ok(header.distortion <= 0.1, `distortion ${header.distortion}`);
    assert.ok(Math.abs(header.distortion - header.energy / header.area) <= 1e-12 * header.distortion);
    // The charts cover the surface once (float32 positions: 1e-6 relative).
    assert.ok(Math.abs(header.area - surfaceArea(X, F)) <= 1e-6 * header.area, `${header.area}`);
    assert.equal(header.texture_size, 512);
    assert.equal(header.tolerance, 1e-4); // the atlas's default, as `iarap param`'s
    console.log(`bunny atlas: ${charts} charts, packing ${header.packing_efficiency.toFixed(3)}, distortion ${header.distortion.toPrecision(3)}, ${header.parameterize_ms.toFixed(0)} ms`);

    // The same charts and seams as `iarap param` with the same options.
    const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'iarap-atlas-'));
    try {
      const cli = JSON.parse(execFileSync(cliPath, ['param', bunnyPath, '--out', path.join(dir, 'uv.obj'), '--texture-size', '512', '--json', '--quiet'], { encoding: 'utf8' }));
      assert.equal(cli.charts, charts);
      assert.deepEqual(cli.chart_list.map((c) => c.faces), header.chart_list.map((c) => c.faces));
      assert.ok(Math.abs(cli.seam_length - header.seam_length) <= 1e-12 * cli.seam_length);
    } finally {
      fs.rmSync(dir, { recursive: true, force: true });
    }
  });

  test('charts "one" refuses the bunny; bad atlas fields are 400s naming them', async () => {
    await expectError(postJson('/api/param', { charts: 'one' }), 422, /not a topological disk.*0 boundary loops/);
    await expectError(postJson('/api/param', { charts: 'keep' }), 400, /^charts must be auto .* or one .*got "keep"/);
    await expectError(postJson('/api/param', { texture_size: 8 }), 400, /^texture_size must be an integer in 16\.\.16384/);
    await expectError(postJson('/api/param', { texture_size: 64.5 }), 400, /^texture_size/);
    await expectError(postJson('/api/param', { padding: 512 }), 400, /^padding must lie in \[0, texture_size \/ 2\) = \[0, 512\)/);
    await expectError(postJson('/api/param', { padding: -1 }), 400, /^padding/);
    await expectError(postJson('/api/param', { texture_size: 33, padding: 16.5 }), 400, /^padding must lie in \[0, texture_size \/ 2\) = \[0, 16\.5\) texels; got 16\.5/);
    await expectError(postJson('/api/param', { padding: '2' }), 400, /^padding must be a finite number/);
    await expectError(postJson('/api/param', { max_angle: 0 }), 400, /^max_angle must be in \(0, 180\] degrees; got 0/);
    await expectError(postJson('/api/param', { max_angle: 181 }), 400, /^max_angle/);
    await expectError(postJson('/api/param', { target_distortion: 0 }), 400, /^target_distortion must be a number > 0/);
    await expectError(postJson('/api/param', { min_chart_faces: 0 }), 400, /^min_chart_faces must be an integer in 1\.\./);
    await expectError(postJson('/api/param', { chart: 'auto' }), 400, /chart/);
    // The server still answers, its mesh unchanged.
    const state = await (await fetch(base + '/api/state')).json();
    assert.equal(state.mesh.name, 'bunny.off');
  });
});
