// Browser test of the viewer: Debian's chromium, headless, driven by playwright-core, on the bunny. Box-selects
// a handle (top) and a fixed region (bottom), drags the gizmo (handle moved, fixed vertices kept), saves the
// scenario, undoes and redoes the drag, loads the scenario back and compares the page's solve with the
// CLI's replay of the file, then side by side selects and drags on the right copy and checks the shared
// colour scale, takes a screenshot (a test artefact, not blank), uploads an STL (nothing of the bunny's
// session left), flattens an uploaded disk in the UV tab (layout, report, checkerboard on the mesh), makes
// an atlas of the closed bunny (charts coloured in the layout and on the mesh) and
// makes the handle soft (it lags behind, less as its weight grows), fits the bunny to a point cloud of its
// deformed shape (progress per round, final distance), uploads a tetrahedral mesh (shown by its boundary,
// iarap only) and finally stops the server (the banner says so). Exit 77 (CTest: skipped) without
// chromium or playwright-core.
// Usage: node tests/web/browser_test.mjs [--screenshot PATH]
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { runBrowserSession, viewerPage } from './browser_page.mjs';
import { cliPath, repoRoot, stopServer } from './server.mjs';

const args = process.argv.slice(2);
const screenshotArg = args.includes('--screenshot') ? args[args.indexOf('--screenshot') + 1] : null;
const artefactDir = process.env.IARAP_WEB_ARTEFACTS ?? path.join(os.tmpdir(), 'iarap-web-artefacts');

