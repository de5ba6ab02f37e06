// HTTP tests of `iarap serve` over loopback: the API's happy path, every class of bad request (status,
// message, server still answering with its state intact), static-file confinement and a concurrent burst.
// Run: IARAP_CLI=build/iarap node --test tests/web/http_test.mjs
import assert from 'node:assert/strict';
import fs from 'node:fs';
import http from 'node:http';
import path from 'node:path';
import { after, before, describe, test } from 'node:test';
import { decodeFrame, repoRoot, startServer, stopServer } from './server.mjs';

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
      res.on('end', () => resolve({ status: res.statusCode, body: Buffer.concat(chunks).toString('utf8') }));
    });
    req.on('error', reject);
    req.end(body);
  });
}

const postJson = (route, body) =>
  fetch(base + route, { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: typeof body === 'string' ? body : JSON.stringify(body) });

async function expectError(responsePromise, status, pattern) {
  const response = await responsePromise;
  const text = await response.text();
  assert.equal(response.status, status, `expected ${status}, got ${response.status}: ${text}`);
  const message = JSON.parse(text).error;
  assert.match(message, pattern);
  return message;
}

async function state() {
  const response = await fetch(base + '/api/state');
  assert.equal(response.status, 200);
  return response.json();
}

const restPositions = async () => new Float32Array(await (await fetch(base + '/api/positions?method=rest')).arrayBuffer());

// Bottom tenth of the bunny fixed, top tenth the handle (by y).
async function bottomAndTop() {
  const X = await restPositions();
  const ys = [];
  for (let i = 1; i < X.length; i += 3) ys.push(X[i]);
  const lo = Math.min(...ys), hi = Math.max(...ys);
  const fixed = [], handle = [];
  ys.forEach((y, i) => {
    if (y < lo + 0.1 * (hi - lo)) fixed.push(i);
    else if (y > hi - 0.1 * (hi - lo)) handle.push(i);
  });
  return { X, fixed, handle, height: hi - lo };
}

before(async () => {
  server = await startServer([bunnyPath]);
  base = server.url.replace(/\/$/, '');
});

after(async () => {
  const code = await stopServer(server);
  assert.equal(code, 0, `server exit: ${code}\n${server.log()}`);
});

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
    await expectError(postJson('/api/solve', { method: 'arap', iterations: 0 }), 400, /iterations must be an integer in 1\.\./);
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

  test('request bodies are capped', async () => {
    const big = 'x'.repeat(17 << 20); // over the 16 MiB JSON limit
    const response = await postJson('/api/constraints', big).catch((error) => error);
    // The server may answer 413 before reading the body, or close the connection on it.
    if (response instanceof Response) {
      assert.equal(response.status, 413);
      await response.text();
    }
    assert.equal((await fetch(base + '/api/state')).status, 200);
  });

  test('uploads: formats, parse errors, bad meshes, server meshes only by name', async () => {
    const before = await state();
    const upload = (name, body) => fetch(`${base}/api/upload?name=${encodeURIComponent(name)}`, { method: 'POST', body });
    await expectError(upload('evil.sh', 'OFF\n'), 400, /must end in \.obj, \.off or \.ply/);
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
