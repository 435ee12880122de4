// E2E steps of the selection tools and the export formats (called from e2e.mjs on the
// page it has open): a rectangle, a lasso added with Shift, a brush stroke subtracted
// with Ctrl, undo/redo of the brush, and downloads in two more formats (SPZ and
// compressed PLY) whose Gaussian counts are checked from their headers.
import fs from 'node:fs';
import path from 'node:path';

function plyVertexCount(file) {
  const head = fs.readFileSync(file).subarray(0, 4096).toString('latin1');
  const m = head.match(/element vertex (\d+)/);
  if (!head.startsWith('ply') || !m) throw new Error(`${file} is not a PLY`);
  return Number(m[1]);
}

// SPZ v4: a plain header "NGSP", version, Gaussian count (little-endian uint32s).
function spzCount(file) {
  const b = fs.readFileSync(file);
  if (b.length < 32 || b.toString('latin1', 0, 4) !== 'NGSP') throw new Error(`${file} is not an SPZ v4 file`);
  return b.readUInt32LE(8);
}

const selectedOf = async (page) => Number(await page.getAttribute('body', 'data-selected'));

export async function selectionToolSteps({ page, fx, work, shots, check, log }) {
  await page.keyboard.press('Escape');  // clear the selection (a history step)
  await page.waitForFunction(() => (document.querySelector('#history-list li.current') || {}).textContent?.includes('clear selection'),
    null, { timeout: 20000 });
  await page.waitForSelector('body[data-selected="0"][data-busy="false"]', { timeout: 20000 });
  const steps0 = Number(await page.getAttribute('body', 'data-history-steps'));
  const frame = await (await page.$('#frame')).boundingBox();
  const at = (fx_, fy_) => [frame.x + fx_ * frame.width, frame.y + fy_ * frame.height];
  const [bx0, by0, bx1, by1] = fx.bbox;  // the object's box in the view, as fractions
  const mx = (bx0 + bx1) / 2;

  // Rectangle over the object's left half.
  await page.keyboard.press('r');
  check(await page.getAttribute('body', 'data-tool') === 'rect', 'R picks the rectangle tool');
  await page.mouse.move(...at(bx0 - 0.02, by0 - 0.02));
  await page.mouse.down();
  await page.mouse.move(...at(mx, by1 + 0.02), { steps: 6 });
  await page.screenshot({ path: path.join(shots, '06a-rect-drawing.png') });
  await page.mouse.up();
  await page.waitForFunction(() => Number(document.body.dataset.selected) > 0, null, { timeout: 20000 });
  const nRect = await selectedOf(page);
  await page.waitForTimeout(600);
  await page.screenshot({ path: path.join(shots, '06b-rect-selected.png') });
  check(nRect > 0 && nRect < fx.total_gaussians / 2, `a rectangle selects the Gaussians under it (${nRect})`);

  // Lasso (Shift: add) around the object's right half.
  await page.keyboard.press('l');
  await page.keyboard.down('Shift');
  const lasso = [[mx, by0 - 0.02], [bx1 + 0.02, by0 - 0.02], [bx1 + 0.04, (by0 + by1) / 2], [bx1 + 0.02, by1 + 0.02], [mx, by1 + 0.02]];
  await page.mouse.move(...at(...lasso[0]));
  await page.mouse.down();
  for (const p of lasso.slice(1)) await page.mouse.move(...at(...p), { steps: 4 });
  await page.mouse.up();
  await page.keyboard.up('Shift');
  await page.waitForFunction((n) => Number(document.body.dataset.selected) > n, nRect, { timeout: 20000 });
  const nLasso = await selectedOf(page);
  await page.waitForTimeout(600);
  await page.screenshot({ path: path.join(shots, '06c-lasso-added.png') });
  check(nLasso > nRect, `a lasso with Shift adds to the selection (${nRect} -> ${nLasso})`);

  // Brush (Ctrl: subtract) across the middle.
  await page.keyboard.press('b');
  await page.keyboard.down('Control');
  await page.mouse.move(...at(bx0, (by0 + by1) / 2));
  await page.mouse.down();
  await page.mouse.move(...at(bx1, (by0 + by1) / 2), { steps: 10 });
  await page.screenshot({ path: path.join(shots, '06d-brush-drawing.png') });
  await page.mouse.up();
  await page.keyboard.up('Control');
  await page.waitForFunction((n) => Number(document.body.dataset.selected) < n, nLasso, { timeout: 20000 });
  const nBrush = await selectedOf(page);
  await page.waitForTimeout(600);
  await page.screenshot({ path: path.join(shots, '06e-brush-subtracted.png') });
  check(nBrush > 0 && nBrush < nLasso, `a brush stroke with Ctrl subtracts (${nLasso} -> ${nBrush})`);
  const steps = Number(await page.getAttribute('body', 'data-history-steps'));
  check(steps === steps0 + 3, `each tool is one history step (${steps0} -> ${steps})`);

  // Undo / redo of the tool selection.
  await page.keyboard.press('Control+z');
  await page.waitForSelector(`body[data-selected="${nLasso}"]`, { timeout: 20000 });
  await page.keyboard.press('Control+Shift+z');
  await page.waitForSelector(`body[data-selected="${nBrush}"]`, { timeout: 20000 });
  check(true, 'Ctrl+Z / Ctrl+Shift+Z undo and redo the brush selection');
  await page.keyboard.press('q');

  // Export in two more formats, chosen in the page.
  const gaussians = Number(await page.getAttribute('body', 'data-gaussians'));
  for (const [ext, count] of [['spz', spzCount], ['compressed.ply', plyVertexCount]]) {
    await page.selectOption('#export-format', ext);
    const [dl] = await Promise.all([page.waitForEvent('download'), page.click('#btn-download')]);
    const file = path.join(work, `downloaded.${ext}`);
    await dl.saveAs(file);
    const n = count(file);
    check(n === gaussians, `downloaded ${ext} holds the scene's ${gaussians} Gaussians (${n})`);
  }
  check(await page.inputValue('#export-path') === 'e2e/edited.compressed.ply', 'the server path follows the chosen format');
  log('selection tools and exports done');
}
