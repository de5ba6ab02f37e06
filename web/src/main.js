// The viewer page: wires the panel, the selection tools, the gizmos, undo / redo and the scenario files to
// the iarap serve API.
import { api } from './api.js';
import { drawColorBar, energyColors, energyScale } from './colormap.js';
import { defaultBudgetMs } from './drag_budget.js';
import { drawEnergyPlot, methodColors } from './energy_plot.js';
import { FitPanel } from './fit_panel.js';
import { UndoHistory } from './history.js';
import { LatestOnly } from './latest_only.js';
import { RefinementFeed } from './refinement.js';
import { NO_GROUP, emptyGroups, groupLists, groupsFromLists, nextGroup } from './rigid_groups.js';
import { FIXED, HANDLE, box, brush, indicesWith, paintLabel } from './selection.js';
import { UvPanel } from './uv_panel.js';
import { Viewer } from './viewer.js';

const allMethods = ['arap', 'spokes-rims', 'iarap'];
const $ = (id) => document.getElementById(id);
const viewer = new Viewer($('viewport'), $('labels'));
const app = {
  labels: new Uint8Array(0), mesh: null, revision: 0, limits: { max_iterations: 1000 },
  groups: new Int32Array(0), // the rigid group of each vertex (rigid_groups.js), apart from the labels
  soft: { dragged: [], count: 0 }, // a loaded file's soft constraints (setSoft)
  cellEnergy: {}, energyColors: {}, scale: null, curves: {},
  history: new UndoHistory(), cancelling: false, converge: false, solves: 0, errors: 0,
  answers: [], frames: [], // the last solve answers' and refinement frames' headers, for tests/web
  budgetChosen: false, // the user typed a time per update: loading a mesh keeps it
};

function setStatus(text) {
  $('status').textContent = text;
}

// Errors go to a banner over the view (visible at any window size) until closed or the next solve.
function showError(message) {
  $('banner-text').textContent = message;
  $('banner').hidden = false;
  app.errors += 1;
}

// Runs an async UI action, showing the server's message on failure instead of throwing.
// The guarded actions still running (a layout change fetching positions, a scenario loading): the test
// hook idle() waits for them as well as for the solver.
const pendingActions = new Set();

async function guarded(action) {
  const run = (async () => {
    try {
      return await action();
    } catch (error) {
      showError(error.message);
      return undefined;
    }
  })();
  pendingActions.add(run);
  try {
    return await run;
  } finally {
    pendingActions.delete(run);
  }
}

const radio = (name) => document.querySelector(`input[name=${name}]:checked`).value;
const shownMethods = () => ($('side-by-side').checked ? allMethods : [$('method').value]);

// The iteration count of the field; an error naming the limit when it is not a whole number in range
// (never clamped behind the user's back).
function iterations() {
  const text = $('iterations').value.trim();
  const value = Number(text);
  if (!/^\d+$/.test(text) || value < 1 || value > app.limits.max_iterations) {
    throw new Error(`Iterations per update must be a whole number from 1 to ${app.limits.max_iterations} (the server's limit); got "${text}".`);
  }
  return value;
}

// The time budget of an update in ms (0: none), checked as iterations() is.
function budgetMs() {
  const text = $('budget').value.trim();
  const value = Number(text);
  if (!/^\d+$/.test(text) || value > 10000) throw new Error(`Time per update must be a whole number of milliseconds from 0 to 10000; got "${text}".`);
  return value;
}

// The relative energy decrease that stops updates and the refinement, a number in (0, 1).
function tolerance() {
  const text = $('tolerance').value.trim();
  const value = Number(text);
  if (text === '' || !(value > 0 && value < 1)) throw new Error(`Tolerance must be a number between 0 and 1 (e.g. 1e-6); got "${text}".`);
  return value;
}

// The rotation smoothing weight (docs/smoothing.md) from the log slider: 10^value, 0 (off) at the slider's
// lowest position.
function rotationSmoothing() {
  const slider = $('smoothing');
  return Number(slider.value) <= Number(slider.min) ? 0 : 10 ** Number(slider.value);
}

function showRotationSmoothing() {
  const alpha = rotationSmoothing();
  $('smoothing-value').textContent = alpha > 0 ? `alpha = ${alpha.toPrecision(2)}` : 'off';
}

