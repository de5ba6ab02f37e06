// HTTP tests of `iarap serve` over loopback: the API's happy path, every class of bad request (status,
// message, server still answering with its state intact), static-file confinement, a concurrent burst,
// undo revisions, scenario files replayed by the CLI, progress and cancel, and a malformed-body campaign.
// Run: IARAP_CLI=build/iarap node --test tests/web/http_test.mjs
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import http from 'node:http';
import os from 'node:os';
import path from 'node:path';
import { after, before, describe, test } from 'node:test';
import { bottomAndTop as bunnyBottomAndTop, expectError } from './api_helpers.mjs';
import { cliPath, decodeFrame, repoRoot, startServerAt, stopServerCleanly } from './server.mjs';

const bunnyPath = path.join(repoRoot, 'data', 'bunny.off');
let server;
let base;

// A request with exactly this path and these headers (fetch would normalise "..", and refuses Host), on a
// connection of its own (agent: false): no reuse of a keep-alive connection the server may be closing.
function rawRequest(method, requestPath, headers = {}, body = null) {
  return new Promise((resolve, reject) => {
    const options = { host: '127.0.0.1', port: server.port, method, path: requestPath, headers, agent: false };
    const req = http.request(options, (res) => {
      const chunks = [];
      res.on('data', (c) => chunks.push(c));
      res.on('end', () => resolve({ status: res.statusCode, headers: res.headers, body: Buffer.concat(chunks).toString('utf8') }));
    });
    req.on('error', reject);
    req.end(body);
  });
}

const postJson = (route, body) =>
  fetch(base + route, { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: typeof body === 'string' ? body : JSON.stringify(body) });

async function state() {
  const response = await fetch(base + '/api/state');
  assert.equal(response.status, 200);
  return response.json();
}

const restPositions = async () => new Float32Array(await (await fetch(base + '/api/positions?method=rest')).arrayBuffer());

const bottomAndTop = () => bunnyBottomAndTop(base);

before(async () => {
  ({ server, base } = await startServerAt([bunnyPath]));
});

after(() => stopServerCleanly(server));

describe('static files', () => {
  test('the app, its modules and three.js are served', async () => {
    const index = await fetch(base + '/');
    assert.equal(index.status, 200);
    assert.match(await index.text(), /importmap/);
    const main = await fetch(base + '/src/main.js');
    assert.equal(main.status, 200);
    assert.match(main.headers.get('content-type'), /javascript/);
    if (fs.existsSync(path.join(repoRoot, 'web/node_modules/three/build/three.module.js'))) {
      assert.equal((await fetch(base + '/node_modules/three/build/three.module.js')).status, 200);
      assert.equal((await fetch(base + '/node_modules/three/examples/jsm/controls/OrbitControls.js')).status, 200);
    }
  });

  test('no path leaves the app folder or reaches files outside the allow-list', async () => {
    for (const p of ['/../CMakeLists.txt', '/%2e%2e/CMakeLists.txt', '/src/../../README.md', '/src/%2e%2e/%2e%2e/README.md',
      '/..%2fCMakeLists.txt', '/%2e%2e%2f%2e%2e%2fetc%2fpasswd', '/package.json', '/.gitignore', '/src/.hidden.js',
      '/node_modules/playwright-core/package.json', '/node_modules/three/package.json', '//etc/passwd', '/src//main.js']) {
      const response = await rawRequest('GET', p);
      assert.equal(response.status, 404, `${p} answered ${response.status}`);
      assert.doesNotMatch(response.body, /cmake_minimum_required|root:|"dependencies"/, p);
    }
  });
});

describe('api', () => {
  test('state names the command-line mesh, never its path', async () => {
    const s = await state();
    assert.deepEqual(s.meshes, ['bunny.off']);
    assert.equal(s.mesh.vertices, 3485);
    assert.equal(s.mesh.faces, 6966);
    assert.doesNotMatch(JSON.stringify(s), /data\//);
  });

  test('solve before any constraint is a 409', async () => {
    await expectError(postJson('/api/solve', { method: 'iarap' }), 409, /no fixed or handle vertices/);
  });

  test('handle moves, fixed vertices stay, energies do not increase (all three methods)', async () => {
    const { X, fixed, handle, height } = await bottomAndTop();
    const s = await (await postJson('/api/constraints', { fixed, handle })).json();
    assert.equal(s.fixed.length, fixed.length);
    const shift = 0.2 * height;
    const transform = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, shift, 0, 0, 1]; // column-major translation
    for (const method of ['arap', 'spokes-rims', 'iarap']) {
      const response = await postJson('/api/solve', { method, iterations: 5, tolerance: -1, transform, cell_energy: true });
      assert.equal(response.status, 200, await response.clone().text());
      const { header, arrays } = decodeFrame(await response.arrayBuffer());
      assert.equal(header.method, method);
      assert.equal(header.iterations, 5);
      assert.equal(arrays.positions.length, X.length);
      assert.equal(arrays.cell_energy.length, X.length / 3);
      // Constrained rows are set to their targets exactly; float32 output rounds at ~6e-8 relative.
      const tol = 1e-5 * height;
      for (const i of fixed) for (let k = 0; k < 3; ++k) assert.ok(Math.abs(arrays.positions[3 * i + k] - X[3 * i + k]) <= tol);
      for (const i of handle) assert.ok(Math.abs(arrays.positions[3 * i] - (X[3 * i] + shift)) <= tol);
      // Local (exact over R) and global (exact over U, L_ff positive definite) steps never increase the
      // energy (Sec. 4.2); rounding allows a relative 1e-9 of its size.
      const energies = [header.initial_energy, ...header.energies];
      for (let k = 1; k < energies.length; ++k) {
        assert.ok(energies[k] <= energies[k - 1] + 1e-9 * Math.abs(energies[k - 1]), `${method} ${energies}`);
      }
      // Original ARAP keeps negative cotan weights and may go below zero on the non-Delaunay bunny.
      if (method !== 'arap') assert.ok(header.energies.at(-1) > 0, `${method} ${energies}`);
      else assert.ok(Number.isFinite(header.energies.at(-1)));
      // New targets for the same constrained set reuse the factorization: no setup time.
      assert.ok(header.precompute_ms > 0, 'the first solve of a method builds its data');
      const again = decodeFrame(await (await postJson('/api/solve', { method, iterations: 1, transform })).arrayBuffer());
      assert.equal(again.header.precompute_ms, 0);
    }
  });

  test('the accelerator is chosen per solve; a bad one is a 400 naming the choices', async () => {
    const { fixed, handle, height } = await bottomAndTop();
    await postJson('/api/constraints', { fixed, handle });
    const transform = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0.2 * height, 0, 0, 1];
    for (const accelerator of ['none', 'anderson', 'lbfgs', 'newton', 'hybrid']) {
      await postJson('/api/reset', {});
      const response = await postJson('/api/solve', { method: 'spokes-rims', iterations: 8, tolerance: -1, accelerator, transform });
      assert.equal(response.status, 200, await response.clone().text());
      const { header } = decodeFrame(await response.arrayBuffer());
      assert.equal(header.accelerator, accelerator);
      assert.equal(header.gradient_norms.length, header.iterations);
      // Every accelerator keeps the energy monotone (safeguards fall back to the plain step).
      const energies = [header.initial_energy, ...header.energies];
      for (let k = 1; k < energies.length; ++k) assert.ok(energies[k] <= energies[k - 1] + 1e-9 * Math.abs(energies[k - 1]));
    }
    const bad = await postJson('/api/solve', { method: 'iarap', accelerator: 'fast', transform });
    assert.equal(bad.status, 400);
    assert.equal((await bad.json()).error, 'accelerator must be one of newton, hybrid, lbfgs, anderson, none; got fast');
    // The solve options' one message (docs/options.md), as `iarap deform` and Python word it.
    await expectError(postJson('/api/solve', { method: 'iarap', gradient_tolerance: -1, transform }), 400,
      /^gradient_tolerance must be a finite number >= 0; got -1$/);
    await expectError(postJson('/api/solve', { window: 1001, transform }), 400, /^window must be an integer in \[0, 1000\]; got 1001$/);
    await expectError(postJson('/api/solve', { time_budget_ms: [1], transform }), 400,
      /^time_budget_ms must be a finite number >= 0; got an array of 1 elements$/);
  });

  test('extrapolate: updates of equal steps start where the drag leads; a non-boolean is a 400', async () => {
    const { fixed, handle, height } = await bottomAndTop();
    await postJson('/api/constraints', { fixed, handle });
    const step = (k) => [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0.05 * k * height, 0, 0, 1];
    const scales = [];
    for (let k = 1; k <= 4; ++k) {
      const response = await postJson('/api/solve', { iterations: 2, accelerator: 'lbfgs', extrapolate: true, transform: step(k) });
      assert.equal(response.status, 200, await response.clone().text());
      scales.push(decodeFrame(await response.arrayBuffer()).header.extrapolation);
    }
    // New constraints forget the motion: the first update has no answer before it, the second one only.
    // Then equal steps of the handle: s = 1 to the rounding of the targets' sums (far below 1e-9).
    assert.deepEqual(scales.slice(0, 2), [0, 0]);
    for (const s of scales.slice(2)) assert.ok(Math.abs(s - 1) < 1e-9, `${scales}`);
    // A solve without the field predicts nothing.
    const plain = decodeFrame(await (await postJson('/api/solve', { iterations: 1, transform: step(5) })).arrayBuffer());
    assert.equal(plain.header.extrapolation, 0);
    await expectError(postJson('/api/solve', { extrapolate: 'yes', transform: step(5) }), 400, /extrapolate/);
  });

  test('intrinsic edges come as a consistent frame', async () => {
    const response = await fetch(base + '/api/intrinsic_edges');
    assert.equal(response.status, 200);
    const { header, arrays } = decodeFrame(await response.arrayBuffer());
    assert.equal(arrays.start.length, header.edges + 1);
    assert.equal(arrays.start.at(-1), header.points);
    assert.ok(arrays.a.every((v) => v >= 0 && v < 3485));
    assert.ok(arrays.c.every((v) => v >= -1 && v < 3485));
    assert.ok(arrays.t.every((t) => t >= 0 && t <= 1));
    assert.ok(arrays.original.some((o) => o === 0), 'the bunny is 9% non-Delaunay: some edges must be flipped');
  });

  test('download writes the deformed mesh', async () => {
    const response = await fetch(base + '/api/download?method=iarap&format=obj');
    assert.equal(response.status, 200);
    assert.match(response.headers.get('content-disposition'), /bunny_iarap\.obj/);
    const text = await response.text();
    assert.equal(text.split('\n').filter((l) => l.startsWith('v ')).length, 3485);
    assert.equal(text.split('\n').filter((l) => l.startsWith('f ')).length, 6966);
    await expectError(fetch(base + '/api/download?method=iarap&format=exe'), 400, /format must be obj, off or ply/);
    await expectError(fetch(base + '/api/download?method=nope'), 400, /nope/);
  });
});

