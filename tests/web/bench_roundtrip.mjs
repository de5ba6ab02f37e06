// Benchmark (not a test): round trip of one interactive update over loopback, i.e. POST /api/solve with a
// new handle transform and 5 iterations, answered with all positions, as the viewer does while dragging.
// Meshes: data/bunny.off, and beetle.off from $IARAP_SHARED_MESHES or ../shared/meshes when present.
// Usage: IARAP_CLI=build/iarap node tests/web/bench_roundtrip.mjs [--updates N] [--method M] [--threads T]
import fs from 'node:fs';
import path from 'node:path';
import { decodeFrame, repoRoot, startServer, stopServer } from './server.mjs';

const args = process.argv.slice(2);
const option = (name, fallback) => (args.includes(name) ? args[args.indexOf(name) + 1] : fallback);
const updates = Number(option('--updates', 60));
const methods = option('--method', 'arap,spokes-rims,iarap').split(',');
const threads = option('--threads', '0'); // solver threads of the server; 0 = all cores
const sharedDir = process.env.IARAP_SHARED_MESHES ?? path.join(repoRoot, '..', 'shared', 'meshes');
const meshes = [path.join(repoRoot, 'data', 'bunny.off'), path.join(sharedDir, 'beetle.off')].filter((p) => fs.existsSync(p));

const post = (base, route, body) =>
  fetch(base + route, { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(body) });

for (const mesh of meshes) {
  const server = await startServer([mesh, '--threads', threads]);
  const base = server.url.replace(/\/$/, '');
  try {
    const X = new Float32Array(await (await fetch(base + '/api/positions?method=rest')).arrayBuffer());
    const ys = [];
    for (let i = 1; i < X.length; i += 3) ys.push(X[i]);
    const lo = Math.min(...ys), hi = Math.max(...ys);
    const fixed = [], handle = [];
    ys.forEach((y, i) => (y < lo + 0.1 * (hi - lo) ? fixed.push(i) : y > hi - 0.1 * (hi - lo) ? handle.push(i) : null));
    await post(base, '/api/constraints', { fixed, handle });
    for (const method of methods) {
      const setup = await post(base, '/api/solve', { method, iterations: 1 }); // precompute, not timed
      const { header } = decodeFrame(await setup.arrayBuffer());
      const times = [];
      let solveMs = 0;
      for (let k = 0; k < updates; ++k) {
        const shift = (0.3 * (hi - lo) * (k + 1)) / updates; // a drag upwards
        const start = performance.now();
        const response = await post(base, '/api/solve', { method, iterations: 5, tolerance: -1, transform: [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, shift, 0, 1] });
        const frame = decodeFrame(await response.arrayBuffer());
        times.push(performance.now() - start);
        solveMs += frame.header.solve_ms;
      }
      times.sort((a, b) => a - b);
      const median = times[Math.floor(times.length / 2)];
      console.log(`${path.basename(mesh)} (${X.length / 3} vertices) ${method}, ${threads} threads: setup ${header.precompute_ms.toFixed(0)} ms; ` +
        `update (5 iterations + positions) median ${median.toFixed(1)} ms, p90 ${times[Math.floor(0.9 * (times.length - 1))].toFixed(1)} ms ` +
        `=> ${(1000 / median).toFixed(1)} updates/s (server solve ${(solveMs / updates).toFixed(1)} ms mean)`);
    }
  } finally {
    await stopServer(server);
  }
}