// The soft handle's weight from the log slider (10^value), or null for a hard handle.
function handleWeight() {
  return $('soft-handle').checked ? 10 ** Number($('handle-weight').value) : null;
}

// The solve's handle_weights: one per handle vertex when the handle is soft (none for a hard one).
function handleWeights(handleCount) {
  const weight = handleWeight();
  return weight !== null && handleCount > 0 ? new Array(handleCount).fill(weight) : undefined;
}

function showHandleWeight() {
  const soft = $('soft-handle').checked;
  $('handle-weight').disabled = !soft;
  $('handle-weight-value').textContent = soft ? `w = ${handleWeight().toPrecision(2)}` : '(hard handle)';
  viewer.setSoftHandle(soft);
}

// Keeps only the last entries of a record list the tests read.
const remember = (list, entry) => {
  list.push(entry);
  if (list.length > 100) list.shift();
};

// Energy colours on one scale over every shown method, and the colour bar showing it.
function updateEnergyColors() {
  const methods = shownMethods().filter((m) => app.cellEnergy[m]);
  app.scale = methods.length > 0 ? energyScale(methods.map((m) => app.cellEnergy[m]), app.labels) : null;
  app.energyColors = {};
  if (app.scale) {
    for (const method of methods) {
      app.energyColors[method] = new Float32Array(3 * app.labels.length);
      energyColors(app.cellEnergy[method], app.scale, app.energyColors[method]);
    }
  }
  drawColorBar($('colorbar-canvas'), app.scale);
}

function repaint() {
  const showEnergy = $('show-energy').checked;
  viewer.paint(app.labels, showEnergy ? app.energyColors : null, app.groups);
  $('colorbar').hidden = !(showEnergy && app.scale);
  const fixed = indicesWith(app.labels, FIXED).length;
  const handle = indicesWith(app.labels, HANDLE).length;
  const soft = app.soft.count ? `, ${app.soft.count} soft (from the file)` : '';
  const weight = handleWeight();
  const softHandle = weight !== null && handle > 0 ? ` (soft, w = ${weight.toPrecision(2)})` : '';
  const { lists, leftOut } = groupLists(app.groups);
  const rigid = lists.length ? `, ${lists.length} rigid group${lists.length > 1 ? 's' : ''}` : '';
  const single = leftOut ? ` (${leftOut} lone vertices not in a group: a group needs 2)` : '';
  $('selection-info').textContent = `${fixed} fixed, ${handle} handle vertices${softHandle}${soft}${rigid}${single}`;
  $('undo').disabled = !app.history.canUndo();
  $('redo').disabled = !app.history.canRedo();
}

// Polls /api/progress while a solve takes longer than a moment; shows the bar and the Cancel button.
function watchProgress() {
  let timer = null;
  let stopped = false;
  const poll = async () => {
    const progress = await api.progress().catch(() => null);
    if (stopped) return;
    if (progress?.running) {
      $('progress').hidden = false;
      $('progress-bar').value = progress.iteration / Math.max(progress.iterations, 1);
      $('progress-text').textContent = `${progress.method}: ${progress.iteration} / ${progress.iterations} iterations`;
      if (app.cancelling) await api.cancel().catch(() => null); // side by side: the next method's solve too
    }
    timer = setTimeout(poll, 250);
  };
  timer = setTimeout(poll, 400);
  return () => {
    stopped = true;
    clearTimeout(timer);
    $('progress').hidden = true;
    app.cancelling = false;
  };
}

// Stops the solve in progress, or else the background refinement (the server keeps its last iterate and
// publishes it as a last frame).
async function cancelSolve() {
  if (!$('progress').hidden) app.cancelling = true;
  await api.cancel().catch(() => null);
}