describe('bad requests leave the server running with its state intact', () => {
  test('malformed JSON, wrong types, unknown fields', async () => {
    const before = await state();
    await expectError(postJson('/api/constraints', '{"fixed": [1, 2'), 400, /malformed JSON/);
    await expectError(postJson('/api/constraints', '[1, 2]'), 400, /must be a JSON object/);
    await expectError(postJson('/api/constraints', { fixed: 'abc' }), 400, /fixed must be an array/);
    await expectError(postJson('/api/constraints', { fixed: [1, 2.5] }), 400, /fixed\[1\] must be an integer/);
    await expectError(postJson('/api/constraints', { fixed: [1], handel: [2] }), 400, /unknown field "handel"/);
    await expectError(postJson('/api/solve', { method: 'arap', iterations: 0 }), 400, /^iterations must be an integer in \[1, \d+\] on this server \(limits\.max_iterations\); got 0$/);
    await expectError(postJson('/api/solve', { method: 'laplace' }), 400, /laplace/);
    assert.deepEqual(await state(), before);
  });

  test('out-of-range indices, repeats, overlap', async () => {
    const before = await state();
    await expectError(postJson('/api/constraints', { fixed: [0, 3485] }), 400, /fixed\[1\] = 3485 is out of range; the mesh has 3485 vertices/);
    await expectError(postJson('/api/constraints', { fixed: [-1] }), 400, /fixed\[0\] = -1 is out of range/);
    await expectError(postJson('/api/constraints', { fixed: [4e12] }), 400, /too large|integer/);
    await expectError(postJson('/api/constraints', { fixed: [5, 6, 5] }), 400, /fixed\[2\] = 5 repeats fixed\[0\]/);
    await expectError(postJson('/api/constraints', { fixed: [5], handle: [7, 5] }), 400, /handle\[1\] = 5 repeats fixed\[0\]/);
    assert.deepEqual(await state(), before);
  });

  test('NaN, infinities and wrong array sizes', async () => {
    const handleCount = (await state()).handle.length;
    const identity = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1];
    const positionsBefore = new Float32Array(await (await fetch(base + '/api/positions?method=iarap')).arrayBuffer());
    await expectError(postJson('/api/solve', '{"transform": [NaN, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]}'), 400, /malformed JSON/);
    await expectError(postJson('/api/solve', `{"transform": [1e999${', 0'.repeat(15)}]}`), 400, /malformed JSON: .*overflow.*1e999/);
    await expectError(postJson('/api/solve', { transform: [null, ...identity.slice(1)] }), 400, /transform\[0\] must be a number/);
    await expectError(postJson('/api/solve', { transform: identity.slice(1) }), 400, /transform has 15 numbers; expected 16/);
    await expectError(postJson('/api/solve', { transform: [...identity.slice(0, 3), 2, ...identity.slice(4)] }), 400, /affine/);
    await expectError(postJson('/api/solve', { handle_targets: [0, 0, 0] }), 400,
      new RegExp(`handle_targets has 3 numbers; expected 3 x ${handleCount} handle vertices`));
    await expectError(postJson('/api/solve', { handle_targets: [0, 0] }), 400, /multiple of 3/);
    await expectError(postJson('/api/solve', { transform: identity, handle_targets: [] }), 400, /either transform or handle_targets/);
    await expectError(postJson('/api/solve', { tolerance: 'small' }), 400, /tolerance must be a finite number/);
    const positionsAfter = new Float32Array(await (await fetch(base + '/api/positions?method=iarap')).arrayBuffer());
    assert.deepEqual(positionsAfter, positionsBefore);
  });

  test('request bodies are capped, naming the limit of the route', async () => {
    const big = 'x'.repeat(17 << 20); // over the 16 MiB JSON limit, under the 64 MiB upload limit
    const response = await postJson('/api/constraints', big).catch((error) => error);
    // The server may answer 413 before reading the body, or close the connection on it.
    if (response instanceof Response) {
      assert.equal(response.status, 413);
      assert.match((await response.json()).error, /limit for JSON bodies is 16 MiB/);
    }
    assert.equal((await fetch(base + '/api/state')).status, 200);
  });

  test('uploads: formats, parse errors, bad meshes, server meshes only by name', async () => {
    const before = await state();
    const upload = (name, body) => fetch(`${base}/api/upload?name=${encodeURIComponent(name)}`, { method: 'POST', body });
    await expectError(upload('evil.sh', 'OFF\n'), 400, /must end in \.obj, \.off, \.ply or \.stl/);
    await expectError(upload('empty.off', ''), 400, /empty/);
    const message = await expectError(upload('bad.off', 'OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 x\n3 0 1 2\n'), 400, /bad\.off/);
    assert.doesNotMatch(message, /iarap-serve-|\/tmp/, 'the message must not show the server temporary path');
    await expectError(upload('fan.off', 'OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 1 1\n3 0 1 2\n3 0 1 3\n3 0 1 4\n'), 422, /not usable/);
    await expectError(postJson('/api/load', { mesh: '../../etc/passwd' }), 404, /no server mesh named/);
    await expectError(postJson('/api/load', { mesh: bunnyPath }), 404, /no server mesh named/);
    assert.deepEqual(await state(), before);

    const tetra = 'OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n';
    const response = await upload('tet.off', tetra);
    assert.equal(response.status, 200, await response.clone().text());
    const loaded = await response.json();
    assert.equal(loaded.mesh.name, 'tet.off');
    assert.equal(loaded.mesh.vertices, 4);
    assert.deepEqual(loaded.fixed, []);
    // check_mesh names repair_mesh; the viewer says where the repair runs instead (issue 36).
    const stray = await (await upload('stray.off', tetra.replace('4 4 0', '5 4 0').replace('0 0 1\n3', '0 0 1\n5 5 5\n3'))).json();
    assert.equal(stray.mesh.vertices, 5);
    assert.match(stray.mesh.warnings.join('\n'), /first: vertex 4; outside the viewer, `iarap deform --repair` removes them/);
    assert.doesNotMatch(stray.mesh.warnings.join('\n'), /RepairOptions/);
    const back = await (await postJson('/api/load', { mesh: 'bunny.off' })).json();
    assert.equal(back.mesh.vertices, 3485);
  });

  test('foreign Origin and Host headers are refused', async () => {
    const evilOrigin = await rawRequest('POST', '/api/reset', { Origin: 'http://evil.example', 'Content-Type': 'application/json' }, '{}');
    assert.equal(evilOrigin.status, 403);
    const rebound = await rawRequest('GET', '/api/state', { Host: `evil.example:${server.port}` });
    assert.equal(rebound.status, 403);
    const own = await rawRequest('GET', '/api/state', { Origin: `http://127.0.0.1:${server.port}` });
    assert.equal(own.status, 200);
  });

  test('wrong methods on existing routes are 405 with Allow', async () => {
    for (const [method, route, allow] of [['GET', '/api/solve', 'POST'], ['POST', '/api/state', 'GET'], ['DELETE', '/api/constraints', 'POST'],
      ['PUT', '/api/upload', 'POST'], ['GET', '/api/cancel', 'POST']]) {
      const response = await rawRequest(method, route);
      assert.equal(response.status, 405, `${method} ${route}: ${response.body}`);
      assert.equal(response.headers.allow, allow);
      assert.match(JSON.parse(response.body).error, new RegExp(`${method} is not allowed on ${route}; use ${allow}`));
    }
  });

  test('unsupported content types are 415 with what to send', async () => {
    // curl -d / --data-binary send a form's type; a mesh that size is over httplib's 8 KiB form limit.
    const bunny = fs.readFileSync(bunnyPath);
    const form = { 'Content-Type': 'application/x-www-form-urlencoded' };
    const upload = await rawRequest('POST', '/api/upload?name=bunny.off', form, bunny);
    assert.equal(upload.status, 415, upload.body);
    assert.match(JSON.parse(upload.body).error, /--data-binary @mesh\.off -H 'Content-Type: application\/octet-stream'/);
    const small = await rawRequest('POST', '/api/upload?name=tet.off', form, 'OFF\n');
    assert.equal(small.status, 415, small.body);
    const json = await rawRequest('POST', '/api/constraints', form, '{"fixed": [1]}');
    assert.equal(json.status, 415, json.body);
    assert.match(JSON.parse(json.body).error, /Content-Type: application\/json/);
    const none = await rawRequest('POST', '/api/solve', {}, '{}');
    assert.equal(none.status, 415, none.body);
    assert.match(JSON.parse(none.body).error, /got none/);
  });

  test('unknown routes are JSON 404s', async () => {
    await expectError(fetch(base + '/api/nothing'), 404, /no API route/);
    await expectError(postJson('/api/nothing', {}), 404, /not found/);
  });
});

