// Debian's chromium, headless, driven by playwright-core, for the browser tests: the launch (exit 77, CTest's
// "skipped", without chromium, playwright-core or three) and the viewer's page helpers they share.
import { createRequire } from 'node:module';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { startServer, stopServer, webDir } from './server.mjs';

const chromiumPath = process.env.IARAP_CHROMIUM ?? '/usr/bin/chromium';

export function skip(reason) {
  console.log(`SKIP: ${reason}`);
  process.exit(77);
}

// {browser, userDataDir}: a fresh profile (playwright passes it as --user-data-dir); WebGL through
// SwiftShader, no GPU.
export async function launchBrowser() {
  if (!fs.existsSync(chromiumPath)) skip(`no ${chromiumPath} (apt-get install chromium)`);
  let chromium;
  try {
    ({ chromium } = createRequire(path.join(webDir, 'package.json'))('playwright-core'));
  } catch {
    skip('playwright-core is not installed (npm ci --prefix web)');
  }
  if (!fs.existsSync(path.join(webDir, 'node_modules/three/build/three.module.js'))) skip('three is not installed (npm ci --prefix web)');
  const userDataDir = fs.mkdtempSync(path.join(os.tmpdir(), 'iarap-chromium-'));
  const browser = await chromium.launchPersistentContext(userDataDir, {
    executablePath: chromiumPath,
    headless: true,
    viewport: { width: 1280, height: 800 },
    args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
      '--disable-component-update', '--disable-sync', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
  });
  return { browser, userDataDir };
}

// The page's test hooks (window.iarapViewer) and the pointer gestures the tests make.
export function viewerPage(page) {
  const idle = () => page.evaluate(() => window.iarapViewer.idle());
  const viewer = (name, ...rest) => page.evaluate(([n, r]) => window.iarapViewer[n](...r), [name, rest]);
  const settle = async () => {
    await page.waitForTimeout(100);
    await idle();
  };
  // Paints `paint` (fixed or handle) over the screen band [fromFraction, toFraction] of the mesh's height.
  const boxSelect = async (paint, fromFraction, toFraction, view = 0) => {
    await page.check('input[name=tool][value=box]');
    await page.check(`input[name=paint][value=${paint}]`);
    const b = await viewer('meshScreenBox', view);
    const y0 = b.y0 + fromFraction * (b.y1 - b.y0);
    const y1 = b.y0 + toFraction * (b.y1 - b.y0);
    await page.mouse.move(b.x0 - 5, y0);
    await page.mouse.down();
    await page.mouse.move((b.x0 + b.x1) / 2, (y0 + y1) / 2, { steps: 4 });
    await page.mouse.move(b.x1 + 5, y1, { steps: 4 });
    await page.mouse.up();
    await settle();
  };
  const dragGizmo = async (view, dx, steps = 12) => {
    await page.check('input[name=tool][value=orbit]');
    const g = await viewer('gizmoXArrowScreenPoint', view);
    await page.mouse.move(g.x, g.y);
    await page.mouse.down();
    for (let k = 1; k <= steps; ++k) {
      await page.mouse.move(g.x + (dx * k) / steps, g.y);
      await page.waitForTimeout(30);
    }
    await page.mouse.up();
    await settle();
  };
  return { idle, viewer, settle, boxSelect, dragGizmo };
}

// Starts `iarap serve serverArgs`, opens its page in the browser and waits until the viewer is ready, then
// runs body({page, server, problems, userDataDir}); problems collects the page's console errors, uncaught
// errors and (with failedRequests) failed requests. On a throw it prints the error, the problems and the
// server's log. Stops everything and exits: 0 when body returned, 1 when it threw.
export async function runBrowserSession(serverArgs, body, { failedRequests = true } = {}) {
  const { browser, userDataDir } = await launchBrowser();
  let server;
  try {
    server = await startServer(serverArgs);
  } catch (error) {
    await browser.close();
    throw error;
  }
  const problems = [];
  let failed = false;
  try {
    const page = browser.pages()[0] ?? (await browser.newPage());
    page.on('console', (message) => { if (message.type() === 'error') problems.push(`console: ${message.text()}`); });
    page.on('pageerror', (error) => problems.push(`page error: ${error.message}`));
    if (failedRequests) page.on('requestfailed', (request) => problems.push(`request failed: ${request.url()}`));
    // Generous limits: under CTest -j2 on two cores the browser shares them with the other tests.
    const loadStart = performance.now();
    await page.goto(server.url, { timeout: 120000 });
    await page.waitForFunction(() => window.iarapViewer?.ready === true, null, { timeout: 120000 });
    console.log(`page ready in ${(performance.now() - loadStart).toFixed(0)} ms`);
    await body({ page, server, problems, userDataDir });
  } catch (error) {
    failed = true;
    console.error(error);
    console.error(problems.join('\n'));
    console.error(server.log());
  } finally {
    await browser.close();
    await stopServer(server);
    fs.rmSync(userDataDir, { recursive: true, force: true });
  }
  process.exit(failed ? 1 : 0);
}