async function solveShown() {
  const fixed = indicesWith(app.labels, FIXED);
  const handle = indicesWith(app.labels, HANDLE);
  if (fixed.length + handle.length + app.soft.count === 0) return;
  let count, budget, stopAt;
  try {
    count = iterations();
    budget = budgetMs();
    stopAt = tolerance();
  } catch (error) {
    showError(error.message);
    return;
  }
  // "Solve to convergence": the server's iteration limit, stopped by the gradient rule instead.
  const converge = app.converge;
  app.converge = false;
  const stopping = converge
    ? { iterations: app.limits.max_iterations, tolerance: 0, gradient_tolerance: 1e-6 }
    : { iterations: count, time_budget_ms: budget, tolerance: stopAt };
  const accelerator = $('accelerator').value;
  const transform = viewer.handleTransform();
  const methods = shownMethods();
  const cellEnergy = $('show-energy').checked;
  // The server refines one method, and its frames carry no cell energies.
  const refine = $('refine').checked && methods.length === 1 && !cellEnergy && !converge;
  const refineAccelerator = $('refine-accelerator').value;
  // Updates start where the drag's motion leads (docs/viewer.md); the server predicts nothing when the
  // targets did not move, so a repeated solve is unchanged. Not for "solve to convergence".
  const extrapolate = !converge;
  const weights = handleWeights(handle.length);
  const smoothing = rotationSmoothing();
  refinement.stop();
  $('refine-info').textContent = '';
  const stopWatching = watchProgress();
  const results = await guarded(() =>
    Promise.all(methods.map((method) => api.solve({ method, ...stopping, accelerator, transform, cell_energy: cellEnergy, refine, refine_accelerator: refineAccelerator, rotation_smoothing: smoothing, extrapolate, ...(weights ? { handle_weights: weights } : {}) }))),
  ).finally(stopWatching);
  if (!results) return;
  const lines = [];
  app.curves = {};
  let cancelled = false;
  results.forEach(({ header, arrays }, i) => {
    const method = methods[i];
    viewer.setPositions(method, arrays.positions);
    if (arrays.cell_energy) app.cellEnergy[method] = Float32Array.from(arrays.cell_energy);
    app.curves[method] = [header.initial_energy, ...header.energies];
    cancelled ||= header.cancelled;
    remember(app.answers, { ...header, receivedAt: performance.now() });
    if (header.refining) {
      refinement.follow(header.sequence, header.generation);
      $('refine-info').textContent = 'refining in the background...';
    }
    const last = header.energies.at(-1) ?? header.initial_energy;
    const precompute = header.precompute_ms > 0 ? ` + setup ${header.precompute_ms.toFixed(0)} ms` : '';
    const stop = header.cancelled ? ' (cancelled)' : header.converged ? ' (converged)' : '';
    lines.push(`${method}: E = ${last.toExponential(3)}, ${header.iterations} it${stop}, ${header.solve_ms.toFixed(1)} ms${precompute}`);
  });
  updateEnergyColors();
  repaint();
  drawEnergyPlot($('energy-plot'), app.curves);
  $('solve-info').textContent = lines.join('\n');
  app.solves += 1;
  $('banner').hidden = true; // a solve went through: an earlier error no longer applies
  if (cancelled) setStatus('Solve cancelled; the shape is the last finished iteration.');
}

const solver = new LatestOnly(solveShown);

// A refinement frame: the next iterate toward the last answer's targets, and how far it still moves.
function showRefinedFrame({ header, arrays }) {
  if (solver.running) return; // a newer solve is on its way
  viewer.setPositions(header.method, arrays.positions);
  remember(app.frames, { ...header, receivedAt: performance.now() });
  const where = `${header.method}: E = ${header.energy.toExponential(4)} after ${header.iterations} more it`;
  $('refine-info').textContent = header.error
    ? `refinement stopped: ${header.error}`
    : header.converged
      ? `${where}, converged (last relative decrease ${header.relative_decrease.toExponential(1)} <= ${header.tolerance})`
      : header.refining
        ? `${where}; refining: last relative decrease ${header.relative_decrease.toExponential(1)}, stops at ${header.tolerance}`
        : `${where}; refinement stopped`;
}

const refinement = new RefinementFeed(showRefinedFrame);

async function fetchPositions(methods) {
  const positions = {};
  await Promise.all(methods.map(async (method) => { positions[method] = await api.positions(method); }));
  return positions;
}

async function showPositions(methods) {
  for (const [method, p] of Object.entries(await fetchPositions(methods))) viewer.setPositions(method, p);
}

// Undo snapshots: the selection, the server's constraint revision (sets and anchors) and the gizmos.
const snapshot = () => ({ labels: app.labels.slice(), groups: app.groups.slice(), revision: app.revision, gizmo: viewer.gizmoState() });

function record() {
  app.history.push(snapshot());
  repaint();
}