describe('concurrency', () => {
  test('a bounded burst of concurrent solves and reads all succeed', async () => {
    const { fixed, handle, height } = await bottomAndTop();
    assert.equal((await postJson('/api/constraints', { fixed, handle })).status, 200);
    // Each request on its own connection: with pooled keep-alive connections the client may reuse one the
    // server is just closing after its idle timeout, a race of the transport, not of the server's state.
    const requests = [];
    for (let i = 0; i < 48; ++i) {
      const shift = (i / 48) * 0.1 * height;
      if (i % 3 === 0) requests.push(rawRequest('GET', '/api/state'));
      else if (i % 3 === 1) requests.push(rawRequest('GET', '/api/positions?method=arap'));
      else {
        const body = JSON.stringify({ method: ['arap', 'spokes-rims', 'iarap'][i % 3], iterations: 2, transform: [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, shift, 0, 1] });
        requests.push(rawRequest('POST', '/api/solve', { 'Content-Type': 'application/json' }, body));
      }
    }
    const responses = await Promise.all(requests);
    for (const response of responses) assert.equal(response.status, 200, response.body.slice(0, 200));
    const s = await state();
    assert.equal(s.fixed.length, fixed.length);
    assert.equal(s.handle.length, handle.length);
  });
});

describe('bodies built to exhaust the parser', () => {
  test('deep nesting is refused before parsing (100,000 levels used to overflow the stack)', async () => {
    const deep = (n) => '['.repeat(n) + ']'.repeat(n);
    await expectError(postJson('/api/constraints', `{"fixed": ${deep(100000)}}`), 400, /JSON nests deeper than 32 arrays \/ objects \(at byte 41\)/);
    await expectError(postJson('/api/solve', `{"method": ${deep(100000)}}`), 400, /nests deeper than 32/);
    await expectError(postJson('/api/load', '{"a":'.repeat(50000) + '1' + '}'.repeat(50000)), 400, /nests deeper than 32/);
    // Inside a string brackets are text, not nesting: this is an ordinary (unknown) method name.
    await expectError(postJson('/api/solve', { method: `${deep(1000)}"\\` }), 400, /method/);
    assert.equal((await fetch(base + '/api/state')).status, 200);
  });

  test('too many values, and no message quotes a whole value', async () => {
    const wide = `{"fixed": [${'0,'.repeat(5000000)}0]}`; // 10 MB, within the byte limit
    await expectError(postJson('/api/constraints', wide), 400, /JSON holds more than 4194304 values/);
    const long = await expectError(postJson('/api/solve', { method: 'x'.repeat(1000000) }), 400, /method/);
    assert.ok(long.length < 700, `message of ${long.length} characters`);
    const array = await expectError(postJson('/api/solve', { method: Array(100000).fill([1, 2]) }), 400, /method must be a string, got an array of 100000 elements/);
    assert.ok(array.length < 200);
    const key = await expectError(postJson('/api/reset', { ['k'.repeat(100000)]: 1 }), 400, /unknown field "k+"\.\.\. \(100000 characters\)/);
    assert.ok(key.length < 200);
    const unterminated = await expectError(postJson('/api/load', `{"mesh": "${'y'.repeat(1000000)}`), 400, /malformed JSON/);
    assert.ok(unterminated.length < 700);
  });
});

