// The viewer page: wires the panel, the selection tools and the gizmo to the iarap serve API.
import { api } from './api.js';
import { energyColors } from './colormap.js';
import { drawEnergyPlot, methodColors } from './energy_plot.js';
import { LatestOnly } from './latest_only.js';
import { FIXED, HANDLE, box, brush, indicesWith, paintLabel } from './selection.js';
import { Viewer } from './viewer.js';

const allMethods = ['arap', 'spokes-rims', 'iarap'];
const $ = (id) => document.getElementById(id);
const viewer = new Viewer($('viewport'), $('labels'));
const app = { labels: new Uint8Array(0), mesh: null, energy: {}, curves: {}, solves: 0, errors: 0 };

function setStatus(text, isError = false) {
  $('status').textContent = text;
  $('status').classList.toggle('error', isError);
  if (isError) app.errors += 1;
}

// Runs an async UI action, showing the server's message on failure instead of throwing.
async function guarded(action) {
  try {
    return await action();
  } catch (error) {
    setStatus(error.message, true);
    return undefined;
  }
}

const radio = (name) => document.querySelector(`input[name=${name}]:checked`).value;
const shownMethods = () => ($('side-by-side').checked ? allMethods : [$('method').value]);
const iterations = () => Math.min(Math.max(parseInt($('iterations').value, 10) || 5, 1), 200);

function repaint() {
  viewer.paint(app.labels, $('show-energy').checked ? app.energy : null);
  const fixed = indicesWith(app.labels, FIXED).length;
  const handle = indicesWith(app.labels, HANDLE).length;
  $('selection-info').textContent = `${fixed} fixed, ${handle} handle vertices`;
}

async function solveShown() {
  const fixed = indicesWith(app.labels, FIXED);
  const handle = indicesWith(app.labels, HANDLE);
  if (fixed.length + handle.length === 0) return;
  const transform = viewer.handleTransform();
  const methods = shownMethods();
  const cellEnergy = $('show-energy').checked;
  const results = await guarded(() =>
    Promise.all(methods.map((method) => api.solve({ method, iterations: iterations(), transform, cell_energy: cellEnergy }))),
  );
  if (!results) return;
  const lines = [];
  app.curves = {};
  results.forEach(({ header, arrays }, i) => {
    const method = methods[i];
    viewer.setPositions(method, arrays.positions);
    if (arrays.cell_energy) {
      app.energy[method] ??= new Float32Array(arrays.positions.length);
      energyColors(arrays.cell_energy, app.labels, app.energy[method]);
    }
    app.curves[method] = [header.initial_energy, ...header.energies];
    const last = header.energies.at(-1) ?? header.initial_energy;
    const precompute = header.precompute_ms > 0 ? ` + setup ${header.precompute_ms.toFixed(0)} ms` : '';
    lines.push(`${method}: E = ${last.toExponential(3)}, ${header.iterations} it, ${header.solve_ms.toFixed(1)} ms${precompute}`);
  });
  repaint();
  drawEnergyPlot($('energy-plot'), app.curves);
  $('solve-info').textContent = lines.join('\n');
  app.solves += 1;
  setStatus('');
}

const solver = new LatestOnly(solveShown);

async function showPositions(methods) {
  const positions = {};
  await Promise.all(methods.map(async (method) => { positions[method] = await api.positions(method); }));
  return positions;
}

async function loadMesh(state) {
  app.mesh = state.mesh;
  $('mesh-info').textContent = state.mesh
    ? [`${state.mesh.name}: ${state.mesh.vertices} vertices, ${state.mesh.faces} faces`, ...state.mesh.notes, ...state.mesh.warnings].join('\n')
    : 'no mesh: upload one';
  if (!state.mesh) return;
  const [faces, rest] = await Promise.all([api.faces(), api.positions('rest')]);
  viewer.setMesh(faces, rest, shownMethods());
  const positions = await showPositions(shownMethods());
  for (const [method, p] of Object.entries(positions)) viewer.setPositions(method, p);
  app.labels = new Uint8Array(state.mesh.vertices);
  for (const i of state.fixed) app.labels[i] = FIXED;
  for (const i of state.handle) app.labels[i] = HANDLE;
  app.energy = {};
  viewer.placeGizmo(state.handle);
  repaint();
  await refreshIntrinsic();
}

async function refreshIntrinsic() {
  viewer.setIntrinsicOverlay($('show-intrinsic').checked ? await api.intrinsicEdges() : null);
}

async function commitSelection() {
  await solver.idle();
  const handle = indicesWith(app.labels, HANDLE);
  await api.setConstraints(indicesWith(app.labels, FIXED), handle);
  viewer.placeGizmo(handle);
  repaint();
  solver.request();
}

async function changeLayout() {
  await solver.idle();
  const methods = shownMethods();
  viewer.setLayout(methods, await showPositions(methods));
  viewer.fitCamera();
  repaint();
  solver.request();
}

// Brush and box strokes with the left button; orbiting moves to the right button meanwhile.
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
  const brushAt = (event) => {
    const hit = viewer.pick(event.clientX, event.clientY);
    if (hit && brush(app.labels, hit.view.positions(), hit.point, Number($('brush-radius').value) * viewer.diagonal, paintLabel(radio('paint')))) repaint();
  };
  canvas.addEventListener('pointerdown', (event) => {
    const tool = radio('tool');
    if (tool === 'orbit' || event.button !== 0 || !app.mesh || viewer.gizmo.dragging || viewer.gizmo.axis !== null) return;
    stroke = { tool, x0: event.clientX, y0: event.clientY, changed: false };
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
      box(app.labels, viewer, 0, rect, paintLabel(radio('paint')));
      repaint();
    }
    await guarded(commitSelection);
  });
  applyTool();
}

