// Starts `iarap serve` on a free loopback port for the web tests and stops it again.
import { spawn } from 'node:child_process';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

export const repoRoot = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
export const webDir = path.join(repoRoot, 'web');
export const cliPath = process.env.IARAP_CLI ?? path.join(repoRoot, 'build', 'iarap');

// Resolves {url, port, child, log()} once the server printed its URL; rejects after timeoutMs.
export function startServer(args, timeoutMs = 60000) {
  const child = spawn(cliPath, ['serve', ...args, '--port', '0', '--app-dir', webDir], { stdio: ['ignore', 'pipe', 'pipe'] });
  let stdout = '';
  let stderr = '';
  child.stderr.on('data', (chunk) => { stderr += chunk; });
  return new Promise((resolve, reject) => {
    const timer = setTimeout(() => { child.kill('SIGKILL'); reject(new Error(`no URL from iarap serve within ${timeoutMs} ms:\n${stderr}`)); }, timeoutMs);
    child.on('exit', (code) => { clearTimeout(timer); reject(new Error(`iarap serve exited with ${code}:\n${stderr}`)); });
    child.stdout.on('data', (chunk) => {
      stdout += chunk;
      const match = stdout.match(/http:\/\/127\.0\.0\.1:(\d+)\//);
      if (match) {
        clearTimeout(timer);
        resolve({ url: match[0], port: Number(match[1]), child, log: () => stderr });
      }
    });
  });
}

// SIGTERM, then waits for the exit (SIGKILL after 10 s); resolves the exit code.
export function stopServer(server) {
  return new Promise((resolve) => {
    if (server.child.exitCode !== null) { resolve(server.child.exitCode); return; }
    const timer = setTimeout(() => server.child.kill('SIGKILL'), 10000);
    server.child.removeAllListeners('exit');
    server.child.on('exit', (code, signal) => { clearTimeout(timer); resolve(code ?? signal); });
    server.child.kill('SIGTERM');
  });
}

// startServer, the base URL without its trailing slash beside it: {server, base}.
export async function startServerAt(args) {
  const server = await startServer(args);
  return { server, base: server.url.replace(/\/$/, '') };
}

// stopServer, and a clean exit (code 0) asserted, with the server's log otherwise.
export async function stopServerCleanly(server) {
  const code = await stopServer(server);
  if (code !== 0) throw new Error(`server exit: ${code}\n${server.log()}`);
}

// The binary frames of /api/solve and /api/intrinsic_edges, decoded as the page does.
export { decodeFrame } from '../../web/src/api.js';