describe('uploads', () => {
  test('a binary STL is read (its corners welded into vertices)', async () => {
    // A tetrahedron as binary STL: 80-byte header, uint32 count, per facet a normal, 3 corners, uint16.
    const V = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]];
    const F = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
    const stl = Buffer.alloc(84 + 50 * F.length);
    stl.writeUInt32LE(F.length, 80);
    F.forEach((f, i) => f.forEach((v, k) => V[v].forEach((x, c) => stl.writeFloatLE(x, 84 + 50 * i + 12 + 12 * k + 4 * c))));
    const response = await fetch(`${base}/api/upload?name=tet.stl`, { method: 'POST', headers: { 'Content-Type': 'application/octet-stream' }, body: stl });
    assert.equal(response.status, 200, await response.clone().text());
    const loaded = await response.json();
    assert.equal(loaded.mesh.name, 'tet.stl');
    assert.equal(loaded.mesh.vertices, 4);
    assert.equal(loaded.mesh.faces, 4);
    assert.equal((await postJson('/api/load', { mesh: 'bunny.off' })).status, 200);
  });
});

describe('flat meshes', () => {
  test('a mesh in z = 0 is solved in its plane, as `iarap deform` solves it', async () => {
    // A 13 x 4 vertex strip of [0, 3] x [0, 1] in z = 0; the left column fixed, the right one the handle,
    // turned by 150 degrees about the middle: a fold whose 3D solve (cells turned over) ends elsewhere.
    const columns = 12, rows = 3;
    const V = [];
    const F = [];
    for (let j = 0; j <= rows; ++j) for (let i = 0; i <= columns; ++i) V.push([(3 * i) / columns, j / rows, 0]);
    for (let j = 0; j < rows; ++j) {
      for (let i = 0; i < columns; ++i) {
        const a = j * (columns + 1) + i;
        F.push([a, a + 1, a + columns + 2], [a, a + columns + 2, a + columns + 1]);
      }
    }
    const column = (i) => Array.from({ length: rows + 1 }, (_, j) => j * (columns + 1) + i);
    const fixed = column(0), handle = column(columns);
    const angle = (150 * Math.PI) / 180;
    const targets = handle.map((v) => {
      const x = V[v][0] - 1.5, y = V[v][1] - 0.5;
      return [1.5 + Math.cos(angle) * x - Math.sin(angle) * y, 0.5 + Math.sin(angle) * x + Math.cos(angle) * y, 0];
    });
    const off = ['OFF', `${V.length} ${F.length} 0`, ...V.map((v) => v.join(' ')), ...F.map((f) => `3 ${f.join(' ')}`)].join('\n');
    const upload = await fetch(`${base}/api/upload?name=strip.off`, { method: 'POST', headers: { 'Content-Type': 'application/octet-stream' }, body: off });
    assert.equal(upload.status, 200, await upload.clone().text());
    assert.equal((await postJson('/api/constraints', { fixed, handle })).status, 200);
    const response = await postJson('/api/solve', { method: 'iarap', iterations: 50, handle_targets: targets.flat() });
    assert.equal(response.status, 200, await response.clone().text());
    const { header, arrays } = decodeFrame(await response.arrayBuffer());
    assert.equal(header.planar, true);
    for (let v = 0; v < V.length; ++v) assert.equal(arrays.positions[3 * v + 2], 0, `vertex ${v} left the plane`);

    const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'iarap_flat_'));
    fs.writeFileSync(path.join(dir, 'strip.off'), off);
    const lines = [...fixed.map((v) => `${v} ${V[v][0]} ${V[v][1]} 0`), ...handle.map((v, k) => `${v} ${targets[k][0]} ${targets[k][1]} 0`)];
    fs.writeFileSync(path.join(dir, 'strip.txt'), lines.join('\n') + '\n');
    execFileSync(cliPath, ['deform', path.join(dir, 'strip.off'), '--constraints', path.join(dir, 'strip.txt'), '--out', path.join(dir, 'out.obj'), '--iterations', '50', '--quiet']);
    const deformed = objVertices(path.join(dir, 'out.obj'));
    fs.rmSync(dir, { recursive: true, force: true });
    // The answer's positions are float32: equal to the CLI's doubles to float rounding (2^-24 of the
    // coordinates, at most 3 here), far below 1e-6 of the diagonal (sqrt(10)).
    let gap = 0;
    deformed.forEach((p, v) => p.forEach((x, c) => { gap = Math.max(gap, Math.abs(x - arrays.positions[3 * v + c])); }));
    assert.ok(gap <= 1e-6 * Math.sqrt(10), `server vs iarap deform: ${gap}`);

    // Lifted off the plane, the same strip is a 3D solve.
    const lifted = targets.map(([x, y]) => [x, y, 0.5]);
    const lift = decodeFrame(await (await postJson('/api/solve', { iterations: 5, handle_targets: lifted.flat() })).arrayBuffer());
    assert.equal(lift.header.planar, false);
    assert.equal((await postJson('/api/load', { mesh: 'bunny.off' })).status, 200);
  });
});

describe('UV maps', () => {
  test('a disk is flattened like `iarap param`; one chart of a closed mesh and bad options are refused', async () => {
    // The closed bunny as one chart (atlases: atlas_http_test.mjs).
    await expectError(postJson('/api/param', { charts: 'one' }), 422, /not a topological disk.*0 boundary loops/);
    // A 5 x 5 vertex grid of the unit square: a flat disk, whose best map is an isometry (energy ~0).
    const n = 5;
    const V = [];
    const F = [];
    for (let j = 0; j < n; ++j) for (let i = 0; i < n; ++i) V.push([i / (n - 1), j / (n - 1), 0.1 * i * j / 16]);
    for (let j = 0; j + 1 < n; ++j) {
      for (let i = 0; i + 1 < n; ++i) {
        const a = j * n + i;
        F.push([a, a + 1, a + n + 1], [a, a + n + 1, a + n]);
      }
    }
    const off = ['OFF', `${V.length} ${F.length} 0`, ...V.map((v) => v.join(' ')), ...F.map((f) => `3 ${f.join(' ')}`)].join('\n');
    const upload = await fetch(`${base}/api/upload?name=sheet.off`, { method: 'POST', headers: { 'Content-Type': 'application/octet-stream' }, body: off });
    assert.equal(upload.status, 200, await upload.clone().text());
    for (const energy of ['triangle', 'arap', 'iarap']) {
      const response = await postJson('/api/param', { energy, boundary: 'free', iterations: 50 });
      assert.equal(response.status, 200, await response.clone().text());
      const { header, arrays } = decodeFrame(await response.arrayBuffer());
      assert.equal(arrays.uv.length, 2 * V.length);
      assert.equal(header.energy_kind, energy);
      assert.equal(header.flipped, 0);
      assert.equal(header.mesh, 'sheet.off');
      // A gently curved sheet (z up to 0.1): nearly developable, energy well under 1e-2 of its area 1.
      assert.ok(header.energy < 1e-2, `${energy}: energy ${header.energy}`);
      assert.ok(arrays.uv.every(Number.isFinite));
    }
    // A disk is one chart whatever "charts" says: auto (the default) answers what one does, the same map
    // to the bit and the same report but its times (the same library, input and options).
    const [auto, one] = await Promise.all([{}, { charts: 'one' }].map(async (charts) => {
      const response = await postJson('/api/param', { iterations: 50, ...charts });
      assert.equal(response.status, 200, await response.clone().text());
      return decodeFrame(await response.arrayBuffer());
    }));
    assert.equal(auto.header.atlas, undefined);
    assert.deepEqual(auto.arrays.uv, one.arrays.uv);
    const untimed = (header) => Object.fromEntries(Object.entries(header).filter(([key]) => !key.includes('_ms')));
    assert.deepEqual(untimed(auto.header), untimed(one.header));
    await expectError(postJson('/api/param', { energy: 'spokes-rims' }), 400, /unknown energy/);
    await expectError(postJson('/api/param', { boundary: 'circle', init: 'lscm' }), 400, /circular boundary needs/);
    await expectError(postJson('/api/param', { iterations: 100000 }), 400, /iterations/);
    await expectError(postJson('/api/param', { pins: [0] }), 400, /pins/);
    assert.equal((await postJson('/api/load', { mesh: 'bunny.off' })).status, 200);
  });
});

