// View-dependent colour in the WebGL free view: its picture is compared with the server's
// render of the same camera (the reference rasteriser) on the demo scene with strong SH
// (the fixture's sh_scene: degrees 1-3 amplified; the plain demo scene's SH is too faint
// to tell). Then the same view is drawn with the SH capped at degree 0 (the base colour
// only): it must be clearly further from the server render, so the check fails when the
// SH is ignored or evaluated in another basis.
import { spawn } from 'node:child_process';

// Mean absolute RGB difference (0..1) between the WebGL picture (read back from the
// renderer) and the server's render of the camera the free view shows, and the PSNR (dB).
async function glVsServer(page) {
  return page.evaluate(async () => {
    const spec = JSON.parse(document.getElementById('frame').dataset.key.slice(1));
    const gl = window.__splatRenderer.snapshot();  // bottom row first
    const q = new URLSearchParams({ eye: spec.eye.join(','), target: spec.target.join(','), up: spec.up.join(','),
      fov: String(spec.fov), width: String(gl.width), height: String(gl.height), format: 'png', highlight: '0' });
    const bmp = await createImageBitmap(await (await fetch(`/api/render?${q}`)).blob());
    const c = new OffscreenCanvas(bmp.width, bmp.height);
    const g = c.getContext('2d');
    g.drawImage(bmp, 0, 0);
    const b = g.getImageData(0, 0, bmp.width, bmp.height);
    if (gl.width !== b.width || gl.height !== b.height) throw new Error(`sizes differ: ${gl.width}x${gl.height} vs ${b.width}x${b.height}`);
    let sum = 0, sq = 0;
    for (let y = 0; y < b.height; ++y)
      for (let x = 0; x < b.width; ++x) {
        const i = 4 * (y * b.width + x), j = 4 * ((b.height - 1 - y) * b.width + x);
        for (let k = 0; k < 3; ++k) { const d = Math.abs(gl.data[j + k] - b.data[i + k]) / 255; sum += d; sq += d * d; }
      }
    const n = 3 * b.width * b.height;
    return { mad: sum / n, psnr: -10 * Math.log10(sq / n), width: b.width, height: b.height };
  });
}

// Opens `url` in a new page, switches to the free camera (the orbit starts at the first
// training camera), waits for the full-quality still frame and compares it with the
// server render; then again with the SH capped at degree 0.
async function freeView(context, url, shots) {
  const page = await context.newPage();
  try {
    await page.goto(url);
    await page.waitForSelector('#view-img[data-rendered]', { timeout: 30000 });
    await page.click('#btn-orbit');
    await page.waitForSelector('#frame[data-key^="f"]');
    if (await page.getAttribute('body', 'data-renderer') !== 'webgl') return null;
    // Splats loaded, sorted and drawn in full (the caption names every splat, not moving).
    const still = () => page.waitForFunction(() => /WebGL · [\d,]+ of [\d,]+ splats/.test(document.getElementById('view-caption').textContent) &&
      !/moving/.test(document.getElementById('view-caption').textContent), null, { timeout: 60000 });
    await still();
    await page.waitForTimeout(1000);
    await page.screenshot({ path: `${shots}/01b-webgl-sh.png` });
    const withSh = await glVsServer(page);
    // Base colour only: wait for a sort made after the cap.
    const sorts = await page.evaluate(() => { const R = window.__splatRenderer; R.setMaxShDegree(0); return R.stats.sorts; });
    await page.waitForFunction((n) => window.__splatRenderer.stats.sorts > n, sorts, { timeout: 30000 });
    await page.waitForTimeout(500);
    await page.screenshot({ path: `${shots}/01c-webgl-no-sh.png` });
    return { withSh, baseOnly: await glVsServer(page) };
  } finally {
    await page.close();
  }
}

// Serves `scene` (no segmentation) with `bin` for the two pages, then stops it.
export async function viewDependentColourChecks({ context, bin, scene, outDir, shots, check, log }) {
  const server = spawn(bin, ['serve', scene, '--host', '127.0.0.1', '--port', '0', '--no-segmentation', '--out-dir', outDir,
    '--max-seconds', '120'], { stdio: ['ignore', 'pipe', 'pipe'] });
  try {
    let text = '';
    const url = await new Promise((resolve, reject) => {
      const timer = setTimeout(() => reject(new Error(`SH scene server did not start:\n${text}`)), 30000);
      const onData = (d) => {
        text += d.toString();
        const m = text.match(/listening on (http:\/\/127\.0\.0\.1:\d+\/)/);
        if (m) { clearTimeout(timer); resolve(m[1]); }
      };
      server.stdout.on('data', onData);
      server.stderr.on('data', onData);
    });
    const r = await freeView(context, url, shots);
    if (!r) { log('WARNING: no WebGL2: the view-dependent colour check is skipped'); return; }
    const { withSh, baseOnly } = r;
    log(`WebGL vs server render ${withSh.width}x${withSh.height}: with SH mean |diff| ${withSh.mad.toFixed(4)} ` +
      `(PSNR ${withSh.psnr.toFixed(1)} dB), base colour only ${baseOnly.mad.toFixed(4)} (PSNR ${baseOnly.psnr.toFixed(1)} dB)`);
    check(withSh.mad < 0.006, `the WebGL free view matches the server render with SH (mean |diff| ${withSh.mad.toFixed(4)} < 0.006)`);
    check(baseOnly.mad > 3 * withSh.mad,
      `without the SH rest the WebGL view is clearly further from the server render (${baseOnly.mad.toFixed(4)} > 3 x ${withSh.mad.toFixed(4)})`);
  } finally {
    server.kill('SIGTERM');
  }
}
