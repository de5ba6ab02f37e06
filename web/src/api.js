// Calls to the iarap serve API. JSON errors become ApiError with the server's message, a server that does
// not answer an ApiError saying so (fetch itself only says "Failed to fetch"); binary frames (uint32 JSON
// length, JSON header, padding, typed arrays) become {header, arrays: {name: TypedArray}}.

export class ApiError extends Error {
  constructor(status, message) {
    super(message);
    this.status = status;
  }
}

async function request(path, options) {
  let response;
  try {
    response = await fetch(path, options);
  } catch {
    throw new ApiError(0, 'The iarap server does not answer: it was stopped or crashed. Start `iarap serve` again, then reload this page.');
  }
  if (response.ok) return response;
  let message = `HTTP ${response.status}`;
  try {
    message = (await response.json()).error ?? message;
  } catch {
    // not JSON: keep the status line
  }
  throw new ApiError(response.status, message);
}

const getJson = async (path) => (await request(path)).json();
const getBuffer = async (path) => (await request(path)).arrayBuffer();
const postJson = (path, body) =>
  request(path, { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(body) });
// A file's bytes as they are; the type is never a form's (the server refuses those, see api_routes.cpp).
const postFile = (path, file) =>
  request(path, { method: 'POST', headers: { 'Content-Type': 'application/octet-stream' }, body: file });

const arrayTypes = { float32: Float32Array, int32: Int32Array, uint32: Uint32Array };

export function decodeFrame(buffer) {
  const view = new DataView(buffer);
  const length = view.getUint32(0, true);
  const header = JSON.parse(new TextDecoder().decode(new Uint8Array(buffer, 4, length)));
  const arrays = {};
  let offset = 4 + length;
  for (const { name, type, count } of header.arrays) {
    arrays[name] = new arrayTypes[type](buffer, offset, count);
    offset += 4 * count;
  }
  return { header, arrays };
}

// The file name of a Content-Disposition attachment.
const attachmentName = (response, fallback) => response.headers.get('Content-Disposition')?.match(/filename="([^"]+)"/)?.[1] ?? fallback;

export const api = {
  state: () => getJson('/api/state'),
  load: async (mesh) => (await postJson('/api/load', { mesh })).json(),
  upload: async (file) => (await postFile(`/api/upload?name=${encodeURIComponent(file.name)}`, file)).json(),
  faces: async () => new Uint32Array(await getBuffer('/api/faces')),
  positions: async (method) => new Float32Array(await getBuffer(`/api/positions?method=${method}`)),
  setConstraints: async (fixed, handle, rigidGroups = []) => (await postJson('/api/constraints', { fixed, handle, rigid_groups: rigidGroups })).json(),
  restoreConstraints: async (revision) => (await postJson('/api/constraints', { revision })).json(),
  solve: async (body) => decodeFrame(await (await postJson('/api/solve', body)).arrayBuffer()),
  progress: () => getJson('/api/progress'),
  // The newest frame after `after` (waiting up to waitMs), or null when none came.
  frame: async (after, waitMs) => {
    const response = await request(`/api/frame?after=${after}&wait_ms=${waitMs}`);
    return response.status === 204 ? null : decodeFrame(await response.arrayBuffer());
  },
  cancel: async () => (await postJson('/api/cancel', {})).json(),
  reset: async () => (await postJson('/api/reset', {})).json(),
  // The rest mesh's UV map (the UV tab): {header: report, arrays: {uv: Float32Array #V x 2}} for a disk,
  // {header: atlas report (atlas: true), arrays: {corner_uv: Float32Array #F x 3 x 2, chart: Int32Array #F}}
  // for any other mesh.
  param: async (body) => decodeFrame(await (await postJson('/api/param', body)).arrayBuffer()),
  intrinsicEdges: async () => decodeFrame(await getBuffer('/api/intrinsic_edges')),
  downloadUrl: (method, format) => `/api/download?method=${method}&format=${format}`,
  // {name, blob}: the scenario (or constraints) file of the method's session.
  saveScenario: async (method, transform, handleWeights) => {
    const response = await postJson('/api/scenario', { method, transform, ...(handleWeights ? { handle_weights: handleWeights } : {}) });
    return { name: attachmentName(response, 'scenario.json'), blob: await response.blob() };
  },
  // A point cloud or mesh to fit the mesh to (session JSON with `target`), its points for drawing
  // ({header, arrays: {points, faces}}), and a fit started in the background: {generation, after, max_rounds}
  // (its rounds come as frames after `after`).
  uploadTarget: async (file) => (await postFile(`/api/target?name=${encodeURIComponent(file.name)}`, file)).json(),
  target: async () => decodeFrame(await getBuffer('/api/target')),
  fit: async (body) => (await postJson('/api/fit', body)).json(),
  loadScenario: async (file) => (await postFile(`/api/scenario/load?name=${encodeURIComponent(file.name)}`, file)).json(),
};