// The rows of an OBJ the CLI wrote (full precision).
function objVertices(file) {
  return fs.readFileSync(file, 'utf8').split('\n').filter((l) => l.startsWith('v ')).map((l) => l.split(/\s+/).slice(1, 4).map(Number));
}

describe('undo revisions, scenario files, progress', () => {
  test('an earlier constraint revision comes back with its anchors', async () => {
    const { X, fixed, handle, height } = await bottomAndTop();
    const first = await (await postJson('/api/constraints', { fixed, handle })).json();
    const shift = 0.2 * height;
    const moved = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, shift, 0, 0, 1];
    assert.equal((await postJson('/api/solve', { method: 'iarap', iterations: 2, transform: moved })).status, 200);
    // Re-anchored on the deformed shape: the identity now keeps the handle where it was moved to.
    const second = await (await postJson('/api/constraints', { fixed, handle: handle.slice(1) })).json();
    assert.ok(second.revision > first.revision);
    const restored = await (await postJson('/api/constraints', { revision: first.revision })).json();
    assert.deepEqual([restored.fixed, restored.handle], [fixed, handle]);
    // Revision `first` anchored the handle at rest, so the identity takes it back there (float32 output).
    const identity = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1];
    const { arrays } = decodeFrame(await (await postJson('/api/solve', { method: 'iarap', iterations: 1, transform: identity })).arrayBuffer());
    for (const i of handle) assert.ok(Math.abs(arrays.positions[3 * i] - X[3 * i]) <= 1e-6 * height);
    await expectError(postJson('/api/constraints', { revision: 999999 }), 409, /revision 999999 is not kept/);
    await expectError(postJson('/api/constraints', { revision: 1, fixed: [] }), 400, /unknown field "fixed"/);
  });

  test('saved scenario replays with the CLI; loading it back gives the same targets', async () => {
    const { X, fixed, handle, height } = await bottomAndTop();
    await postJson('/api/reset', {});
    await postJson('/api/constraints', { fixed, handle });
    // A rotation by 30 degrees about z, then a translation: rigid, from the rest shape.
    const c = Math.cos(Math.PI / 6), s = Math.sin(Math.PI / 6);
    const transform = [c, s, 0, 0, -s, c, 0, 0, 0, 0, 1, 0, 0.1 * height, 0.05 * height, 0, 1];
    const apply = (i) => [c * X[3 * i] - s * X[3 * i + 1] + 0.1 * height, s * X[3 * i] + c * X[3 * i + 1] + 0.05 * height, X[3 * i + 2]];
    const saved = await fetch(base + '/api/scenario', { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify({ method: 'iarap', transform }) });
    assert.equal(saved.status, 200, await saved.clone().text());
    assert.match(saved.headers.get('content-disposition'), /bunny_scenario\.json/);
    const text = await saved.text();
    const scenario = JSON.parse(text);
    assert.deepEqual(scenario.fixed.indices, fixed);
    assert.ok(Math.abs(scenario.handles[0].rotate.degrees - 30) < 1e-9, JSON.stringify(scenario.handles[0].rotate));

    const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'iarap-scenario-'));
    try {
      fs.writeFileSync(path.join(dir, 'scene.json'), text);
      execFileSync(cliPath, ['deform', bunnyPath, '--scenario', path.join(dir, 'scene.json'), '--iterations', '1', '--out', path.join(dir, 'out.obj'), '--quiet']);
      const U = objVertices(path.join(dir, 'out.obj'));
      // The CLI rebuilds R from axis and angle: the targets agree to rounding (1e-12 of the mesh size),
      // while the input positions are float32 (the server's rest positions read back), 1e-7 relative.
      for (const i of handle) apply(i).forEach((x, k) => assert.ok(Math.abs(U[i][k] - x) <= 1e-6 * height, `${i}: ${U[i]} vs ${apply(i)}`));
      for (const i of fixed) for (let k = 0; k < 3; ++k) assert.ok(Math.abs(U[i][k] - X[3 * i + k]) <= 1e-6 * height);

      // Loaded back: the same sets, the shape at rest, and the identity reaches the saved targets.
      const loaded = await (await fetch(`${base}/api/scenario/load?name=scene.json`, { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: text })).json();
      assert.deepEqual([loaded.fixed, loaded.handle], [fixed, handle]);
      const identity = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1];
      const { arrays } = decodeFrame(await (await postJson('/api/solve', { method: 'iarap', iterations: 1, transform: identity })).arrayBuffer());
      for (const i of handle) apply(i).forEach((x, k) => assert.ok(Math.abs(arrays.positions[3 * i + k] - x) <= 1e-6 * height));

      // Anchors re-taken on the deformed shape are no longer "rest moved rigidly": a constraints file,
      // which the CLI reads and which loads back with the same fixed / handle split.
      await postJson('/api/constraints', { fixed, handle });
      const constraints = await fetch(base + '/api/scenario', { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify({ method: 'iarap', transform }) });
      assert.match(constraints.headers.get('content-disposition'), /bunny_constraints\.txt/);
      const lines = await constraints.text();
      assert.equal(lines.split('\n').filter((l) => /^\d/.test(l)).length, fixed.length + handle.length);
      fs.writeFileSync(path.join(dir, 'c.txt'), lines);
      execFileSync(cliPath, ['deform', bunnyPath, '--constraints', path.join(dir, 'c.txt'), '--iterations', '1', '--out', path.join(dir, 'c.obj'), '--quiet']);
      const back = await (await fetch(`${base}/api/scenario/load?name=c.txt`, { method: 'POST', headers: { 'Content-Type': 'text/plain' }, body: lines })).json();
      assert.deepEqual([back.fixed, back.handle], [fixed, handle]);
      await expectError(fetch(`${base}/api/scenario/load?name=bad.txt`, { method: 'POST', body: '12 0\n' }), 400, /bad\.txt:1/);
      await expectError(fetch(`${base}/api/scenario/load?name=deep.json`, { method: 'POST', body: `{"fixed": ${'['.repeat(100000)}` }), 400, /nests deeper/);
    } finally {
      fs.rmSync(dir, { recursive: true, force: true });
    }
  });

  test('a long solve reports progress and stops on cancel', async () => {
    const { fixed, handle, height } = await bottomAndTop();
    await postJson('/api/constraints', { fixed, handle });
    const transform = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0.3 * height, 0, 0, 1];
    const solving = postJson('/api/solve', { method: 'arap', iterations: 1000, tolerance: -1, transform });
    let progress;
    for (let k = 0; k < 2000; ++k) { // at most 20 s (sanitizer builds) for the first iteration
      progress = await (await fetch(base + '/api/progress')).json();
      if (progress.running && progress.iteration > 0) break;
      await new Promise((resolve) => setTimeout(resolve, 10));
    }
    assert.ok(progress.running && progress.iteration > 0, JSON.stringify(progress));
    assert.equal(progress.iterations, 1000);
    assert.equal(progress.method, 'arap');
    assert.deepEqual(await (await postJson('/api/cancel', {})).json(), { cancelling: true, refinement_stopped: false, fit_cancelled: false });
    const { header } = decodeFrame(await (await solving).arrayBuffer());
    assert.equal(header.cancelled, true);
    assert.ok(header.iterations >= progress.iteration && header.iterations < 1000, `${header.iterations}`);
    assert.equal(header.energies.length, header.iterations);
    assert.equal((await (await fetch(base + '/api/progress')).json()).running, false);
    assert.deepEqual(await (await postJson('/api/cancel', {})).json(), { cancelling: false, refinement_stopped: false, fit_cancelled: false });
  });
});

