// Benchmark (not a test) of interactive dragging through `iarap serve`, driven like the viewer drives it:
// the bottom 10% along y fixed, the top 10% turned about z around its centroid in 30 steps to 60 degrees,
// one POST /api/solve per step (the next sent when the previous is answered, as the viewer's LatestOnly
// does), each with a time budget and `refine`, while a second connection long-polls GET /api/frame for the
// background refinement's frames. After the drag no request is sent until the refinement stops.
// Prints per mesh: updates/s over the drag, the relative gap of the last answer's energy to the converged
// energy of its targets, and the time after the last answer until a frame is within 1e-2 / 1e-6 of it.
// The converged energy is a separate solve from the refinement's end to a 1e-9 relative gradient.
//
// Meshes: beetle.off, armadillo.obj and armadillo.obj subdivided 1-to-4 (173K vertices, uploaded as an
// OBJ) from $IARAP_SHARED_MESHES or ../shared/meshes.
// Usage: node bench/drag_bench.mjs --help. Each update asks the server to extrapolate (as the page does).
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { decodeFrame, repoRoot, startServer, stopServer } from '../tests/web/server.mjs';
import { defaultBudgetMs } from '../web/src/drag_budget.js';
import { readObj, subdivideMidpoint, writeObj } from './drag_bench_mesh.mjs';

const usage = `Usage: IARAP_CLI=build/iarap node bench/drag_bench.mjs [options]
  --meshes LIST        beetle,armadillo,armadillo173k (default: all three; from $IARAP_SHARED_MESHES or
                       ../shared/meshes; the 173K mesh is armadillo.obj subdivided 1-to-4 here and uploaded)
  --method M           iarap (default), arap or spokes-rims
  --accel A            the updates' accelerator: lbfgs (default, the page's), none, anderson, newton, hybrid
  --refine-accel A     the background refinement's: newton (default, the page's), hybrid, lbfgs, ...
  --budget-ms MS       each update's time budget (default: the page's for the mesh, web/src/drag_budget.js:
                       20 ms for the beetle, 43 for the armadillo, 60 for the 173K)
  --iterations N       N iterations per update and no time budget instead (the lag without the load)
  --threads N          the server's threads (default 2)
  --steps N            drag steps to 60 degrees (default 30)
  --no-refine          no background refinement
  --no-extrapolate     updates start from the last answer (the page extrapolates; servers before issue 48's
                       drag3 branch refuse the field, so run them with this flag)
Environment: DRAG_DEBUG=1 prints each answer [iterations, stop reason, solve_ms, local_ms, global_ms,
wait_ms, extrapolation] and each refinement frame; DRAG_PROFILE=FILE writes the server's stderr.
Compare two builds in one run (the machine's load changes between runs):
  for cli in /path/to/main/build/iarap build/iarap; do IARAP_CLI=$cli node bench/drag_bench.mjs ...; done`;
const args = process.argv.slice(2);
if (args.includes('--help') || args.includes('-h')) {
  console.log(usage);
  process.exit(0);
}
const option = (name, fallback) => (args.includes(name) ? args[args.indexOf(name) + 1] : fallback);
const method = option('--method', 'iarap');
const accelerator = option('--accel', 'lbfgs'); // of the drag's updates
const refineAccelerator = option('--refine-accel', 'newton');
const givenBudgetMs = option('--budget-ms', null);
const fixedIterations = Number(option('--iterations', '0'));
const threads = option('--threads', '2');
const steps = Number(option('--steps', '30'));
const refine = !args.includes('--no-refine');
const extrapolate = !args.includes('--no-extrapolate');
const sharedDir = process.env.IARAP_SHARED_MESHES ?? path.join(repoRoot, '..', 'shared', 'meshes');
const meshSources = {
  beetle: { file: 'beetle.off' },
  armadillo: { file: 'armadillo.obj' },
  armadillo173k: { file: 'armadillo.obj', subdivide: 1 },
};
const meshNames = option('--meshes', 'beetle,armadillo,armadillo173k').split(',');

