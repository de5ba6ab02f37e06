// Calls to the iarap serve API. JSON errors become ApiError with the server's message; binary frames
// (uint32 JSON length, JSON header, padding, typed arrays) become {header, arrays: {name: TypedArray}}.

export class ApiError extends Error {
  constructor(status, message) {
    super(message);
    this.status = status;
  }
}

async function check(response) {
  if (response.ok) return response;
  let message = `HTTP ${response.status}`;
  try {
    message = (await response.json()).error ?? message;
  } catch {
    // not JSON: keep the status line
  }
  throw new ApiError(response.status, message);
}

async function getJson(path) {
  return (await check(await fetch(path))).json();
}

async function postJson(path, body) {
  const response = await fetch(path, {
    method: 'POST',
    headers: { 'Content-Type': 'application/json' },
    body: JSON.stringify(body),
  });
  return check(response);
}

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

export const api = {
  state: () => getJson('/api/state'),
  load: async (mesh) => (await postJson('/api/load', { mesh })).json(),
  upload: async (file) => {
    const response = await fetch(`/api/upload?name=${encodeURIComponent(file.name)}`, { method: 'POST', body: file });
    return (await check(response)).json();
  },
  faces: async () => new Uint32Array(await (await check(await fetch('/api/faces'))).arrayBuffer()),
  positions: async (method) =>
    new Float32Array(await (await check(await fetch(`/api/positions?method=${method}`))).arrayBuffer()),
  setConstraints: async (fixed, handle) => (await postJson('/api/constraints', { fixed, handle })).json(),
  solve: async (request) => decodeFrame(await (await postJson('/api/solve', request)).arrayBuffer()),
  reset: async () => (await postJson('/api/reset', {})).json(),
  intrinsicEdges: async () => decodeFrame(await (await check(await fetch('/api/intrinsic_edges'))).arrayBuffer()),
  downloadUrl: (method, format) => `/api/download?method=${method}&format=${format}`,
};