// The soft constraints of a loaded file, kept by the server (they are not labels: a selection never holds
// them): the weighted handles' vertices, which the gizmo drags with the handle, and how many there are.
function setSoft(state) {
  const soft = state.soft ?? { vertices: [], dragged: [], face_points: 0, hard_face_points: 0 };
  app.soft = {
    dragged: soft.vertices.filter((_, k) => soft.dragged[k]),
    count: soft.vertices.length + soft.face_points + soft.hard_face_points,
  };
}

// The vertices the gizmo moves: the handle and the dragged soft vertices.
const gizmoVertices = () => [...indicesWith(app.labels, HANDLE), ...app.soft.dragged];

function setLabels(state) {
  setSoft(state);
  app.labels = new Uint8Array(state.mesh.vertices);
  for (const i of state.fixed) app.labels[i] = FIXED;
  for (const i of state.handle) app.labels[i] = HANDLE;
  app.groups = groupsFromLists(state.mesh.vertices, state.rigid_groups);
  app.revision = state.revision ?? 0;
}

// Everything shown for the previous mesh goes: energies, curves, solve figures, history, error banner.
function clearResults() {
  app.cellEnergy = {};
  app.energyColors = {};
  app.scale = null;
  app.curves = {};
  drawEnergyPlot($('energy-plot'), app.curves);
  drawColorBar($('colorbar-canvas'), null);
  $('solve-info').textContent = '';
  $('banner').hidden = true;
}

function showMeshChoice(state) {
  const select = $('mesh-select');
  select.querySelector('option[data-upload]')?.remove();
  if (state.mesh && !state.meshes.includes(state.mesh.name)) {
    const option = Object.assign(document.createElement('option'), { value: '', textContent: `${state.mesh.name} (uploaded)`, disabled: true });
    option.dataset.upload = 'true';
    select.append(option);
    option.selected = true;
  } else if (state.mesh) {
    select.value = state.mesh.name;
  }
}

// A tetrahedral mesh is deformed by the volume energy only (method iarap) and has no per-vertex cells or
// intrinsic edges: the choices that need a triangle mesh are switched off and disabled for it.
function allowSurfaceChoices(mesh) {
  const tets = (mesh?.tetrahedra ?? 0) > 0;
  for (const option of $('method').options) option.disabled = tets && option.value !== 'iarap';
  if (tets) $('method').value = 'iarap';
  for (const id of ['side-by-side', 'show-energy', 'show-intrinsic']) {
    if (tets) $(id).checked = false;
    $(id).disabled = tets;
  }
}

function describeMesh(mesh) {
  if (!mesh) return 'no mesh: upload one';
  const size = mesh.tetrahedra > 0
    ? `${mesh.tetrahedra} tetrahedra, ${mesh.vertices} vertices, shown by its ${mesh.faces} boundary faces`
    : `${mesh.vertices} vertices, ${mesh.faces} faces`;
  return [`${mesh.name}: ${size}`, ...mesh.notes, ...mesh.warnings].join('\n');
}

async function loadMesh(state) {
  refinement.stop(); // frames of the previous mesh's refinement must not land on this one
  app.mesh = state.mesh;
  clearResults();
  showMeshChoice(state);
  allowSurfaceChoices(state.mesh);
  $('mesh-info').textContent = describeMesh(state.mesh);
  if (!state.mesh) return;
  // The budget follows the mesh's size until the user sets one.
  if (!app.budgetChosen) $('budget').value = String(defaultBudgetMs(state.mesh.vertices));
  const [faces, rest] = await Promise.all([api.faces(), api.positions('rest')]);
  viewer.setMesh(faces, rest, shownMethods());
  uvPanel.setMesh(faces);
  await showPositions(shownMethods());
  setLabels(state);
  viewer.placeGizmo(gizmoVertices());
  await fitPanel.setMesh(state);
  app.history.reset(snapshot());
  repaint();
  await refreshIntrinsic();
}

async function refreshIntrinsic() {
  viewer.setIntrinsicOverlay($('show-intrinsic').checked ? await api.intrinsicEdges() : null);
}

async function commitSelection() {
  await solver.idle();
  refinement.stop();
  const handle = indicesWith(app.labels, HANDLE);
  app.revision = (await api.setConstraints(indicesWith(app.labels, FIXED), handle, groupLists(app.groups).lists)).revision;
  viewer.placeGizmo(gizmoVertices());
  record();
  solver.request();
}

