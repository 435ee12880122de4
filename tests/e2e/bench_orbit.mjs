// Frame rate of the web app's free camera while orbiting (a benchmark, not a test): serves
// a scene (default: the fern fixture), opens the page in headless Chromium at 1366x768
// with the view sized to 960x540, drags the mouse in circles for a few seconds and prints
// frames per second (after a 3 s warm-up drag) for the WebGL view (lower resolution and a
// subset of the splats while moving, adapted to the frame rate), the WebGL view drawing
// every splat at full resolution (?full) and the server-render fallback (?nogl).
// Chromium here has no GPU: WebGL2 runs on SwiftShader (software).
//   node tests/e2e/bench_orbit.mjs [scene] [--seconds S] [--only webgl|full|server] [--shots DIR]
// --shots saves the view half way through the measured drag and once still again.
// ISEGMAN_BIN (default build/isegman) names the binary.
import { spawn } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const root = path.join(here, '..', '..');
const args = process.argv.slice(2);
const secIdx = args.indexOf('--seconds');
const seconds = secIdx >= 0 ? Number(args.splice(secIdx, 2)[1]) : 6;
const onlyIdx = args.indexOf('--only');  // one row: webgl, full or server (repeated A/B runs)
const only = onlyIdx >= 0 ? args.splice(onlyIdx, 2)[1] : null;
const shotsIdx = args.indexOf('--shots');  // screenshots of the view while moving and still
const shots = shotsIdx >= 0 ? args.splice(shotsIdx, 2)[1] : null;
if (shots) fs.mkdirSync(shots, { recursive: true });
const scene = args[0] || path.join(root, '..', 'shared', 'fixtures', 'fern', 'scene');
const bin = process.env.ISEGMAN_BIN || path.join(root, 'build', 'isegman');
const CHROMIUM = '/usr/bin/chromium';
for (const [p, what] of [[scene, 'scene'], [bin, 'isegman binary'], [CHROMIUM, 'chromium']])
  if (!fs.existsSync(p)) { console.log(`SKIPPED: ${what} not found: ${p}`); process.exit(77); }
const { chromium } = await import('playwright-core');

const server = spawn(bin, ['serve', scene, '--port', '0', '--no-segmentation', '--out-dir', '/tmp/isegman-bench-out', '--max-seconds', '300']);
let serverLog = '';
const url = await new Promise((resolve, reject) => {
  const on = (d) => { serverLog += d; const m = serverLog.match(/listening on (http:\S+)/); if (m) resolve(m[1]); };
  server.stdout.on('data', on); server.stderr.on('data', on);
  server.on('exit', (c) => reject(new Error(`server exited (${c}): ${serverLog}`)));
});
// SwiftShader for WebGL (the machine has no GPU).
const browser = await chromium.launch({ executablePath: CHROMIUM,
  args: ['--no-sandbox', '--enable-unsafe-swiftshader', '--use-angle=swiftshader', '--ignore-gpu-blocklist'] });

async function measure(query, name) {
  const page = await browser.newPage({ viewport: { width: 1366, height: 768 } });
  await page.goto(`${url}${query}`);
  await page.addStyleTag({ content: '.stage { flex: none !important; width: 964px !important; height: 544px !important; }' });
  await page.click('#btn-orbit');
  const gl = await page.getAttribute('body', 'data-renderer') === 'webgl';
  // Let the splats load and the first full frame draw.
  await page.waitForTimeout(gl ? 4000 : 1500);
  const size = await page.$eval('#frame', (f) => `${f.clientWidth}x${f.clientHeight}`);
  const box = await (await page.$('#frame')).boundingBox();
  const count = () => page.evaluate(() => (document.body.dataset.renderer === 'webgl'
    ? Number(document.getElementById('frame').dataset.rendered || 0)
    : Number(document.getElementById('view-img').dataset.loads || 0)));
  // The drag is driven inside the page (pointer events every 8 ms, like a 125 Hz mouse),
  // so the input rate does not depend on the automation protocol's round trips. A first
  // drag (not counted) lets the WebGL view settle its quality step, as a user's first drag does.
  const drag = (secs) => page.evaluate(async ({ cx, cy, seconds }) => {
    const el = document.getElementById('frame');
    const ev = (type, x, y) => el.dispatchEvent(new PointerEvent(type, { clientX: x, clientY: y, pointerId: 1, button: 0, buttons: 1, bubbles: true }));
    ev('pointerdown', cx, cy);
    const t0 = performance.now(), caption = [];
    await new Promise((done) => {
      const timer = setInterval(() => {
        const t = (performance.now() - t0) / 1000;
        ev('pointermove', cx + 150 * Math.sin(2 * t), cy + 40 * Math.sin(4 * t));
        if (Math.random() < 0.05) caption.push(document.getElementById('view-caption').textContent);
        if (t > seconds) { clearInterval(timer); done(); }
      }, 8);
    });
    const ms = performance.now() - t0;
    ev('pointerup', cx, cy);
    return { caption, ms };
  }, { cx: box.x + box.width / 2, cy: box.y + box.height / 2, seconds: secs });
  await drag(3);
  await page.waitForTimeout(gl ? 2000 : 500);
  const f0 = await count();
  const measured = drag(seconds);
  if (shots) {
    await page.waitForTimeout((seconds * 1000) / 2);
    await (await page.$('#frame')).screenshot({ path: path.join(shots, `${name}-moving.png`) });
  }
  const { caption, ms } = await measured;
  const f1 = await count();
  if (shots) {
    await page.waitForTimeout(gl ? 4000 : 2000);
    await (await page.$('#frame')).screenshot({ path: path.join(shots, `${name}-still.png`) });
  }
  await page.close();
  const drawn = caption.map((c) => c.match(/([\d,]+) of [\d,]+ splats · (\d+)×(\d+)/)).filter(Boolean)
    .map((m) => [Number(m[1].replace(/,/g, '')), Number(m[2]) * Number(m[3])]);
  const mean = (k) => drawn.reduce((a, d) => a + d[k], 0) / drawn.length;
  return { fps: (f1 - f0) / (ms / 1000), size,
    drawn: drawn.length ? `; while moving, on average ${Math.round(mean(0)).toLocaleString()} splats at ${Math.round(mean(1)).toLocaleString()} pixels` : '' };
}

try {
  const rows = [['WebGL, subset while moving', '', 'webgl'], ['WebGL, every splat', '?full', 'full'], ['server renders (fallback)', '?nogl', 'server']]
    .filter((r) => !only || r[2] === only);
  const load = () => os.loadavg().map((v) => v.toFixed(1)).join(' ');
  console.log(`scene ${scene}, ${seconds} s of orbiting each; CPU ${os.cpus()[0].model} x${os.cpus().length}, load average ${load()}`);
  for (const [name, q, key] of rows) {
    const r = await measure(q, key);
    console.log(`${name.padEnd(28)} ${r.fps.toFixed(1).padStart(6)} frames/s  view ${r.size}` +
      r.drawn + `  (load ${load()})`);
  }
} finally {
  await browser.close();
  server.kill();
}