const post = async (base, route, body) => {
  const response = await fetch(base + route, { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(body) });
  if (!response.ok) throw new Error(`${route}: HTTP ${response.status} ${await response.text()}`);
  return response;
};
const solve = async (base, body) => decodeFrame(await (await post(base, '/api/solve', { method, accelerator, ...body })).arrayBuffer());

// Column-major 4 x 4: rotation by `degrees` about z around c.
function rotationAbout(c, degrees) {
  const a = (degrees * Math.PI) / 180, cos = Math.cos(a), sin = Math.sin(a);
  const tx = c[0] - (cos * c[0] - sin * c[1]), ty = c[1] - (sin * c[0] + cos * c[1]);
  return [cos, sin, 0, 0, -sin, cos, 0, 0, 0, 0, 1, 0, tx, ty, 0, 1];
}

// Frames after `after` until the refinement stops (or 60 s pass), each with its arrival time.
async function collectFrames(base, after, clock) {
  const frames = [];
  const deadline = clock() + 60000;
  for (;;) {
    const response = await fetch(`${base}/api/frame?after=${after}&wait_ms=2000`);
    if (response.status === 200) {
      const { header } = decodeFrame(await response.arrayBuffer());
      frames.push({ ...header, at: clock() });
      after = header.sequence;
      if (!header.refining) return frames;
    } else {
      await response.arrayBuffer();
    }
    if (clock() > deadline) return frames;
  }
}

async function loadMesh(base, server, name) {
  const source = meshSources[name];
  const file = path.join(sharedDir, source.file);
  if (!source.subdivide) {
    await post(base, '/api/load', { mesh: path.basename(file) });
    return;
  }
  let mesh = readObj(fs.readFileSync(file, 'utf8'), file);
  for (let k = 0; k < source.subdivide; ++k) mesh = subdivideMidpoint(mesh);
  const response = await fetch(`${base}/api/upload?name=${name}.obj`, { method: 'POST', headers: { 'Content-Type': 'application/octet-stream' }, body: writeObj(mesh) });
  if (!response.ok) throw new Error(`upload: HTTP ${response.status} ${await response.text()}`);
}