function setupPanel(state) {
  const select = $('mesh-select');
  select.replaceChildren(...state.meshes.map((name) => Object.assign(document.createElement('option'), { value: name, textContent: name })));
  if (state.mesh) select.value = state.mesh.name;
  select.addEventListener('change', () => guarded(async () => { await solver.idle(); await loadMesh(await api.load(select.value)); }));
  $('upload').addEventListener('change', () => guarded(async () => {
    const file = $('upload').files[0];
    if (!file) return;
    await solver.idle();
    setStatus(`uploading ${file.name}...`);
    await loadMesh(await api.upload(file));
    setStatus(`loaded ${file.name}`);
  }));
  $('clear-selection').addEventListener('click', () => guarded(async () => { app.labels.fill(0); await commitSelection(); }));
  $('method').addEventListener('change', () => guarded(changeLayout));
  $('side-by-side').addEventListener('change', () => guarded(changeLayout));
  $('step').addEventListener('click', () => solver.request());
  $('reset').addEventListener('click', () => guarded(async () => {
    await solver.idle();
    await api.reset();
    const positions = await showPositions(shownMethods());
    for (const [method, p] of Object.entries(positions)) viewer.setPositions(method, p);
    viewer.placeGizmo(indicesWith(app.labels, HANDLE));
    app.curves = {};
    drawEnergyPlot($('energy-plot'), app.curves);
  }));
  $('download').addEventListener('click', () => {
    const link = Object.assign(document.createElement('a'), { href: api.downloadUrl(shownMethods()[0], 'obj') });
    link.click();
  });
  const gizmoMode = (mode) => {
    viewer.gizmo.setMode(mode);
    $('gizmo-translate').classList.toggle('active', mode === 'translate');
    $('gizmo-rotate').classList.toggle('active', mode === 'rotate');
  };
  $('gizmo-translate').addEventListener('click', () => gizmoMode('translate'));
  $('gizmo-rotate').addEventListener('click', () => gizmoMode('rotate'));
  window.addEventListener('keydown', (event) => {
    if (event.target instanceof HTMLInputElement && event.target.type !== 'radio' && event.target.type !== 'checkbox') return;
    if (event.key === 'w') gizmoMode('translate');
    if (event.key === 'e') gizmoMode('rotate');
  });
  $('show-intrinsic').addEventListener('change', () => guarded(refreshIntrinsic));
  $('show-energy').addEventListener('change', () => {
    repaint();
    if ($('show-energy').checked) solver.request();
  });
  $('show-wireframe').addEventListener('change', () => viewer.setWireframe($('show-wireframe').checked));
  viewer.gizmo.addEventListener('objectChange', () => solver.request());
  for (const method of allMethods) $('method').querySelector(`[value=${method}]`).style.color = methodColors[method];
}

// For automated checks (tests/web): what is displayed, and where to point.
window.iarapViewer = {
  ready: false,
  solves: () => app.solves,
  errors: () => app.errors,
  idle: () => solver.idle(),
  displayedPositions: (method) => Array.from(viewer.view(method ?? shownMethods()[0]).positions()),
  labels: () => Array.from(app.labels),
  meshScreenBox: () => {
    const view = viewer.views[0];
    view.mesh.geometry.computeBoundingBox();
    const { min, max } = view.mesh.geometry.boundingBox;
    const corners = [];
    for (const x of [min.x, max.x]) for (const y of [min.y, max.y]) for (const z of [min.z, max.z]) corners.push(viewer.toScreen(min.clone().set(x, y, z)));
    return { x0: Math.min(...corners.map((c) => c.x)), x1: Math.max(...corners.map((c) => c.x)), y0: Math.min(...corners.map((c) => c.y)), y1: Math.max(...corners.map((c) => c.y)) };
  },
  // A point on the gizmo's x arrow (TransformControls scales its handles by this factor; the x picker
  // spans 0..0.6 of it along +x).
  gizmoXArrowScreenPoint: () => {
    const origin = viewer.gizmoTarget.position.clone();
    const { fov, zoom } = viewer.camera;
    const factor = (origin.distanceTo(viewer.camera.position) * Math.min((1.9 * Math.tan((Math.PI * fov) / 360)) / zoom, 7) * viewer.gizmo.size) / 4;
    const p = origin.add(new origin.constructor(0.4 * factor, 0, 0)).project(viewer.camera);
    const rect = viewer.renderer.domElement.getBoundingClientRect();
    return { x: rect.left + (0.5 + 0.5 * p.x) * rect.width, y: rect.top + (0.5 - 0.5 * p.y) * rect.height };
  },
};

guarded(async () => {
  const state = await api.state();
  setupPanel(state);
  setupSelectionTools();
  await loadMesh(state);
  window.iarapViewer.ready = true;
  setStatus(state.mesh ? 'Pick Brush or Box, paint Fixed and Handle vertices, then drag the gizmo.' : 'Upload a mesh to start.');
});