describe('background refinement', () => {
  const solveFrame = async (body) => decodeFrame(await (await postJson('/api/solve', body)).arrayBuffer());
  // The next frame after `after` (null when none came within waitMs).
  const nextFrame = async (after, waitMs = 10000) => {
    const response = await fetch(`${base}/api/frame?after=${after}&wait_ms=${waitMs}`);
    if (response.status === 204) return null;
    assert.equal(response.status, 200);
    return decodeFrame(await response.arrayBuffer());
  };
  // A large edit whose plain refinement takes hundreds of iterations (seconds) on the bunny.
  const bend = async () => {
    const { fixed, handle, height } = await bottomAndTop();
    await postJson('/api/constraints', { fixed, handle });
    return [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0.3 * height, 0, 0, 1];
  };

  test('frames follow the answer until the tolerance; the last one is the session\'s iterate', async () => {
    const transform = await bend();
    const answer = await solveFrame({ method: 'spokes-rims', iterations: 1, transform, refine: true, refine_accelerator: 'newton' });
    assert.equal(answer.header.refining, true);
    let { sequence } = answer.header;
    const frames = [];
    for (let frame = await nextFrame(sequence); frame; frame = frame.header.refining ? await nextFrame(sequence) : null) {
      frames.push(frame);
      sequence = frame.header.sequence;
    }
    assert.ok(frames.length > 0);
    const last = frames.at(-1).header;
    assert.ok(frames.every((f) => f.header.generation === answer.header.generation && f.header.refined && f.header.method === 'spokes-rims'));
    // Newton never increases the energy (a step that would is replaced by the plain one), and each frame
    // continues from the one before. At the minimum the plain step's decrease is below the rounding of the
    // energy's sum over the bunny's cells (seen: +2 ulps, 5e-16 relative, in 1 of 6 runs): 1e-12 allows that
    // and nothing a real increase could hide in.
    const energies = [answer.header.energies.at(-1), ...frames.map((f) => f.header.energy)];
    energies.slice(1).forEach((e, k) => assert.ok(e <= energies[k] * (1 + 1e-12), `frame ${k}: ${e} > ${energies[k]}`));
    assert.equal(last.converged, true, JSON.stringify(last));
    assert.ok(last.relative_decrease <= last.tolerance && last.tolerance === 1e-6);
    // A frame is one whole iterate: the positions the session keeps, bit for bit.
    const kept = new Float32Array(await (await fetch(base + '/api/positions?method=spokes-rims')).arrayBuffer());
    assert.deepEqual(Array.from(frames.at(-1).arrays.positions), Array.from(kept));
    // The next solve starts there: its initial energy is the last frame's (the same U and targets, the same
    // sums; 1e-12 leaves room for a different summation order only).
    const again = await solveFrame({ method: 'spokes-rims', iterations: 1, transform });
    assert.ok(Math.abs(again.header.initial_energy - last.energy) <= 1e-12 * last.energy, `${again.header.initial_energy} vs ${last.energy}`);
    assert.equal(again.header.refining, false);
    assert.equal(await nextFrame(again.header.sequence, 300), null); // no refinement without `refine`
  });

  test('a solve during the refinement preempts it at an iteration boundary', async () => {
    const transform = await bend();
    const answer = await solveFrame({ method: 'arap', iterations: 1, transform, refine: true, refine_accelerator: 'none' });
    const frame = await nextFrame(answer.header.sequence);
    assert.ok(frame.header.refining, 'the plain refinement ended within one frame');
    const started = performance.now();
    const preempting = await solveFrame({ method: 'arap', iterations: 1, transform });
    const roundTrip = performance.now() - started;
    // It waited for at most the refinement's current iteration (about 2 ms on the bunny; the remaining
    // refinement takes hundreds of them), as the server counts it: the milliseconds are the machine's.
    console.log(`preempting solve: waited ${preempting.header.wait_ms.toFixed(1)} ms and ${preempting.header.refinement_iterations_waited} refinement iterations for the session, round trip ${roundTrip.toFixed(1)} ms`);
    assert.ok(preempting.header.refinement_iterations_waited <= 1, `${preempting.header.refinement_iterations_waited} iterations, ${preempting.header.wait_ms} ms`);
    assert.equal(preempting.header.generation, answer.header.generation + 1);
    assert.equal(preempting.header.refinement_preempted, true);
    assert.equal(answer.header.refinement_preempted, false); // bend() set new constraints: nothing to end
    // The old generation's refinement is over: no frame follows the new answer.
    assert.equal(await nextFrame(preempting.header.sequence, 300), null);
  });

  test('reads pause the refinement, which then goes on; cancel ends it with a last frame', async () => {
    const transform = await bend();
    // tolerance -1: the refinement runs to the server's iteration limit (seconds) instead of ending on a
    // stall of original ARAP's energy, which on an idle machine came within 150 ms, before the first frame.
    const answer = await solveFrame({ method: 'arap', iterations: 1, transform, refine: true, refine_accelerator: 'none', tolerance: -1 });
    const first = await nextFrame(answer.header.sequence);
    assert.ok(first.header.refining);
    await state(); // takes the session: the chunk stops at an iteration boundary
    const resumed = await nextFrame(first.header.sequence);
    assert.equal(resumed.header.generation, answer.header.generation);
    assert.ok(resumed.header.iterations > first.header.iterations);
    const cancel = await (await postJson('/api/cancel', {})).json();
    assert.equal(cancel.cancelling, false);
    let last = resumed;
    while (last.header.refining) last = await nextFrame(last.header.sequence); // a chunk published before the cancel
    assert.equal(last.header.generation, answer.header.generation);
    if (!cancel.refinement_stopped) {
      // On an idle machine the refinement can reach the server's iteration limit before the cancel arrives
      // (seen once in a clean clone, where the shared-mesh tests beside it were skipped): nothing was left
      // to stop, and its own last frame must say it ended there.
      assert.deepEqual(cancel, { cancelling: false, refinement_stopped: false, fit_cancelled: false });
      assert.ok(last.header.iterations >= 1 && !last.header.refining, 'the refinement neither ended nor was stopped');
      console.log(`# the refinement ended (${last.header.iterations} iterations) before the cancel: not exercised`);
      return;
    }
    assert.deepEqual([last.header.refining, last.header.converged], [false, false]);
    assert.equal(await nextFrame(last.header.sequence, 300), null);
  });

  test('frame parameters are checked', async () => {
    for (const query of ['after=-1', 'after=x', 'wait_ms=10001', 'wait_ms=1.5', 'after=99999999999999999999']) {
      await expectError(fetch(`${base}/api/frame?${query}`), 400, /must be a whole number/);
    }
    await expectError(postJson('/api/solve', { refine: 1 }), 400, /refine/);
    await expectError(postJson('/api/solve', { refine_accelerator: 'fast' }), 400, /refine_accelerator must be/);
  });
});

