// Where the time of an orbiting free camera goes (a profiling aid, not a test): serves a
// scene (default the fern fixture), drags in circles like bench_orbit.mjs with Chrome
// tracing on, and prints per process/thread the busy time of top-level trace events and
// the page's own counters (sort time in the worker, frames).
//   node tests/e2e/profile_orbit.mjs [scene] [--query ?full] [--seconds S] [--trace out.json] [--eval JS]
import { spawn } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const root = path.join(here, '..', '..');
const args = process.argv.slice(2);
const opt = (name, def) => { const i = args.indexOf(name); return i >= 0 ? args.splice(i, 2)[1] : def; };
const seconds = Number(opt('--seconds', 4)), query = opt('--query', ''), traceOut = opt('--trace', '');
const setup = opt('--eval', '');  // run in the page before the drags (experiments)
const scene = args[0] || path.join(root, '..', 'shared', 'fixtures', 'fern', 'scene');
const bin = process.env.ISEGMAN_BIN || path.join(root, 'build', 'isegman');
const { chromium } = await import('playwright-core');
const server = spawn(bin, ['serve', scene, '--port', '0', '--no-segmentation', '--out-dir', '/tmp/isegman-bench-out', '--max-seconds', '300']);
let serverLog = '';
const url = await new Promise((resolve) => {
  const on = (d) => { serverLog += d; const m = serverLog.match(/listening on (http:\S+)/); if (m) resolve(m[1]); };
  server.stdout.on('data', on); server.stderr.on('data', on);
});
const browser = await chromium.launch({ executablePath: '/usr/bin/chromium',
  args: ['--no-sandbox', '--enable-unsafe-swiftshader', '--use-angle=swiftshader', '--ignore-gpu-blocklist'] });
try {
  const page = await browser.newPage({ viewport: { width: 1366, height: 768 } });
  await page.goto(`${url}${query}`);
  await page.addStyleTag({ content: '.stage { flex: none !important; width: 964px !important; height: 544px !important; }' });
  await page.click('#btn-orbit');
  await page.waitForTimeout(4000);
  if (setup) await page.evaluate(setup);
  const box = await (await page.$('#frame')).boundingBox();
  const drag = (secs) => page.evaluate(async ({ cx, cy, seconds }) => {
    const el = document.getElementById('frame');
    const ev = (type, x, y) => el.dispatchEvent(new PointerEvent(type, { clientX: x, clientY: y, pointerId: 1, button: 0, buttons: 1, bubbles: true }));
    ev('pointerdown', cx, cy);
    const t0 = performance.now();
    const f0 = Number(el.dataset.rendered || 0);
    await new Promise((done) => {
      const timer = setInterval(() => {
        const t = (performance.now() - t0) / 1000;
        ev('pointermove', cx + 150 * Math.sin(2 * t), cy + 40 * Math.sin(4 * t));
        if (t > seconds) { clearInterval(timer); done(); }
      }, 8);
    });
    const ms = performance.now() - t0, frames = Number(el.dataset.rendered || 0) - f0;
    ev('pointerup', cx, cy);
    return { fps: (1000 * frames) / ms, caption: document.getElementById('view-caption').textContent,
      stats: window.__splatRenderer ? window.__splatRenderer.stats : null };
  }, { cx: box.x + box.width / 2, cy: box.y + box.height / 2, seconds: secs });
  await drag(3);
  await page.waitForTimeout(1500);
  const cdp = await page.context().newCDPSession(page);
  const events = [];
  cdp.on('Tracing.dataCollected', (e) => events.push(...e.value));
  const done = new Promise((r) => cdp.once('Tracing.tracingComplete', r));
  await cdp.send('Tracing.start', { categories: 'toplevel,disabled-by-default-devtools.timeline,gpu,viz,blink,v8,benchmark,cc', transferMode: 'ReportEvents' });
  const r = await drag(seconds);
  await cdp.send('Tracing.end');
  await done;
  console.log(`${query || '(adaptive)'}: ${r.fps.toFixed(1)} frames/s; ${r.caption}`);
  if (r.stats) console.log('page counters:', JSON.stringify(r.stats));
  // Frames the display compositor presented (a frame drawn but never swapped is not seen).
  const swaps = events.filter((e) => e.name === 'SkiaOutputSurfaceImplOnGpu::SwapBuffers' && e.ph === 'X').length;
  console.log(`presented: ${(swaps / seconds).toFixed(1)} frames/s (display compositor swaps)`);
  if (traceOut) fs.writeFileSync(traceOut, JSON.stringify(events));
  // Busy time per thread: top-level complete events (ph X) on each thread, nested ones not double counted.
  const names = {}, pnames = {};
  for (const e of events) {
    if (e.ph === 'M' && e.name === 'thread_name') names[`${e.pid}:${e.tid}`] = e.args.name;
    if (e.ph === 'M' && e.name === 'process_name') pnames[e.pid] = e.args.name;
  }
  const busy = {}, top = {};
  const byThread = {};
  for (const e of events) if (e.ph === 'X' && e.dur) (byThread[`${e.pid}:${e.tid}`] ||= []).push(e);
  for (const [k, list] of Object.entries(byThread)) {
    list.sort((a, b) => a.ts - b.ts || b.dur - a.dur);
    let end = -1;
    for (const e of list) {
      if (e.ts >= end) { busy[k] = (busy[k] || 0) + e.dur; end = e.ts + e.dur; (top[k] ||= {})[e.name] = (top[k][e.name] || 0) + e.dur; }
    }
  }
  const rows = Object.entries(busy).sort((a, b) => b[1] - a[1]).slice(0, 12);
  for (const [k, us] of rows) {
    const pid = k.split(':')[0];
    const best = Object.entries(top[k]).sort((a, b) => b[1] - a[1]).slice(0, 4).map(([n, d]) => `${n} ${(d / 1000 / seconds).toFixed(0)}`).join(', ');
    console.log(`${(pnames[pid] || pid).padEnd(16)} ${(names[k] || k).padEnd(24)} ${(us / 1000 / seconds).toFixed(0).padStart(5)} ms/s  [${best}]`);
  }
} finally {
  await browser.close();
  server.kill();
}
