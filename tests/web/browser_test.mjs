// Browser test of the viewer: Debian's chromium, headless, driven by playwright-core. Opens the page on the
// bunny, box-selects a handle (top) and a fixed region (bottom), drags the gizmo, and checks that the
// displayed positions changed, that fixed vertices did not move, that the page logged no error, and that
// the screenshot (a test artefact) is not blank. Exit 77 (CTest: skipped) without chromium or playwright-core.
// Usage: node tests/web/browser_test.mjs [--screenshot PATH] [--side-by-side]
import assert from 'node:assert/strict';
import fs from 'node:fs';
import { createRequire } from 'node:module';
import os from 'node:os';
import path from 'node:path';
import { repoRoot, startServer, stopServer, webDir } from './server.mjs';

const chromiumPath = process.env.IARAP_CHROMIUM ?? '/usr/bin/chromium';
const args = process.argv.slice(2);
const screenshotArg = args.includes('--screenshot') ? args[args.indexOf('--screenshot') + 1] : null;
const artefactDir = process.env.IARAP_WEB_ARTEFACTS ?? path.join(os.tmpdir(), 'iarap-web-artefacts');

function skip(reason) {
  console.log(`SKIP: ${reason}`);
  process.exit(77);
}

if (!fs.existsSync(chromiumPath)) skip(`no ${chromiumPath} (apt-get install chromium)`);
let chromium;
try {
  ({ chromium } = createRequire(path.join(webDir, 'package.json'))('playwright-core'));
} catch {
  skip('playwright-core is not installed (npm ci --prefix web)');
}
if (!fs.existsSync(path.join(webDir, 'node_modules/three/build/three.module.js'))) skip('three is not installed (npm ci --prefix web)');

const userDataDir = fs.mkdtempSync(path.join(os.tmpdir(), 'iarap-chromium-'));
// A fresh profile (playwright passes it as --user-data-dir); WebGL through SwiftShader, no GPU.
const browser = await chromium.launchPersistentContext(userDataDir, {
  executablePath: chromiumPath,
  headless: true,
  viewport: { width: 1280, height: 800 },
  args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
    '--disable-component-update', '--disable-sync', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
});
let server;
try {
  server = await startServer([path.join(repoRoot, 'data', 'bunny.off')]);
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
  page.on('requestfailed', (request) => problems.push(`request failed: ${request.url()}`));
  await page.goto(server.url);
  await page.waitForFunction(() => window.iarapViewer?.ready === true, null, { timeout: 60000 });

  const idle = () => page.evaluate(() => window.iarapViewer.idle());
  const boxSelect = async (paint, fromFraction, toFraction) => {
    await page.check('input[name=tool][value=box]');
    await page.check(`input[name=paint][value=${paint}]`);
    const b = await page.evaluate(() => window.iarapViewer.meshScreenBox());
    const y0 = b.y0 + fromFraction * (b.y1 - b.y0);
    const y1 = b.y0 + toFraction * (b.y1 - b.y0);
    await page.mouse.move(b.x0 - 5, y0);
    await page.mouse.down();
    await page.mouse.move((b.x0 + b.x1) / 2, (y0 + y1) / 2, { steps: 4 });
    await page.mouse.move(b.x1 + 5, y1, { steps: 4 });
    await page.mouse.up();
    await page.waitForTimeout(100);
    await idle();
  };
  await boxSelect('handle', -0.02, 0.22); // screen y grows downwards: the top (ears)
  await boxSelect('fixed', 0.85, 1.02);
  if (args.includes('--side-by-side')) {
    await page.check('#side-by-side');
    await page.waitForTimeout(300);
    await idle();
  }
  const labels = await page.evaluate(() => window.iarapViewer.labels());
  const fixed = labels.flatMap((l, i) => (l === 1 ? [i] : []));
  const handle = labels.flatMap((l, i) => (l === 2 ? [i] : []));
  assert.ok(fixed.length > 10 && handle.length > 10, `selection: ${fixed.length} fixed, ${handle.length} handle`);

  await page.check('input[name=tool][value=orbit]');
  const before = await page.evaluate(() => window.iarapViewer.displayedPositions());
  const solvesBefore = await page.evaluate(() => window.iarapViewer.solves());
  const g = await page.evaluate(() => window.iarapViewer.gizmoXArrowScreenPoint());
  await page.mouse.move(g.x, g.y);
  await page.mouse.down();
  for (let k = 1; k <= 12; ++k) {
    await page.mouse.move(g.x + 8 * k, g.y);
    await page.waitForTimeout(30);
  }
  await page.mouse.up();
  await page.waitForTimeout(100);
  await idle();
  await page.check('#show-intrinsic');
  await page.check('#show-energy');
  await page.waitForTimeout(300);
  await idle();
  await page.waitForTimeout(300);
  const after = await page.evaluate(() => window.iarapViewer.displayedPositions());
  const solvesAfter = await page.evaluate(() => window.iarapViewer.solves());

  let lo = Infinity, hi = -Infinity;
  for (let i = 1; i < before.length; i += 3) { lo = Math.min(lo, before[i]); hi = Math.max(hi, before[i]); }
  const height = hi - lo;
  const moved = (i) => Math.hypot(after[3 * i] - before[3 * i], after[3 * i + 1] - before[3 * i + 1], after[3 * i + 2] - before[3 * i + 2]);
  const handleMove = Math.max(...handle.map(moved));
  const fixedMove = Math.max(...fixed.map(moved));
  const centroid = (X) => [0, 1, 2].map((k) => handle.reduce((s, i) => s + X[3 * i + k], 0) / handle.length);
  console.log(`handle centroid ${centroid(before).map((v) => v.toFixed(3))} -> ${centroid(after).map((v) => v.toFixed(3))}, mesh height ${height.toFixed(3)}`);
  console.log(`solves during the drag: ${solvesAfter - solvesBefore}; largest handle move ${(handleMove / height).toFixed(3)} x height; largest fixed move ${fixedMove}`);
  assert.ok(solvesAfter > solvesBefore, 'dragging the gizmo ran no solve');
  assert.ok(handleMove > 0.05 * height, `handle moved only ${handleMove} (mesh height ${height})`);
  // Fixed rows are set to their targets exactly; float32 display rounds at ~6e-8 relative.
  assert.ok(fixedMove <= 1e-6 * height, `fixed vertices moved by ${fixedMove}`);
  assert.equal(await page.evaluate(() => window.iarapViewer.errors()), 0, await page.textContent('#status'));

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
  // Reset brings the displayed shape back to the rest positions (which the fixed vertices never left).
  const rest = await page.evaluate(async () => Array.from(new Float32Array(await (await fetch('/api/positions?method=rest')).arrayBuffer())));
  await page.click('#reset');
  await page.waitForFunction(([X, tol]) => window.iarapViewer.displayedPositions().every((v, i) => Math.abs(v - X[i]) <= tol),
    [rest, 1e-6 * height], { timeout: 20000, polling: 200 });
  assert.deepEqual(problems, []);
  console.log('browser test: 1 passed, 0 failed');
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