async function benchMesh(name) {
  const file = path.join(sharedDir, meshSources[name].file);
  const server = await startServer([file, '--threads', threads, '--max-upload-mb', '256']);
  const base = server.url.replace(/\/$/, '');
  try {
    await loadMesh(base, server, name);
    const X = new Float32Array(await (await fetch(base + '/api/positions?method=rest')).arrayBuffer());
    const n = X.length / 3;
    let lo = Infinity, hi = -Infinity;
    for (let i = 0; i < n; ++i) { lo = Math.min(lo, X[3 * i + 1]); hi = Math.max(hi, X[3 * i + 1]); }
    const fixed = [], handle = [];
    const centroid = [0, 0, 0];
    for (let i = 0; i < n; ++i) {
      const y = X[3 * i + 1];
      if (y < lo + 0.1 * (hi - lo)) fixed.push(i);
      else if (y > hi - 0.1 * (hi - lo)) {
        handle.push(i);
        for (let k = 0; k < 3; ++k) centroid[k] += X[3 * i + k];
      }
    }
    for (let k = 0; k < 3; ++k) centroid[k] /= handle.length;
    await post(base, '/api/constraints', { fixed, handle });
    const setup = await solve(base, { iterations: 1 }); // precomputation, not timed
    const clock = () => performance.now();
    const budgetMs = givenBudgetMs === null ? defaultBudgetMs(n) : Number(givenBudgetMs);
    const budget = { iterations: fixedIterations || 1000, tolerance: 1e-6, time_budget_ms: fixedIterations ? 0 : budgetMs, refine, refine_accelerator: refineAccelerator, ...(extrapolate ? { extrapolate } : {}) };
    const answers = [];
    const start = clock();
    let last = null;
    for (let k = 1; k <= steps; ++k) {
      last = await solve(base, { ...budget, transform: rotationAbout(centroid, (60 * k) / steps) });
      answers.push(last.header);
    }
    const dragMs = clock() - start;
    if (process.env.DRAG_DEBUG) console.log(JSON.stringify(answers.map((h) => [h.iterations, h.stop_reason, h.solve_ms.toFixed(1), h.local_ms.toFixed(1), h.global_ms.toFixed(1), h.wait_ms.toFixed(1), (h.extrapolation ?? 0).toFixed(2)])));
    const lastAt = clock();
    const frames = last.header.refining ? await collectFrames(base, last.header.sequence, clock) : [];
    if (process.env.DRAG_DEBUG) console.log(JSON.stringify(frames.map((f) => [f.iterations, f.energy.toExponential(6), f.relative_decrease.toExponential(1), f.converged, (f.at - lastAt).toFixed(0)])));
    const refineEnd = frames.length ? frames.at(-1).at - lastAt : 0;
    // The converged energy of the last targets, from where the refinement ended.
    const reference = await solve(base, { iterations: 1000, tolerance: 0, gradient_tolerance: 1e-9, transform: rotationAbout(centroid, 60) });
    const converged = reference.header.energies.at(-1) ?? reference.header.initial_energy;
    const gap = (energy) => (energy - converged) / Math.abs(converged);
    const lastEnergy = last.header.energies.at(-1);
    const reach = (tolerance) => {
      if (gap(lastEnergy) <= tolerance) return 0;
      const frame = frames.find((f) => gap(f.energy) <= tolerance);
      return frame ? frame.at - lastAt : null;
    };
    const ms = (value) => (value === null ? 'not reached' : `${(value / 1000).toFixed(2)} s`);
    const iterationsPerUpdate = answers.reduce((sum, h) => sum + h.iterations, 0) / answers.length;
    const solveMs = answers.reduce((sum, h) => sum + h.solve_ms, 0) / answers.length;
    console.log(`${name} (${n} vertices, ${fixed.length} fixed, ${handle.length} handle) ${method} ${accelerator}, ${threads} threads, ${fixedIterations ? `${fixedIterations} iterations per update` : `budget ${budgetMs} ms`}${extrapolate ? ', extrapolated' : ''}${refine ? `, refine ${refineAccelerator}` : ''}: ` +
      `setup ${setup.header.precompute_ms.toFixed(0)} ms; ${(steps / (dragMs / 1000)).toFixed(1)} updates/s ` +
      `(${(dragMs / steps).toFixed(1)} ms per update, ${solveMs.toFixed(1)} ms solving, ${iterationsPerUpdate.toFixed(1)} iterations); ` +
      `last frame gap ${gap(lastEnergy).toExponential(2)}; after the last update: 1e-2 at ${ms(reach(1e-2))}, 1e-6 at ${ms(reach(1e-6))}, ` +
      `refinement stopped at ${ms(refineEnd)} (${frames.length} frames, ${frames.at(-1)?.iterations ?? 0} iterations, final gap ${frames.length ? gap(frames.at(-1).energy).toExponential(2) : '-'}); converged E = ${converged.toExponential(6)}`);
  } finally {
    if (process.env.DRAG_PROFILE) fs.writeFileSync(process.env.DRAG_PROFILE, server.log());
    await stopServer(server);
  }
}

console.log(`drag benchmark on ${os.cpus().length} cores (${os.cpus()[0]?.model ?? 'unknown CPU'}), load ${os.loadavg()[0].toFixed(2)}`);
for (const name of meshNames) {
  if (!meshSources[name]) throw new Error(`unknown mesh ${name}; choose from ${Object.keys(meshSources).join(', ')}`);
  if (!fs.existsSync(path.join(sharedDir, meshSources[name].file))) {
    console.log(`${name}: ${meshSources[name].file} not in ${sharedDir}, skipped`);
    continue;
  }
  await benchMesh(name);
}