describe('malformed-body campaign', () => {
  test('1,000 deep, wide and malformed bodies on every route; the server still answers', async () => {
    // A fixed seed: the same campaign each run.
    let seed = 12345;
    const random = () => ((seed = (seed * 1103515245 + 12345) % 2147483648) / 2147483648);
    const pick = (list) => list[Math.floor(random() * list.length)];
    const valid = ['{"fixed": [1, 2, 3], "handle": [4]}', '{"method": "iarap", "iterations": 3, "transform": [1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1]}',
      '{"mesh": "bunny.off"}', '{"revision": 1}', '{}', '{"method": "arap", "handle_targets": [0, 0, 0]}'];
    const generators = [
      () => '['.repeat(1 + Math.floor(random() * 60000)),
      () => `{"fixed": ${'['.repeat(20 + Math.floor(random() * 40000))}1${']'.repeat(Math.floor(random() * 40000))}}`,
      () => `{"${pick(['fixed', 'handle', 'method', 'transform', 'mesh'])}": ${'{"a":'.repeat(Math.floor(random() * 5000))}0}`,
      () => `{"fixed": [${Array.from({ length: Math.floor(random() * 20000) }, () => Math.floor(random() * 1e10) - 5e9).join(',')}]}`,
      () => `{"transform": [${Array.from({ length: 16 }, () => pick(['1e999', '-0', 'null', 'true', '"x"', '1e-400', '0.5'])).join(',')}]}`,
      () => { const body = pick(valid); const at = Math.floor(random() * body.length); return body.slice(0, at); },
      () => { const body = [...pick(valid)]; for (let k = 0; k < 3; ++k) body[Math.floor(random() * body.length)] = String.fromCharCode(Math.floor(random() * 128)); return body.join(''); },
      () => Buffer.from(Array.from({ length: Math.floor(random() * 2000) }, () => Math.floor(random() * 256))),
      () => `"${'\\'.repeat(Math.floor(random() * 10000))}`,
      () => `{"method": "${'\u00e9\u4e2d'.repeat(Math.floor(random() * 2000))}"}`,
    ];
    const routes = ['/api/constraints', '/api/solve', '/api/load', '/api/reset', '/api/scenario', '/api/cancel',
      '/api/upload?name=f.off', '/api/upload?name=f.stl', '/api/upload?name=f.ply', '/api/scenario/load?name=s.json',
      '/api/param'];
    const allowed = new Set([200, 400, 404, 405, 409, 413, 415, 422]);
    const counts = {};
    const started = performance.now();
    for (let batch = 0; batch < 1000 / 20; ++batch) {
      const requests = Array.from({ length: 20 }, () => {
        const route = pick(routes);
        const generator = Math.floor(random() * generators.length);
        const body = generators[generator]();
        // JSON to the JSON routes (to reach the parser), raw types to the file routes, now and then a form.
        const type = random() < 0.1 ? 'application/x-www-form-urlencoded' : route.includes('load?') || route.includes('upload') ? 'application/octet-stream' : 'application/json';
        return rawRequest('POST', route, { 'Content-Type': type }, body)
          .then((response) => ({ route, response }), (error) => ({ route: `${route} (generator ${generator}, ${body.length} bytes)`, error }));
      });
      for (const { route, response, error } of await Promise.all(requests)) {
        assert.ok(!error, `${route}: ${error}`);
        assert.ok(allowed.has(response.status), `${route} answered ${response.status}: ${response.body.slice(0, 300)}`);
        assert.ok(response.body.length < 2000 || response.status === 200, `${route}: a ${response.body.length}-byte error`);
        counts[response.status] = (counts[response.status] ?? 0) + 1;
      }
    }
    console.log(`campaign: 1000 requests in ${(performance.now() - started).toFixed(0)} ms, statuses ${JSON.stringify(counts)}`);
    assert.ok(counts[400] > 500, JSON.stringify(counts));
    assert.equal(server.child.exitCode, null, 'the server exited');
    const s = await state();
    assert.equal(s.mesh.vertices, 3485);
  });
});