// Back or forward to a snapshot: the server gets its constraint revision back, the page its selection
// and gizmos, and a solve moves the shape there.
async function travel(state) {
  if (!state) return;
  await solver.idle();
  refinement.stop(); // a frame still on its way would undo the undo
  let answer = null;
  if (state.revision === 0) answer = await api.setConstraints([], [], []);
  else if (state.revision !== app.revision) answer = await api.restoreConstraints(state.revision);
  if (answer) {
    app.revision = answer.revision;
    setSoft(answer); // an undo past a file's load takes its soft constraints away
  }
  app.labels.set(state.labels);
  app.groups.set(state.groups);
  viewer.setGizmoState(state.gizmo);
  repaint();
  solver.request();
}

async function changeLayout() {
  await solver.idle();
  const methods = shownMethods();
  viewer.setLayout(methods, await fetchPositions(methods));
  viewer.placeGizmo(gizmoVertices(), false);
  viewer.fitCamera();
  updateEnergyColors();
  repaint();
  solver.request();
}

function download(href, name) {
  const link = Object.assign(document.createElement('a'), { href, download: name ?? '' });
  document.body.append(link);
  link.click();
  link.remove();
}

// Brush and box strokes with the left button, on any copy; orbiting moves to the right button meanwhile.
function setupSelectionTools() {
  const canvas = viewer.renderer.domElement;
  const rectElement = $('box-rect');
  let stroke = null;
  const applyTool = () => {
    const selecting = radio('tool') !== 'orbit';
    viewer.orbit.mouseButtons.LEFT = selecting ? null : 0;
    viewer.orbit.mouseButtons.RIGHT = selecting ? 0 : 2;
  };
  document.querySelectorAll('input[name=tool]').forEach((input) => input.addEventListener('change', applyTool));
  // What a stroke paints: [array, value] pairs. A rigid-group stroke paints a new group; the eraser
  // clears both the labels and the groups.
  const strokeTargets = (done) => {
    const paint = radio('paint');
    if (paint === 'rigid') return [[app.groups, done.group]];
    const targets = [[app.labels, paintLabel(paint)]];
    if (paint === 'erase') targets.push([app.groups, NO_GROUP]);
    return targets;
  };
  const brushAt = (event) => {
    const hit = viewer.pick(event.clientX, event.clientY);
    if (!hit) return;
    const radius = Number($('brush-radius').value) * viewer.diagonal;
    let changed = false;
    for (const [array, value] of strokeTargets(stroke)) changed = brush(array, hit.view.positions(), hit.point, radius, value) || changed;
    if (changed) {
      stroke.changed = true;
      repaint();
    }
  };
  canvas.addEventListener('pointerdown', (event) => {
    const tool = radio('tool');
    if (tool === 'orbit' || event.button !== 0 || !app.mesh || viewer.gizmoActive()) return;
    stroke = { tool, x0: event.clientX, y0: event.clientY, changed: false, view: viewer.viewAt(event.clientX, event.clientY), group: nextGroup(app.groups) };
    canvas.setPointerCapture(event.pointerId);
    if (tool === 'brush') brushAt(event);
  });
  canvas.addEventListener('pointermove', (event) => {
    if (!stroke) return;
    if (stroke.tool === 'brush') {
      brushAt(event);
      return;
    }
    const bounds = $('viewport').getBoundingClientRect();
    Object.assign(rectElement.style, {
      left: `${Math.min(stroke.x0, event.clientX) - bounds.left}px`, top: `${Math.min(stroke.y0, event.clientY) - bounds.top}px`,
      width: `${Math.abs(event.clientX - stroke.x0)}px`, height: `${Math.abs(event.clientY - stroke.y0)}px`,
    });
    rectElement.hidden = false;
  });
  canvas.addEventListener('pointerup', async (event) => {
    if (!stroke) return;
    const done = stroke;
    stroke = null;
    rectElement.hidden = true;
    if (done.tool === 'box') {
      const rect = { x0: Math.min(done.x0, event.clientX), x1: Math.max(done.x0, event.clientX), y0: Math.min(done.y0, event.clientY), y1: Math.max(done.y0, event.clientY) };
      for (const [array, value] of strokeTargets(done)) done.changed = box(array, viewer, done.view, rect, value) || done.changed;
    }
    if (done.changed) await guarded(commitSelection);
  });
  applyTool();
}

let uvPanel = null;
let fitPanel = null;

