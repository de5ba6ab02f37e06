// What the HTTP tests of `iarap serve` share: a refused request checked by status and message, and the
// bunny's bottom and top tenths (fixed and handle).
import assert from 'node:assert/strict';

// Awaits the response; asserts its status and that its JSON error matches pattern; returns the message.
export async function expectError(responsePromise, status, pattern) {
  const response = await responsePromise;
  const text = await response.text();
  assert.equal(response.status, status, `expected ${status}, got ${response.status}: ${text}`);
  const message = JSON.parse(text).error;
  assert.match(message, pattern);
  return message;
}

// The rest positions of the server at base, and its vertices in the bottom tenth (fixed) and the top tenth
// (handle) by y, with the height.
export async function bottomAndTop(base) {
  const X = new Float32Array(await (await fetch(base + '/api/positions?method=rest')).arrayBuffer());
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