// Soft constraints, weighted handles and statics through the session, against `iarap deform` on the same
// mesh, file and solve options (issue 43 item 3). Both results come as OBJ files with %.17g coordinates.
describe('soft constraints and statics, as `iarap deform`', () => {
  const solveOptions = { iterations: 40, tolerance: 0, accelerator: 'lbfgs' };
  const cliOptions = ['--iterations', '40', '--tolerance', '0', '--accel', 'lbfgs', '--quiet'];
  let dir;
  before(() => { dir = fs.mkdtempSync(path.join(os.tmpdir(), 'iarap-soft-')); });
  after(() => fs.rmSync(dir, { recursive: true, force: true }));

  const loadFile = (name, text) => fetch(`${base}/api/scenario/load?name=${name}`, { method: 'POST', headers: { 'Content-Type': 'text/plain' }, body: text });

  // The session's iarap positions (full precision) after a solve with extra fields, and deform's with
  // extra flags, agree to 1e-9 of the bounding-box diagonal; returns the largest displacement.
  async function expectSameAsDeform(name, text, fields, flags) {
    const loaded = await loadFile(name, text);
    assert.equal(loaded.status, 200, await loaded.clone().text());
    const solved = await postJson('/api/solve', { method: 'iarap', ...solveOptions, ...fields });
    assert.equal(solved.status, 200, await solved.clone().text());
    // The energy of the result is the total: E_ARAP + penalty + potential (negative: the forces do work).
    const { header } = decodeFrame(await solved.arrayBuffer());
    const total = header.arap_energy + header.penalty + header.potential;
    assert.ok(Math.abs(header.energies.at(-1) - total) <= 1e-9 * Math.abs(total), JSON.stringify(header));
    assert.ok(fields.gravity ? header.potential < 0 : header.potential === 0 && header.penalty > 0, JSON.stringify(header));
    const session = path.join(dir, 'session.obj');
    fs.writeFileSync(session, Buffer.from(await (await fetch(`${base}/api/download?method=iarap&format=obj`)).arrayBuffer()));
    fs.writeFileSync(path.join(dir, name), text);
    const out = path.join(dir, 'deform.obj');
    const kind = text.trimStart().startsWith('{') ? '--scenario' : '--constraints';
    execFileSync(cliPath, ['deform', bunnyPath, kind, path.join(dir, name), ...cliOptions, ...flags, '--out', out]);
    const [A, B] = [objVertices(session), objVertices(out)];
    const diagonal = (await state()).mesh.bbox_diagonal;
    let gap = 0, moved = 0;
    A.forEach((a, i) => a.forEach((x, k) => { gap = Math.max(gap, Math.abs(x - B[i][k])); }));
    const X = await restPositions();
    A.forEach((a, i) => { moved = Math.max(moved, Math.hypot(a[0] - X[3 * i], a[1] - X[3 * i + 1], a[2] - X[3 * i + 2])); });
    assert.equal(A.length, 3485);
    assert.ok(gap <= 1e-9 * diagonal, `${name}: server and deform differ by ${gap} (diagonal ${diagonal})`);
    return moved / diagonal;
  }

  const line = (i, p) => `${i} ${p[0]} ${p[1]} ${p[2]}`;

  test('a constraints file with soft lines and points on faces solves as deform --constraints', async () => {
    const { X, fixed, handle, height } = await bottomAndTop();
    const at = (i) => [X[3 * i], X[3 * i + 1], X[3 * i + 2]];
    const faces = new Uint32Array(await (await fetch(base + '/api/faces')).arrayBuffer());
    // A face with no constrained corner, in the middle of the bunny by index.
    const taken = new Set([...fixed, ...handle]);
    const free = [];
    for (let f = 0; f < faces.length / 3 && free.length < 2; f += 97)
      if ([0, 1, 2].every((k) => !taken.has(faces[3 * f + k]))) free.push(f);
    const point = (f, b) => [0, 1, 2].map((k) => b[0] * X[3 * faces[3 * f] + k] + b[1] * X[3 * faces[3 * f + 1] + k] + b[2] * X[3 * faces[3 * f + 2] + k]);
    const text = [
      ...fixed.map((i) => line(i, at(i))),
      ...handle.map((i) => `${line(i, [at(i)[0] + 0.2 * height, at(i)[1], at(i)[2]])} 5`),
      `b ${free[0]} 0.2 0.3 0.5 ${point(free[0], [0.2, 0.3, 0.5]).map((x, k) => x + (k === 2 ? 0.05 * height : 0)).join(' ')} 2`,
      `b ${free[1]} 0.25 0.25 0.5 ${point(free[1], [0.25, 0.25, 0.5]).join(' ')}`,
    ].join('\n') + '\n';
    const moved = await expectSameAsDeform('soft.txt', text, {}, []);
    assert.ok(moved > 0.01, `the soft handle moved the mesh by ${moved} of the diagonal`);
    const s = await state();
    // The file's hard lines hold the float32 rest positions read back: fixed or handle by the exact double.
    const hard = [...s.fixed, ...s.handle].sort((a, b) => a - b);
    assert.deepEqual([hard, s.soft.vertices, s.soft.face_points, s.soft.hard_face_points], [fixed, handle, 1, 1]);
    assert.ok(s.soft.dragged.every((d) => d) && s.soft.weights.every((w) => w === 5));

    // Saved again, the session is a constraints file with the same soft lines: deform replays it.
    const saved = await postJson('/api/scenario', { method: 'iarap' });
    assert.match(saved.headers.get('content-disposition'), /bunny_constraints\.txt/);
    const again = await saved.text();
    assert.equal(again.split('\n').filter((l) => /^\d+( \S+){4}$/.test(l)).length, handle.length);
    assert.equal(again.split('\n').filter((l) => l.startsWith('b ')).length, 2);
    await expectSameAsDeform('again.txt', again, {}, []);
  });

  test('a weighted handle dragged by a transform moves its soft targets, as deform with that translation', async () => {
    const { fixed, handle, height } = await bottomAndTop();
    const scenario = (dx) => JSON.stringify({ fixed: { indices: fixed }, handles: [{ name: 'top', vertices: { indices: handle }, translate: [dx, 0, 0], weight: 10 }] });
    const deformed = path.join(dir, 'moved.json');
    fs.writeFileSync(deformed, scenario(0.15 * height));
    const loaded = await (await loadFile('rest.json', scenario(0))).json();
    assert.deepEqual([loaded.fixed, loaded.handle, loaded.soft.vertices], [fixed, [], handle]);
    const transform = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0.15 * height, 0, 0, 1];
    const solved = await postJson('/api/solve', { method: 'iarap', ...solveOptions, transform });
    assert.equal(solved.status, 200, await solved.clone().text());
    const session = path.join(dir, 'drag.obj');
    fs.writeFileSync(session, Buffer.from(await (await fetch(`${base}/api/download?method=iarap&format=obj`)).arrayBuffer()));
    execFileSync(cliPath, ['deform', bunnyPath, '--scenario', deformed, ...cliOptions, '--out', path.join(dir, 'moved.obj')]);
    const [A, B] = [objVertices(session), objVertices(path.join(dir, 'moved.obj'))];
    const diagonal = loaded.mesh.bbox_diagonal;
    let gap = 0;
    A.forEach((a, i) => a.forEach((x, k) => { gap = Math.max(gap, Math.abs(x - B[i][k])); }));
    // The drag's targets are R p + t of the loaded ones: the same doubles as the scenario's translation.
    assert.ok(gap <= 1e-9 * diagonal, `drag and deform differ by ${gap}`);
    // Explicit handle targets cannot place the soft vertices: refused, naming the field.
    await expectError(postJson('/api/solve', { method: 'iarap', handle_targets: [] }), 400, /handle_targets: this session has \d+ weighted handle/);
    // A new hard set re-anchors the dragged soft vertices where the drag left them: the identity keeps them
    // there (released a little: they were short of their targets), it does not take them back.
    const draggedAt = await (await fetch(`${base}/api/positions?method=iarap`)).arrayBuffer().then((b) => new Float32Array(b));
    assert.equal((await postJson('/api/constraints', { fixed: loaded.fixed, handle: [] })).status, 200);
    const { arrays } = decodeFrame(await (await postJson('/api/solve', { method: 'iarap', ...solveOptions })).arrayBuffer());
    const back = Math.max(...handle.map((i) => Math.hypot(...[0, 1, 2].map((k) => arrays.positions[3 * i + k] - draggedAt[3 * i + k]))));
    assert.ok(back < 0.01 * height, `re-anchored soft handle moved by ${back / height} x height`);
    // A hard set beside the soft one: a vertex cannot be both.
    await expectError(postJson('/api/constraints', { fixed, handle: [handle[1]] }), 400, /handle\[0\] = \d+ repeats a soft vertex of the loaded file \(rest\.json/);
  });

  test('gravity and per-vertex forces solve as deform --gravity --density --forces', async () => {
    const { X, fixed, height } = await bottomAndTop();
    const text = fixed.map((i) => line(i, [X[3 * i], X[3 * i + 1], X[3 * i + 2]])).join('\n') + '\n';
    const gravity = [0, -0.5 * height, 0.1 * height];
    const moved = await expectSameAsDeform('fixed.txt', text, { gravity, density: 3 }, ['--gravity', ...gravity.map(String), '--density', '3']);
    assert.ok(moved > 1e-3, `gravity moved the mesh by ${moved} of the diagonal`);
    const s = await state();
    assert.deepEqual([...s.fixed, ...s.handle].sort((a, b) => a - b), fixed);

    const forces = new Array(3 * s.mesh.vertices).fill(0);
    const pulled = [100, 2000, 3000];
    pulled.forEach((v, k) => { forces[3 * v + k] = (k + 1) * 0.01 * height; });
    const forcesFile = path.join(dir, 'forces.txt');
    fs.writeFileSync(forcesFile, pulled.map((v, k) => `${v} ${[0, 1, 2].map((c) => forces[3 * v + c]).join(' ')}`).join('\n') + '\n');
    await expectSameAsDeform('fixed.txt', text, { gravity, forces }, ['--gravity', ...gravity.map(String), '--forces', forcesFile]);
  });

  test('bad weights, gravity, density and forces are 400s naming the field; a free body is a 422', async () => {
    const { X, fixed, handle } = await bottomAndTop();
    const at = (i) => [X[3 * i], X[3 * i + 1], X[3 * i + 2]];
    await expectError(loadFile('neg.txt', `${line(fixed[0], at(fixed[0]))}\n${line(handle[0], at(handle[0]))} -2\n`), 400, /neg\.txt:2: weight -2 must be > 0/);
    await expectError(loadFile('neg.json', JSON.stringify({ fixed: { indices: fixed }, handles: [{ vertices: { indices: handle }, translate: [0, 0, 0], weight: -1 }] })), 400, /weight must be > 0/);
    await loadFile('fixed.txt', fixed.map((i) => line(i, at(i))).join('\n'));
    await expectError(postJson('/api/solve', { gravity: [NaN, 0, 0] }), 400, /gravity\[0\] must be a number/);
    await expectError(postJson('/api/solve', { gravity: [0, 1] }), 400, /gravity has 2 numbers; expected 3/);
    await expectError(postJson('/api/solve', { gravity: '0 0 1' }), 400, /gravity/);
    for (const density of [0, -1, 'heavy', null])
      await expectError(postJson('/api/solve', { gravity: [0, -1, 0], density }), 400, /density must be a finite number > 0/);
    await expectError(postJson('/api/solve', { forces: [1, 2, 3] }), 400, /forces has 3 numbers; expected 3 x 3485 vertices = 10455/);
    await expectError(postJson('/api/solve', { forces: [1, 'x'] }), 400, /forces\[1\] must be a number/);

    // Two separate triangles, one held: the other falls without end under gravity.
    const upload = await fetch(`${base}/api/upload?name=two.off`, { method: 'POST', headers: { 'Content-Type': 'application/octet-stream' }, body: 'OFF\n6 2 0\n0 0 0\n1 0 0\n0 1 0\n5 0 0\n6 0 0\n5 1 0\n3 0 1 2\n3 3 4 5\n' });
    assert.equal(upload.status, 200, await upload.clone().text());
    await postJson('/api/constraints', { fixed: [0, 1], handle: [] });
    await expectError(postJson('/api/solve', { gravity: [0, -1, 0] }), 422, /gravity \/ forces: connected component 1 \(3 vertices, e\.g\. vertex 3\) has no constrained vertex/);
    assert.equal((await postJson('/api/solve', {})).status, 200); // without forces it is pinned, as before
    assert.equal((await postJson('/api/load', { mesh: 'bunny.off' })).status, 200);
  });
});