function setupPanel(state) {
  uvPanel = new UvPanel(api, viewer, guarded);
  fitPanel = new FitPanel(api, viewer, guarded, {
    method: () => $('method').value,
    beforeFit: async () => {
      await solver.idle();
      refinement.stop();
    },
    // The server re-took the anchors on the fitted shape: the gizmo starts there.
    afterFit: () => viewer.placeGizmo(gizmoVertices()),
  });
  const softHandleChanged = () => {
    showHandleWeight();
    repaint();
    solver.request();
  };
  $('soft-handle').addEventListener('change', softHandleChanged);
  $('handle-weight').addEventListener('input', softHandleChanged);
  showHandleWeight();
  app.limits = state.limits;
  $('iterations').max = String(state.limits.max_iterations);
  $('iterations-limit').textContent = `(1 to ${state.limits.max_iterations})`;
  $('iterations').addEventListener('change', () => guarded(async () => iterations()));
  $('budget').addEventListener('input', () => { app.budgetChosen = true; });
  const select = $('mesh-select');
  select.replaceChildren(...state.meshes.map((name) => Object.assign(document.createElement('option'), { value: name, textContent: name })));
  select.addEventListener('change', () => guarded(async () => {
    await solver.idle();
    await loadMesh(await api.load(select.value));
  }));
  $('upload').addEventListener('change', () => guarded(async () => {
    const file = $('upload').files[0];
    if (!file) return;
    $('upload').value = '';
    await solver.idle();
    setStatus(`uploading ${file.name}...`);
    await loadMesh(await api.upload(file));
    setStatus(`loaded ${file.name}`);
  }));
  $('clear-selection').addEventListener('click', () => guarded(async () => { app.labels.fill(0); await commitSelection(); }));
  $('clear-rigid').addEventListener('click', () => guarded(async () => { app.groups.fill(NO_GROUP); await commitSelection(); }));
  $('smoothing').addEventListener('input', () => {
    showRotationSmoothing();
    solver.request();
  });
  showRotationSmoothing();
  $('undo').addEventListener('click', () => guarded(() => travel(app.history.undo())));
  $('redo').addEventListener('click', () => guarded(() => travel(app.history.redo())));
  $('method').addEventListener('change', () => guarded(changeLayout));
  $('side-by-side').addEventListener('change', () => guarded(changeLayout));
  $('step').addEventListener('click', () => solver.request());
  $('converge').addEventListener('click', () => {
    app.converge = true;
    solver.request();
  });
  $('cancel').addEventListener('click', cancelSolve);
  $('reset').addEventListener('click', () => guarded(async () => {
    await solver.idle();
    refinement.stop();
    app.revision = (await api.reset()).revision ?? app.revision;
    await showPositions(shownMethods());
    viewer.placeGizmo(gizmoVertices());
    clearResults();
    record();
  }));
  // One OBJ per shown method.
  $('download').addEventListener('click', () => {
    shownMethods().forEach((method, i) => setTimeout(() => download(api.downloadUrl(method, 'obj')), 300 * i));
  });
  $('save-scenario').addEventListener('click', () => guarded(async () => {
    await solver.idle();
    const weights = handleWeights(indicesWith(app.labels, HANDLE).length);
    const { name, blob } = await api.saveScenario($('method').value, viewer.handleTransform(), weights);
    const url = URL.createObjectURL(blob);
    download(url, name);
    setTimeout(() => URL.revokeObjectURL(url), 10000);
    const option = name.endsWith('.json') ? '--scenario' : '--constraints';
    setStatus(`Saved ${name}; replay: iarap deform ${app.mesh.name} ${option} ${name} --method ${$('method').value} --out out.obj`);
  }));
  $('load-scenario').addEventListener('change', () => guarded(async () => {
    const file = $('load-scenario').files[0];
    if (!file) return;
    $('load-scenario').value = '';
    await solver.idle();
    refinement.stop();
    const loaded = await api.loadScenario(file);
    setLabels(loaded);
    clearResults();
    await showPositions(shownMethods()); // the server went back to the rest shape
    viewer.placeGizmo(gizmoVertices());
    solver.request(); // the anchors are the file's targets: a solve with M = identity reaches them
    await solver.idle();
    viewer.placeGizmo(gizmoVertices());
    record();
    setStatus(`loaded ${file.name}${loaded.warnings.length ? `\n${loaded.warnings.join('\n')}` : ''}`);
  }));
  const gizmoMode = (mode) => {
    viewer.setGizmoMode(mode);
    $('gizmo-translate').classList.toggle('active', mode === 'translate');
    $('gizmo-rotate').classList.toggle('active', mode === 'rotate');
  };
  $('gizmo-translate').addEventListener('click', () => gizmoMode('translate'));
  $('gizmo-rotate').addEventListener('click', () => gizmoMode('rotate'));
  const toggleHelp = (show = $('help').hidden) => { $('help').hidden = !show; };
  $('help-button').addEventListener('click', () => toggleHelp());
  $('banner-close').addEventListener('click', () => { $('banner').hidden = true; });
  window.addEventListener('keydown', (event) => {
    const typing = event.target instanceof HTMLInputElement && !['radio', 'checkbox', 'file'].includes(event.target.type);
    if (typing) return;
    const key = event.key.toLowerCase();
    if ((event.ctrlKey || event.metaKey) && (key === 'z' || key === 'y')) {
      event.preventDefault();
      const redo = key === 'y' || event.shiftKey;
      guarded(() => travel(redo ? app.history.redo() : app.history.undo()));
    } else if (event.key === 'Escape') {
      toggleHelp(false);
      cancelSolve();
    } else if (event.key === '?') {
      toggleHelp();
    } else if (key === 'w' && !event.ctrlKey) {
      gizmoMode('translate');
    } else if (key === 'e' && !event.ctrlKey) {
      gizmoMode('rotate');
    }
  });
  $('show-intrinsic').addEventListener('change', () => guarded(refreshIntrinsic));
  $('show-energy').addEventListener('change', () => {
    repaint();
    if ($('show-energy').checked) solver.request();
  });
  $('show-wireframe').addEventListener('change', () => viewer.setWireframe($('show-wireframe').checked));
  viewer.onGizmoChange(() => solver.request());
  viewer.onGizmoDragEnd(record);
  for (const method of allMethods) $('method').querySelector(`[value=${method}]`).style.color = methodColors[method];
}