await runBrowserSession([path.join(repoRoot, 'data', 'bunny.off')], async ({ page, server, problems, userDataDir }) => {

  const { idle, viewer, settle, boxSelect, dragGizmo } = viewerPage(page);
  const rowsOf = (X, rows) => rows.map((i) => [X[3 * i], X[3 * i + 1], X[3 * i + 2]]);
  const maxDistance = (A, B) => Math.max(...A.map((a, r) => Math.hypot(a[0] - B[r][0], a[1] - B[r][1], a[2] - B[r][2])));

  await boxSelect('handle', -0.02, 0.22); // screen y grows downwards: the top (ears)
  await boxSelect('fixed', 0.85, 1.02);
  const labels = await viewer('labels');
  const fixed = labels.flatMap((l, i) => (l === 1 ? [i] : []));
  const handle = labels.flatMap((l, i) => (l === 2 ? [i] : []));
  assert.ok(fixed.length > 10 && handle.length > 10, `selection: ${fixed.length} fixed, ${handle.length} handle`);

  // 0. Background refinement. One plain iteration per update, so that the refinement has work: after the
  // last pointer event frames keep arriving until Newton's refinement converges, and the last one shows what
  // the server keeps. Then, with a plain refinement (seconds on this edit), a drag during it is answered
  // after at most the refinement's current iteration.
  {
    await page.selectOption('#accelerator', 'none');
    await page.fill('#iterations', '1');
    await page.fill('#budget', '0');
    const g = await viewer('gizmoXArrowScreenPoint', 0);
    await page.check('input[name=tool][value=orbit]');
    await page.mouse.move(g.x, g.y);
    await page.mouse.down();
    let lastInput = 0;
    for (let k = 1; k <= 6; ++k) {
      // The page's clock just before the last move, the last input that moves the targets (the pointer-up
      // sends no solve): a lower bound of its time. Read after mouse.up() returned, or after the last move,
      // it could come after the whole refinement on a loaded machine (the page handles the event, the
      // answer and a converging Newton refinement before the call returns), and the wait below then timed
      // out (under ctest -j2: 1 run of 15 read after the pointer-up; one read before the pointer-up saw the
      // last generation's final frame 68 ms before it).
      if (k === 6) lastInput = await page.evaluate(() => performance.now());
      await page.mouse.move(g.x + 16 * k, g.y);
      await page.waitForTimeout(30);
    }
    await page.mouse.up();
    await idle();
    const generation = (await viewer('answers')).at(-1).generation;
    try {
      await page.waitForFunction(([t, gen]) => window.iarapViewer.frames().some((f) => f.receivedAt > t && f.generation === gen && !f.refining), [lastInput, generation], { timeout: 60000 });
    } catch (e) {
      const seen = (await viewer('frames')).map((f) => `${f.generation}:${f.refining ? 'r' : 'final'}:${f.iterations}:${(f.receivedAt - lastInput).toFixed(0)}`);
      const answers = (await viewer('answers')).map((a) => `${a.generation}`);
      throw new Error(`no final frame of generation ${generation} after the last input; frames ${seen.slice(-12).join(' ')}; answers ${answers.slice(-6).join(' ')}; ${e.message}`);
    }
    const frames = (await viewer('frames')).filter((f) => f.generation === generation);
    const last = frames.at(-1);
    console.log(`refinement after the drag: ${frames.length} frames, the first ${(frames[0].receivedAt - lastInput).toFixed(0)} ms and the last ${(last.receivedAt - lastInput).toFixed(0)} ms after the last pointer event, ${last.iterations} iterations, converged ${last.converged}`);
    // Under load the refinement of the last move's targets may start before the pointer-up is processed (it
    // begins 40 ms after an answer), so only the last frame is bound to come after the last input.
    assert.ok(last.receivedAt > lastInput, 'no frame of the last generation came after the last input');
    assert.equal(last.converged, true);
    assert.match(await page.textContent('#refine-info'), /converged/);
    const kept = Array.from(new Float32Array(await (await fetch(`${server.url}api/positions?method=iarap`)).arrayBuffer()));
    assert.deepEqual(await viewer('displayedPositions'), kept, 'the page does not show the refined iterate the server keeps');

    await page.selectOption('#refine-accelerator', 'none');
    await page.fill('#tolerance', '1e-12'); // the plain refinement then runs to the server's iteration limit
    await page.mouse.move(g.x + 96, g.y);
    await page.mouse.down();
    await page.mouse.move(g.x + 300, g.y); // a large edit in one update: the plain refinement is long
    await page.mouse.up();
    await idle();
    const plainAnswer = (await viewer('answers')).at(-1);
    const plainGeneration = plainAnswer.generation;
    // A frame of its refinement: a running one, or, where the page was slowed by the tests beside it, the
    // final one (the long poll answers with the newest frame, so a plain refinement of 1-3 s can end before
    // the page asks; waiting for a running frame then timed out, once in a clean clone's run under load).
    await page.waitForFunction((gen) => window.iarapViewer.frames().some((f) => f.generation === gen), plainGeneration, { timeout: 60000 });
    await page.mouse.move(g.x + 300, g.y);
    await page.mouse.down();
    await page.mouse.move(g.x + 280, g.y);
    await page.mouse.up();
    await idle();
    const preempting = (await viewer('answers')).find((a) => a.generation > plainGeneration);
    const refined = (await viewer('frames')).filter((f) => f.generation === plainGeneration);
    // About 2 ms (one plain iteration on the bunny) unless the machine is loaded; the remainder of the
    // plain refinement was hundreds of iterations (it had not converged).
    console.log(`drag during the refinement: answered after waiting ${preempting.wait_ms.toFixed(1)} ms and ${preempting.refinement_iterations_waited} refinement iterations for the session; the refinement had run ${refined.at(-1).iterations} iterations`);
    // The plain refinement stops at the server's iteration limit (1000, 1-3 s here); a browser slowed by
    // the tests beside it under ctest -j2 can reach the drag only after that. Then there is nothing to
    // preempt: said, not failed (tests/web/http_test.mjs checks the preemption itself, without a browser).
    // The page stops following the refinement once it drags again, so it may not see the refinement's last
    // frame: at the pace of the frames it saw (a lower bound: counted from the answer), the refinement
    // reached the limit before the drag's answer when its remaining iterations took less than the time
    // between its last frame seen and that answer.
    const lastSeen = refined.at(-1);
    const maxIterations = (await (await fetch(`${server.url}api/state`)).json()).limits.max_iterations;
    const pace = lastSeen.iterations / Math.max(lastSeen.receivedAt - plainAnswer.receivedAt, 1); // per ms
    const endedUnseen = lastSeen.receivedAt + (maxIterations - lastSeen.iterations) / pace <= preempting.receivedAt;
    // Whether the server ended a running refinement is the HTTP test's to check (tests/web/http_test.mjs,
    // without a browser's timing): here, under ctest -j2, the page may reach the drag after the refinement
    // ended unseen even when the pace estimate says otherwise (2 of 9 loaded runs, 229 of 1000 iterations
    // seen). What the page must show either way: the drag answered without waiting out a refinement.
    if (!preempting.refinement_preempted) {
      const why = refined.some((f) => !f.refining) || lastSeen.iterations >= 900 || endedUnseen ? 'ended' : 'ended unseen';
      console.log(`the plain refinement ${why} (${refined.at(-1).iterations} iterations seen) before the drag reached the server: preemption not exercised in this run`);
    } else {
      assert.ok(refined.every((f) => !f.converged), 'the plain refinement converged before the drag');
    }
    // The drag waits for the refinement's iteration in progress at most. Counted by the server, not timed:
    // under ctest -j2 beside the drag test, CI's drag once waited 1355 ms for that one iteration and the
    // threads' turns on two busy cores (the 1000 ms this asserted before), where waiting out the rest of
    // the refinement would have been hundreds of iterations.
    assert.ok(preempting.refinement_iterations_waited <= 1, `the drag waited for ${preempting.refinement_iterations_waited} refinement iterations (${preempting.wait_ms} ms)`);
    await page.selectOption('#refine-accelerator', 'newton');
    await page.fill('#tolerance', '1e-6');
    await page.uncheck('#refine'); // the checks below compare solves with the CLI's
    await page.selectOption('#accelerator', 'lbfgs');
    await page.fill('#iterations', '5');
    await page.click('#reset');
    await settle();
  }

  // 1. Drag the gizmo: the handle follows, the fixed vertices stay.
  const rest = await viewer('displayedPositions');
  const solvesBefore = await viewer('solves');
  await dragGizmo(0, 96);
  await page.check('#show-intrinsic');
  await page.check('#show-energy');
  await settle();
  const dragged = await viewer('displayedPositions');
  let lo = Infinity, hi = -Infinity;
  for (let i = 1; i < rest.length; i += 3) { lo = Math.min(lo, rest[i]); hi = Math.max(hi, rest[i]); }
  const height = hi - lo;
  const handleMove = maxDistance(rowsOf(dragged, handle), rowsOf(rest, handle));
  const fixedMove = maxDistance(rowsOf(dragged, fixed), rowsOf(rest, fixed));
  console.log(`solves during the drag: ${(await viewer('solves')) - solvesBefore}; largest handle move ${(handleMove / height).toFixed(3)} x height; largest fixed move ${fixedMove}`);
  assert.ok(handleMove > 0.05 * height, `handle moved only ${handleMove} (mesh height ${height})`);
  // Fixed rows are set to their targets exactly; float32 display rounds at ~6e-8 relative.
  const displayTolerance = 1e-6 * height;
  assert.ok(fixedMove <= displayTolerance, `fixed vertices moved by ${fixedMove}`);
  assert.ok(await page.isVisible('#colorbar'), 'the colour bar is not shown with the energy overlay');

  // 2. Save the scenario (a file download).
  const [download] = await Promise.all([page.waitForEvent('download'), page.click('#save-scenario')]);
  assert.match(download.suggestedFilename(), /^bunny_scenario\.json$/);
  const scenarioPath = path.join(userDataDir, download.suggestedFilename());
  await download.saveAs(scenarioPath);
  const scenario = JSON.parse(fs.readFileSync(scenarioPath, 'utf8'));
  assert.deepEqual(scenario.fixed.indices, fixed);
  assert.deepEqual(scenario.handles[0].vertices.indices, handle);

  // 3. Undo takes the handle back to rest, redo to where it was dragged (constrained rows: exact targets).
  await page.keyboard.press('Control+z');
  await settle();
  assert.ok(maxDistance(rowsOf(await viewer('displayedPositions'), handle), rowsOf(rest, handle)) <= displayTolerance, 'undo left the handle moved');
  assert.deepEqual(await viewer('handleTransform'), [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]);
  await page.keyboard.press('Control+Shift+z');
  await settle();
  assert.ok(maxDistance(rowsOf(await viewer('displayedPositions'), handle), rowsOf(dragged, handle)) <= displayTolerance, 'redo did not restore the move');

  // 4. Load the saved scenario and replay it with the CLI: the page solves 50 iterations from the rest
  // shape to the file's targets, as `iarap deform` does; both run the same iterations from the same start
  // (one arap_solve call with the page's accelerator, L-BFGS), so they agree to the float32 rounding of the
  // display.
  await page.fill('#iterations', '50');
  await page.setInputFiles('#load-scenario', scenarioPath);
  await page.waitForFunction(() => document.getElementById('status').textContent.startsWith('loaded'), null, { timeout: 30000 });
  await settle();
  const replayed = await viewer('displayedPositions');
  const outPath = path.join(userDataDir, 'replay.obj');
  execFileSync(cliPath, ['deform', path.join(repoRoot, 'data', 'bunny.off'), '--scenario', scenarioPath, '--method', 'iarap', '--iterations', '50', '--accel', 'lbfgs', '--out', outPath, '--quiet']);
  const cli = fs.readFileSync(outPath, 'utf8').split('\n').filter((l) => l.startsWith('v ')).map((l) => l.split(/\s+/).slice(1, 4).map(Number));
  const replayGap = maxDistance(cli, rowsOf(replayed, cli.map((_, i) => i)));
  console.log(`page vs CLI replay of the saved scenario (50 iterations): largest gap ${(replayGap / height).toExponential(2)} x height`);
  assert.ok(replayGap <= 1e-5 * height, `page and CLI differ by ${replayGap}`);
  // The saved targets are where the page had dragged the handle.
  assert.ok(maxDistance(rowsOf(replayed, handle), rowsOf(dragged, handle)) <= displayTolerance);
  await page.fill('#iterations', '5');

  // 4b. A weighted handle (soft, weight 10) loads and drags: the gizmo sits on its vertices and moves
  // their targets; the fixed vertices stay. Then the saved scenario comes back for the steps below.
  const weightedPath = path.join(userDataDir, 'weighted.json');
  fs.writeFileSync(weightedPath, JSON.stringify({ fixed: { indices: fixed }, handles: [{ name: 'top', vertices: { indices: handle }, translate: [0, 0, 0], weight: 10 }] }));
  await page.setInputFiles('#load-scenario', weightedPath);
  await page.waitForFunction(() => document.getElementById('status').textContent.startsWith('loaded weighted'), null, { timeout: 30000 });
  await settle();
  assert.match(await page.textContent('#selection-info'), new RegExp(`^${fixed.length} fixed, 0 handle vertices, ${handle.length} soft`));
  const softRest = await viewer('displayedPositions');
  await dragGizmo(0, 96);
  const softDragged = await viewer('displayedPositions');
  const softMove = maxDistance(rowsOf(softDragged, handle), rowsOf(softRest, handle));
  console.log(`weighted handle: largest move ${(softMove / height).toFixed(3)} x height after the drag`);
  assert.ok(softMove > 0.05 * height, `the weighted handle moved only ${softMove}`);
  assert.ok(maxDistance(rowsOf(softDragged, fixed), rowsOf(softRest, fixed)) <= displayTolerance);
  assert.equal(await viewer('errors'), 0, await page.textContent('#banner-text'));
  await page.setInputFiles('#load-scenario', scenarioPath);
  await page.waitForFunction(() => document.getElementById('status').textContent.startsWith('loaded bunny'), null, { timeout: 30000 });
  await settle();

  // 5. Side by side: all copies fit, selection and the gizmo work on the right copy, one colour scale.
  await page.uncheck('#show-intrinsic'); // three overlays cost software WebGL, and hide the energy colours
  await page.check('#side-by-side');
  await settle();
  assert.equal(await viewer('viewCount'), 3);
  const viewport = await page.locator('#viewport').boundingBox();
  for (const view of [0, 2]) {
    const b = await viewer('meshScreenBox', view);
    assert.ok(b.x0 >= viewport.x && b.x1 <= viewport.x + viewport.width, `copy ${view} is cut off: ${JSON.stringify(b)}`);
  }
  await boxSelect('fixed', 0.45, 0.55, 2);
  const sideLabels = await viewer('labels');
  const added = sideLabels.flatMap((l, i) => (l === 1 && labels[i] !== 1 ? [i] : []));
  assert.ok(added.length > 10, `box selection on the right copy fixed ${added.length} vertices`);
  const right = await viewer('displayedPositions', 'iarap');
  assert.ok(added.every((i) => right[3 * i + 1] > lo + 0.2 * height && right[3 * i + 1] < lo + 0.8 * height), 'selected outside the band');
  const arapBefore = await viewer('displayedPositions', 'arap');
  await dragGizmo(2, -60, 6);
  const arapAfter = await viewer('displayedPositions', 'arap');
  assert.ok(maxDistance(rowsOf(arapAfter, handle), rowsOf(arapBefore, handle)) > 0.02 * height, 'the right gizmo did not move the left copy');
  const shared = await page.evaluate(async () => {
    const { energyScale } = await import('/src/colormap.js');
    const v = window.iarapViewer;
    const labelsNow = v.labels();
    const energies = ['arap', 'spokes-rims', 'iarap'].map((m) => Float32Array.from(v.cellEnergy(m)));
    return { scale: v.colorScale(), union: energyScale(energies, labelsNow), own: energies.map((e) => energyScale([e], labelsNow)) };
  });
  console.log(`colour scale ${JSON.stringify(shared.scale)}; per-method ranges would be ${JSON.stringify(shared.own.map((s) => [s.lo, s.hi]))}`);
  assert.deepEqual(shared.scale, shared.union, 'the colour scale is not the one of all copies together');
  assert.ok(shared.own.some((s) => s.lo !== shared.scale.lo || s.hi !== shared.scale.hi), 'copies would have had the same range anyway');
  assert.ok(await page.isVisible('#colorbar'));
  assert.equal(await viewer('errors'), 0, await page.textContent('#banner-text'));

  fs.mkdirSync(artefactDir, { recursive: true });
  const shotPath = path.join(artefactDir, 'viewer.png');
  const png = await page.screenshot({ path: shotPath });
  if (screenshotArg) fs.copyFileSync(shotPath, path.resolve(screenshotArg));
  // Not blank: decode the screenshot in the page and count pixels of many distinct colours.
  const stats = await page.evaluate(async (dataUrl) => {
    const image = new Image();
    image.src = dataUrl;
    await image.decode();
    const canvas = Object.assign(document.createElement('canvas'), { width: image.width, height: image.height });
    const ctx = canvas.getContext('2d');
    ctx.drawImage(image, 0, 0);
    const { data } = ctx.getImageData(0, 0, image.width, image.height);
    const colours = new Set();
    let meshPixels = 0;
    for (let i = 0; i < data.length; i += 4) {
      colours.add((data[i] >> 3) * 1024 + (data[i + 1] >> 3) * 32 + (data[i + 2] >> 3));
      if (Math.abs(data[i] - 0x1c) + Math.abs(data[i + 1] - 0x1f) + Math.abs(data[i + 2] - 0x24) > 30) meshPixels += 1;
    }
    return { colours: colours.size, share: meshPixels / (data.length / 4) };
  }, `data:image/png;base64,${png.toString('base64')}`);
  console.log(`screenshot ${shotPath}: ${stats.colours} colours, ${(100 * stats.share).toFixed(1)}% non-background`);
  assert.ok(stats.colours > 50 && stats.share > 0.1, `screenshot looks blank: ${JSON.stringify(stats)}`);

  // 6. Switching meshes (an STL upload) leaves nothing of the bunny's session on the page.
  const V = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]];
  const F = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
  const stl = ['solid tet', ...F.flatMap((f) => ['facet normal 0 0 0', 'outer loop', ...f.map((v) => `vertex ${V[v].join(' ')}`), 'endloop', 'endfacet']), 'endsolid tet'].join('\n');
  await page.setInputFiles('#upload', { name: 'tet.stl', mimeType: 'model/stl', buffer: Buffer.from(stl) });
  await page.waitForFunction(() => document.getElementById('status').textContent === 'loaded tet.stl', null, { timeout: 30000 });
  const after = await page.evaluate(() => ({
    choice: document.getElementById('mesh-select').selectedOptions[0]?.textContent,
    info: document.getElementById('solve-info').textContent,
    labels: window.iarapViewer.labels(),
    undo: document.getElementById('undo').disabled,
    colorbar: document.getElementById('colorbar').hidden,
    plotInk: Array.from(document.getElementById('energy-plot').getContext('2d').getImageData(0, 0, 260, 120).data).some((v) => v !== 0),
  }));
  assert.deepEqual(after, { choice: 'tet.stl (uploaded)', info: '', labels: [0, 0, 0, 0], undo: true, colorbar: true, plotInk: false });
  // 6b. The UV tab on an uploaded disk (a spherical cap): Flatten shows the layout and the report's
  // figures, and puts the checkerboard on the mesh; unchecking takes it off.
  const rings = 6;
  const sectors = 20;
  const cap = [[0, 0, 1]];
  for (let r = 1; r <= rings; ++r) {
    for (let k = 0; k < sectors; ++k) {
      const t = (0.45 * Math.PI * r) / rings;
      const a = (2 * Math.PI * (k + 0.5 * (r % 2))) / sectors;
      cap.push([Math.sin(t) * Math.cos(a), Math.sin(t) * Math.sin(a), Math.cos(t)]);
    }
  }
  const capFaces = Array.from({ length: sectors }, (_, k) => [0, 1 + k, 1 + ((k + 1) % sectors)]);
  for (let r = 0; r + 1 < rings; ++r) {
    for (let k = 0; k < sectors; ++k) {
      const a = 1 + r * sectors + k;
      const b = 1 + r * sectors + ((k + 1) % sectors);
      capFaces.push([a, a + sectors, b + sectors], [a, b + sectors, b]);
    }
  }
  const off = ['OFF', `${cap.length} ${capFaces.length} 0`, ...cap.map((v) => v.join(' ')), ...capFaces.map((f) => `3 ${f.join(' ')}`)].join('\n');
  await page.setInputFiles('#upload', { name: 'cap.off', mimeType: 'application/octet-stream', buffer: Buffer.from(off) });
  await page.waitForFunction(() => document.getElementById('status').textContent === 'loaded cap.off', null, { timeout: 30000 });
  await page.click('#uv-flatten');
  await page.waitForFunction(() => window.iarapViewer.uvReport() !== null, null, { timeout: 30000 });
  const uv = await page.evaluate(() => ({
    report: window.iarapViewer.uvReport(),
    layoutShown: !document.getElementById('uv-layout').hidden,
    textured: window.iarapViewer.hasTexture(),
    info: document.getElementById('uv-info').textContent,
    layoutInk: Array.from(document.getElementById('uv-layout-canvas').getContext('2d').getImageData(0, 0, 320, 320).data).filter((v, i) => i % 4 === 3 && v > 0).length,
  }));
  assert.equal(uv.report.flipped, 0);
  assert.equal(uv.report.vertices, cap.length);
  assert.ok(uv.layoutShown && uv.textured, JSON.stringify(uv));
  assert.match(uv.info, /0 flipped triangles/);
  // A cap of 0.45 pi flattens to roughly a disk: well over a third of the square canvas is inked.
  assert.ok(uv.layoutInk > 0.35 * 320 * 320, `layout pixels: ${uv.layoutInk}`);
  await settle();
  await page.screenshot({ path: path.join(artefactDir, 'viewer_uv.png') });
  await page.uncheck('#uv-texture');
  assert.equal(await page.evaluate(() => window.iarapViewer.hasTexture()), false);
  console.log(`UV tab: cap flattened, energy ${uv.report.energy.toPrecision(4)}, ${uv.layoutInk} layout pixels`);

  await page.selectOption('#mesh-select', 'bunny.off');
  await page.waitForFunction(() => window.iarapViewer.labels().length === 3485, null, { timeout: 30000 });
  assert.equal(await page.evaluate(() => document.getElementById('uv-layout').hidden), true);
  assert.deepEqual(problems, []);

  // 6c. The UV tab on the closed bunny (not a disk): Flatten makes an atlas. The layout shows the unit
  // square with each chart in its own colour, the report its figures, and every copy the checkerboard
  // through the atlas, tinted by chart; unchecking takes it off.
  await page.check('#uv-texture');
  await page.fill('#uv-texture-size', '512');
  await page.click('#uv-flatten');
  await page.waitForFunction(() => window.iarapViewer.uvReport()?.atlas === true, null, { timeout: 60000 });
  const atlas = await page.evaluate(() => {
    const pixels = document.getElementById('uv-layout-canvas').getContext('2d').getImageData(0, 0, 320, 320).data;
    const colours = new Set();
    let ink = 0;
    for (let i = 0; i < pixels.length; i += 4) {
      if (pixels[i + 3] > 0) ink += 1;
      if (pixels[i + 3] === 255) colours.add((pixels[i] << 16) | (pixels[i + 1] << 8) | pixels[i + 2]);
    }
    return {
      report: window.iarapViewer.uvReport(),
      title: document.getElementById('uv-layout-title').textContent,
      info: document.getElementById('uv-info').textContent,
      atlasShown: window.iarapViewer.hasAtlas(),
      ink,
      colours: colours.size,
    };
  });
  assert.equal(atlas.report.flipped, 0);
  assert.ok(atlas.report.charts >= 2 && atlas.report.packing_efficiency >= 0.5, JSON.stringify(atlas.report));
  assert.ok(atlas.atlasShown, 'no atlas on the 3D copies');
  assert.match(atlas.title, new RegExp(`UV atlas: ${atlas.report.charts} charts`));
  assert.match(atlas.info, /atlas of \d+ charts \(closed, genus 0\)[\s\S]*0 flipped triangles[\s\S]*packing efficiency 0\.\d{3} at 512 texels/);
  // The charts fill packing_efficiency of the square (308 x 308 pixels of the 320 x 320 canvas; antialiased
  // triangle edges leave pixels partly transparent, so any ink counts), in at least as many opaque colours
  // as charts (the half-transparent edges drawn over them add more).
  assert.ok(atlas.ink > 0.9 * atlas.report.packing_efficiency * 308 * 308, `atlas pixels: ${atlas.ink}`);
  assert.ok(atlas.colours >= atlas.report.charts, `${atlas.colours} colours for ${atlas.report.charts} charts`);
  await page.evaluate(() => document.getElementById('uv-info').scrollIntoView({ block: 'end' })); // the report in the picture
  await settle();
  await page.screenshot({ path: path.join(artefactDir, 'viewer_atlas.png') });
  await page.uncheck('#uv-texture');
  assert.equal(await page.evaluate(() => window.iarapViewer.hasAtlas()), false);
  await page.click('#uv-layout-close');
  console.log(`UV tab: bunny atlas, ${atlas.report.charts} charts, packing ${atlas.report.packing_efficiency.toFixed(3)}, ${atlas.colours} layout colours`);
  assert.deepEqual(problems, []);

  // 8. A soft handle: with the gizmo held still, a weight of 0.001 lets the handle lag behind where the hard
  // handle put it (its targets), a weight of 100 much less (the bunny's neck bends easily: a weight of 0.1
  // lags by 0.2% of the height only). Solved to convergence each time, so that the
  // lags are those of the minima.
  await page.uncheck('#side-by-side'); // one copy, iarap: the method the fit below uses
  await settle();
  await boxSelect('handle', -0.02, 0.22);
  await boxSelect('fixed', 0.85, 1.02);
  const bunnyLabels = await viewer('labels');
  const softHandleRows = bunnyLabels.flatMap((l, i) => (l === 2 ? [i] : []));
  await dragGizmo(0, 96);
  const converge = async () => {
    await page.click('#converge');
    await settle();
  };
  await converge();
  const onTargets = rowsOf(await viewer('displayedPositions'), softHandleRows);
  const setWeight = async (exponent) => {
    await page.evaluate((value) => {
      const slider = document.getElementById('handle-weight');
      slider.value = String(value);
      slider.dispatchEvent(new Event('input'));
    }, exponent);
    await settle();
    await converge();
    const rows = rowsOf(await viewer('displayedPositions'), softHandleRows);
    return rows.reduce((sum, r, k) => sum + Math.hypot(r[0] - onTargets[k][0], r[1] - onTargets[k][1], r[2] - onTargets[k][2]), 0) / rows.length;
  };
  await page.check('#soft-handle');
  const lagLight = await setWeight(-3);
  assert.match(await page.textContent('#selection-info'), /handle vertices \(soft, w = 0\.0010\)/);
  const lagHeavy = await setWeight(2);
  console.log(`soft handle: mean lag behind the hard handle's positions ${(lagLight / height).toExponential(2)} x height at w = 0.001, ${(lagHeavy / height).toExponential(2)} at w = 100`);
  assert.ok(lagLight > 0.01 * height, `a soft handle of weight 0.001 lags only ${lagLight}`);
  assert.ok(lagHeavy < 0.5 * lagLight && lagHeavy > 0, `weight 100 lags ${lagHeavy}, weight 0.001 ${lagLight}`);
  const lastSolve = (await viewer('answers')).at(-1);
  assert.equal(lastSolve.converged, true);
  await page.uncheck('#soft-handle');
  await settle();

  // 8b. Rigid group and rotation smoothing (issue 45): a box stroke in the Rigid group mode paints one
  // group across the middle, which the server then keeps rigid through a drag (pairwise distances to
  // float32 rounding, 1e-6 of the height); once the groups are cleared, the smoothing slider changes the
  // converged shape (its refusal with groups: rigid_smoothing_http_test.mjs).
  {
    await page.click('#reset');
    await settle();
    await boxSelect('rigid', 0.45, 0.55);
    const groups = await viewer('rigidGroups');
    const members = groups.flatMap((g, i) => (g === 0 ? [i] : []));
    assert.ok(members.length > 10 && groups.every((g) => g <= 0), `rigid group of ${members.length} vertices`);
    assert.match(await page.textContent('#selection-info'), /, 1 rigid group$/);
    const state = await (await fetch(server.url + 'api/state')).json();
    assert.deepEqual(state.rigid_groups, [members]);
    await dragGizmo(0, 60);
    await converge();
    const rest = rowsOf(await (async () => Array.from(new Float32Array(await (await fetch(server.url + 'api/positions?method=rest')).arrayBuffer())))(), members);
    const moved = rowsOf(await viewer('displayedPositions'), members);
    let worst = 0;
    for (let a = 0; a < members.length; ++a)
      for (let b = a + 1; b < members.length; ++b)
        worst = Math.max(worst, Math.abs(Math.hypot(...moved[a].map((x, k) => x - moved[b][k])) - Math.hypot(...rest[a].map((x, k) => x - rest[b][k]))));
    console.log(`rigid group of ${members.length} vertices: largest change of a pairwise distance ${(worst / height).toExponential(2)} x height`);
    assert.ok(worst <= 1e-6 * height, `the group bent by ${worst}`);
    await page.click('#clear-rigid');
    await settle();
    assert.deepEqual((await (await fetch(server.url + 'api/state')).json()).rigid_groups, []);
    await converge();
    const unsmoothed = await viewer('displayedPositions');
    const setSmoothing = async (value) => {
      await page.evaluate((v) => {
        const slider = document.getElementById('smoothing');
        slider.value = v === null ? slider.min : String(v);
        slider.dispatchEvent(new Event('input'));
      }, value);
      await settle();
      await converge();
    };
    await setSmoothing(-1);
    assert.equal(await page.textContent('#smoothing-value'), 'alpha = 0.10');
    const smoothed = await viewer('displayedPositions');
    const change = Math.max(...smoothed.map((x, k) => Math.abs(x - unsmoothed[k])));
    console.log(`rotation smoothing 0.1 in the page: the converged shape moves by up to ${(change / height).toExponential(2)} x height`);
    // The HTTP test measures 3.3e-2 of the height for a larger drag; well above float32 rounding.
    assert.ok(change > 1e-3 * height, `smoothing changed the shape by ${change}`);
    await setSmoothing(null);
    assert.equal(await page.textContent('#smoothing-value'), 'off');
  }

  // 9. Fit to a scan: the page's bunny deformed by a short drag (a few % of its height), its vertices as a
  // point cloud, is the target; after a reset the Fit button registers the rest bunny to it, redrawing it
  // every round, and says the final distance.
  await page.click('#reset');
  await settle();
  await dragGizmo(0, 20);
  await converge();
  const scanRows = await viewer('displayedPositions');
  const scan = [];
  for (let i = 0; i < scanRows.length; i += 3) scan.push(`${scanRows[i]} ${scanRows[i + 1]} ${scanRows[i + 2]}`);
  await page.click('#reset');
  await settle();
  await page.setInputFiles('#load-target', { name: 'scan.xyz', mimeType: 'text/plain', buffer: Buffer.from(scan.join('\n') + '\n') });
  await page.waitForFunction(() => !document.getElementById('fit').disabled, null, { timeout: 30000 });
  assert.match(await page.textContent('#fit-info'), /target scan\.xyz: 3485 points/);
  await page.fill('#fit-stages', '4');
  await page.fill('#fit-rounds', '15');
  await page.click('#fit');
  await page.waitForFunction(() => /^fit (done|stopped|failed)/.test(document.getElementById('fit-info').textContent), null, { timeout: 120000 });
  const fitInfo = await page.textContent('#fit-info');
  const fitFrames = await viewer('fitFrames');
  const residuals = await viewer('fitResiduals');
  const lastFit = fitFrames.at(-1).fit;
  console.log(`fit in the page: ${fitFrames.length} frames seen, ${lastFit.round} rounds, mean distance ${lastFit.initial_mean.toExponential(2)} after the pre-alignment -> final ${lastFit.final_mean.toExponential(2)} of the target's diagonal; "${fitInfo}"`);
  assert.match(fitInfo, /^fit done after \d+ rounds: mean distance/);
  // The page draws each frame it gets; under load it gets fewer than the rounds (the server keeps the
  // newest frame only): 4 to 14 of 40 seen.
  assert.ok(residuals.length >= 1 && fitFrames.every((f, k) => k === 0 || f.fit.round >= fitFrames[k - 1].fit.round), `rounds seen: ${fitFrames.map((f) => f.fit.round)}`);
  // The scan holds every vertex of the deformed bunny: the fit ends within 0.5% of the scan's diagonal on
  // average and 30% closer than the rigid pre-alignment left it (a drag of 20 px: 0.28% from 0.47%;
  // tests/web/soft_fit_http_test.mjs: 0.26% from 0.48% for a drag of 6% of the height, the same fit as
  // `iarap register`'s).
  assert.ok(lastFit.final_mean < 0.005 && lastFit.final_mean < 0.7 * lastFit.initial_mean, JSON.stringify(lastFit));
  const kept = Array.from(new Float32Array(await (await fetch(`${server.url}api/positions?method=iarap`)).arrayBuffer()));
  assert.deepEqual(await viewer('displayedPositions'), kept, 'the page does not show the fitted shape the server keeps');
  assert.ok(Array.from(await page.evaluate(() => document.getElementById('fit-plot').getContext('2d').getImageData(0, 0, 260, 90).data)).some((v) => v !== 0), 'no residual plot');
  await page.screenshot({ path: path.join(artefactDir, 'viewer_fit.png') });
  assert.equal(await viewer('errors'), 0, await page.textContent('#banner-text'));
  assert.deepEqual(problems, []);

  // 10. A tetrahedral mesh (a MEDIT bar of 2 cubes, 12 tetrahedra) is shown by its boundary, with iarap as
  // its only method and the surface-only choices off.
  const barVertices = [];
  for (let k = 0; k <= 1; ++k) for (let j = 0; j <= 1; ++j) for (let i = 0; i <= 2; ++i) barVertices.push(`${i} ${j} ${k} 0`);
  const at = (i, j, k) => 1 + i + 3 * (j + 2 * k);
  const barTets = [];
  for (let i = 0; i < 2; ++i) { // two cubes, each 6 tetrahedra around its diagonal, all positive
    barTets.push([at(i, 0, 0), at(i + 1, 0, 0), at(i + 1, 1, 0), at(i + 1, 1, 1)], [at(i, 0, 0), at(i + 1, 1, 0), at(i, 1, 0), at(i + 1, 1, 1)],
      [at(i, 0, 0), at(i, 1, 0), at(i, 1, 1), at(i + 1, 1, 1)], [at(i, 0, 0), at(i, 1, 1), at(i, 0, 1), at(i + 1, 1, 1)],
      [at(i, 0, 0), at(i, 0, 1), at(i + 1, 0, 1), at(i + 1, 1, 1)], [at(i, 0, 0), at(i + 1, 0, 1), at(i + 1, 0, 0), at(i + 1, 1, 1)]);
  }
  const medit = ['MeshVersionFormatted 1', 'Dimension 3', `Vertices ${barVertices.length}`, ...barVertices, `Tetrahedra ${barTets.length}`, ...barTets.map((t) => `${t.join(' ')} 0`), 'End'].join('\n');
  await page.setInputFiles('#upload', { name: 'bar.mesh', mimeType: 'application/octet-stream', buffer: Buffer.from(medit) });
  await page.waitForFunction(() => document.getElementById('status').textContent === 'loaded bar.mesh', null, { timeout: 30000 });
  const tetPage = await page.evaluate(() => ({
    info: document.getElementById('mesh-info').textContent.split('\n')[0],
    method: document.getElementById('method').value,
    disabled: Array.from(document.getElementById('method').options).filter((o) => o.disabled).map((o) => o.value),
    sideBySide: document.getElementById('side-by-side').disabled,
    vertices: window.iarapViewer.labels().length,
  }));
  assert.deepEqual(tetPage, { info: 'bar.mesh: 12 tetrahedra, 12 vertices, shown by its 20 boundary faces', method: 'iarap', disabled: ['arap', 'spokes-rims'], sideBySide: true, vertices: 12 });
  assert.equal(await viewer('errors'), 0, await page.textContent('#banner-text'));
  assert.deepEqual(problems, []);

  // 7. A server that went away is named as such, in the banner.
  await stopServer(server);
  await page.click('#reset');
  await page.waitForFunction(() => !document.getElementById('banner').hidden, null, { timeout: 10000 });
  assert.match(await page.textContent('#banner-text'), /iarap server does not answer/);
  console.log('browser test: 1 passed, 0 failed');
});