// For automated checks (tests/web): what is displayed, and where to point.
window.iarapViewer = {
  ready: false,
  solves: () => app.solves,
  answers: () => app.answers,
  frames: () => app.frames,
  fitFrames: () => fitPanel.frames,
  fitResiduals: () => fitPanel.residuals.slice(),
  errors: () => app.errors,
  // No guarded action in flight and the solver idle (an action may start solves, a solve's answer none).
  idle: async () => {
    while (pendingActions.size > 0) await Promise.all([...pendingActions]);
    await solver.idle();
  },
  displayedPositions: (method) => Array.from(viewer.view(method ?? shownMethods()[0]).positions()),
  labels: () => Array.from(app.labels),
  rigidGroups: () => Array.from(app.groups),
  viewCount: () => viewer.views.length,
  meshScreenBox: (index = 0) => viewer.screenBox(index),
  handleTransform: () => viewer.handleTransform(),
  colorScale: () => app.scale,
  cellEnergy: (method) => Array.from(app.cellEnergy[method] ?? []),
  uvReport: () => uvPanel.map?.report ?? null,
  hasTexture: () => viewer.hasTexture(),
  hasAtlas: () => viewer.hasAtlas(),
  // A point on copy `index`'s gizmo x arrow (TransformControls scales its handles by this factor; the x
  // picker spans 0..0.6 of it along +x).
  gizmoXArrowScreenPoint: (index = 0) => {
    const view = viewer.views[index];
    const origin = view.gizmoTarget.position.clone();
    const { fov, zoom } = viewer.camera;
    const factor = (origin.distanceTo(viewer.camera.position) * Math.min((1.9 * Math.tan((Math.PI * fov) / 360)) / zoom, 7) * view.gizmo.size) / 4;
    const p = origin.add(new origin.constructor(0.4 * factor, 0, 0)).project(viewer.camera);
    const rect = viewer.renderer.domElement.getBoundingClientRect();
    return { x: rect.left + (0.5 + 0.5 * p.x) * rect.width, y: rect.top + (0.5 - 0.5 * p.y) * rect.height };
  },
};

guarded(async () => {
  const state = await api.state();
  setupPanel(state);
  await loadMesh(state);
  setupSelectionTools();
  window.iarapViewer.ready = true;
  setStatus(state.mesh ? 'Pick Brush or Box, paint Fixed and Handle vertices, then drag the gizmo. Press ? for help.' : 'Upload a mesh to start.');
});
