// isegman web app: wires the view, the evidence strip and the panel to the server and
// keeps them in sync with /api/status.
import * as api from './api.js';
import { Viewer } from './viewer.js';
import { Strip } from './strip.js';
import { Panels } from './panels.js';
import { SelectionTools } from './tools.js';
import { Files } from './files.js';
import { bindDisplay } from './display_controls.js';
import { initLayout } from './layout.js';

const $ = (id) => document.getElementById(id);
let scene = null, viewer = null, strip = null, panels = null, display = null;
let status = null, lastRevision = -1, lastLogSeq = 0, pollTimer = null;
let marks = [], redoMarks = [];
let toastTimer = null;

// The marks drawn: a granularity step (Larger / Smaller) keeps a placeholder in `marks`, so
// the marks stay in step with the segmentation's log, but draws nothing.
function showMarks(list = marks) { viewer.setMarks(list.filter((m) => !m.granularity)); }

function toast(text, ok = false) {
  const t = $('toast');
  t.textContent = text;
  t.className = `toast${ok ? ' ok' : ''}`;
  clearTimeout(toastTimer);
  toastTimer = setTimeout(() => t.classList.add('hidden'), ok ? 3000 : 7000);
}
function showError(message) { toast(message); document.body.dataset.lastError = message; }

async function run(fn) {
  try {
    const msg = await fn();
    if (typeof msg === 'string') toast(msg, true);
  } catch (e) {
    showError(e.message || String(e));
  } finally {
    poll();
  }
}

async function runJob(what, start, kind) {
  try {
    const { job } = await start();
    poll();
    await api.waitJob(job);
    if (kind === 'undo') { const m = marks.pop(); if (m) redoMarks.push(m); }
    if (kind === 'redo') { const m = redoMarks.pop(); if (m) marks.push(m); }
    showMarks();
    return true;
  } catch (e) {
    showError(`${what}: ${e.message || e}`);
    return false;
  } finally {
    poll();
  }
}

// A click goes to the server as the one click type (core/click.h): continuous pixel
// coordinates of the camera's full-size image, pixel (i, j) covering [i, i+1) x [j, j+1).
// `target.x, target.y` are the fractions of the shown image (any render size).
async function click(target) {
  const cam = target.view !== undefined ? scene.cameras[target.view] : target.camera;
  const body = { x: target.x * cam.width, y: target.y * cam.height, label: target.label };
  if (target.view !== undefined) body.view = target.view; else body.camera = target.camera;
  const mark = { key: target.key, x: target.x, y: target.y, label: target.label };
  const redoBefore = redoMarks;
  marks.push(mark); redoMarks = [];
  showMarks();
  const ok = await runJob('segmenting', () => api.post('/api/click', body));
  if (!ok) { marks = marks.filter((m) => m !== mark); showMarks(); return; }
  // The same click again is no click (the server logs it and changes nothing): its mark
  // goes, and the redo marks stay, as the server's redo does.
  const st = await api.get('/api/status').catch(() => null);
  if (st && !st.busy && st.segmentation && st.segmentation.clicks < marks.length && marks[marks.length - 1] === mark) {
    marks.pop();
    redoMarks = redoBefore;
    showMarks();
  }
}

// The last click's mask one step larger or smaller among SAM's answers at it: one click
// cannot tell a part (a pot) from the whole it belongs to (the potted plant).
async function granularity(step) {
  if (!status || status.segmentation.clicks === 0) {
    showError('Click an object first: Larger and Smaller change the last click\'s mask');
    return;
  }
  const mark = { granularity: step };
  marks.push(mark); redoMarks = [];
  const ok = await runJob(step > 0 ? 'larger mask' : 'smaller mask', () => api.post('/api/click/granularity', { step }));
  if (!ok) marks = marks.filter((m) => m !== mark);
}

// The history walked over a click: its mark goes (undo) or comes back (redo) at once; the
// job brings the segmentation's evidence in line.
function clickWalked(dir, job) {
  if (dir === 'undo') { const m = marks.pop(); if (m) redoMarks.push(m); }
  else { const m = redoMarks.pop(); if (m) marks.push(m); }
  showMarks();
  if (job) api.waitJob(job).catch((e) => showError(`${dir} click: ${e.message || e}`)).finally(() => poll());
}

function setBanner(kind, text, progress) {
  const b = $('banner');
  if (!kind) { b.classList.add('hidden'); return; }
  b.className = `banner ${kind}`;
  $('banner-text').textContent = text;
  const bar = $('banner-bar');
  bar.parentElement.style.display = progress === undefined ? 'none' : '';
  if (progress !== undefined) bar.style.width = `${Math.round(progress * 100)}%`;
}

function render(s) {
  const seg = s.segmentation, ed = s.edit, job = s.job;
  document.body.dataset.seg = seg.state;
  document.body.dataset.busy = String(s.busy);
  document.body.dataset.selected = String(ed.selected);
  document.body.dataset.gaussians = String(ed.gaussians);
  document.body.dataset.clicks = String(seg.clicks);
  $('scene-stats').textContent = `${ed.gaussians.toLocaleString()} Gaussians · ${scene.cameras.length} cameras`;
  $('click-count').textContent = seg.clicks - (seg.steps || 0);  // Larger / Smaller steps are not clicks
  $('selected-count').textContent = ed.selected.toLocaleString();
  const tag = $('seg-state');
  tag.textContent = seg.stale ? 'scene edited' : seg.state;
  tag.className = `tag ${seg.state}`;
  tag.title = seg.message;

  const pill = $('status-pill');
  const running = job.state === 'running' || job.state === 'queued';
  if (s.busy && running) {
    const frac = job.total > 0 ? ` ${job.done}/${job.total}` : '';
    pill.textContent = `computing: ${job.name}${frac}${s.queued ? ` (+${s.queued} queued)` : ''}`;
    pill.className = 'pill busy';
    const msg = job.message ? ` — ${job.message}` : '';
    setBanner('busy', `${job.name[0].toUpperCase()}${job.name.slice(1)}${msg}`, job.total > 0 ? job.done / job.total : undefined);
  } else if (seg.state === 'off' || seg.state === 'error') {
    pill.textContent = seg.state === 'off' ? 'segmentation off' : 'segmentation error';
    pill.className = 'pill err';
    pill.title = seg.message;
    setBanner('info', seg.message);
  } else {
    pill.textContent = `ready · ${ed.selected.toLocaleString()} selected`;
    pill.className = 'pill ok';
    if (ed.selected === 0) setBanner('info', seg.stale ? 'Scene edited — click an object to segment the edited scene'
      : 'No selection — left-click an object to select it (right-click or shift-click to subtract)');
    else setBanner(null);
  }
  if (!s.busy && seg.clicks < marks.length) marks = marks.slice(0, seg.clicks);
  if (!s.busy && seg.clicks === 0) marks = [];
  // Clicks of a segmentation the scene has moved away from are not shown on the new scene.
  showMarks(seg.stale && !s.busy ? [] : marks);
  // Enabled while SAM has a larger / smaller mask at the last click.
  const idle = !s.busy && !seg.stale;
  $('btn-larger').disabled = !(idle && seg.can_grow);
  $('btn-smaller').disabled = !(idle && seg.can_shrink);

  strip.update(seg, viewer.free ? -1 : viewer.cameraIndex);
  panels.update(s);
  display.update(s);
  if (ed.revision !== lastRevision) {
    lastRevision = ed.revision;
    viewer.refresh();  // the WebGL view's selection mask (and splats after an edit), or a server render
  }
  const log = $('log');
  for (const e of [...s.log].reverse()) {
    if (e.seq <= lastLogSeq) continue;
    lastLogSeq = e.seq;
    const li = document.createElement('li');
    li.className = e.level;
    const t = document.createElement('time');
    t.textContent = new Date(e.time * 1000).toLocaleTimeString();
    li.append(t, document.createTextNode(e.text));
    log.prepend(li);
    while (log.children.length > 60) log.lastChild.remove();
  }
}

// Polls overlap (a timed one still in flight when an action asks for one now), and their
// answers can arrive out of order: an answer older than the one shown would put the page
// back to before the action, so it is dropped. Only the latest poll sent schedules the
// next one, so overlapping polls never leave two timers running.
let pollsSent = 0, pollShown = 0;
async function poll() {
  clearTimeout(pollTimer);
  const sent = ++pollsSent;
  try {
    const s = await api.get('/api/status');
    if (sent > pollShown) {
      pollShown = sent;
      status = s;
      render(status);
    }
  } catch (e) {
    $('status-pill').textContent = `server unreachable: ${e.message}`;
    $('status-pill').className = 'pill err';
  }
  if (sent === pollsSent) pollTimer = setTimeout(poll, status && status.busy ? 300 : 1200);
}

function populateCameras() {
  const sel = $('camera-select');
  scene.cameras.forEach((c, i) => sel.add(new Option(`${i}: ${c.name}`, String(i))));
  sel.addEventListener('change', () => viewer.setCamera(Number(sel.value)));
  const step = (d) => {
    const n = scene.cameras.length;
    const i = viewer.free ? viewer.cameraIndex : (viewer.cameraIndex + d + n) % n;
    sel.value = String(i);
    viewer.setCamera(i);
  };
  $('btn-prev').addEventListener('click', () => step(-1));
  $('btn-next').addEventListener('click', () => step(1));
  $('btn-orbit').addEventListener('click', () => viewer.setFree(!viewer.free));
  $('btn-fly').addEventListener('click', () => viewer.setFly(!viewer.fly));
  $('btn-hd').addEventListener('click', () => viewer.render('full'));
  $('btn-nearest').addEventListener('click', nearest);
  $('btn-larger').addEventListener('click', () => granularity(1));
  $('btn-smaller').addEventListener('click', () => granularity(-1));
  return step;
}

// Leaves the free camera for the training camera nearest to it.
function nearest() {
  const i = viewer.free ? viewer.nearestCamera() : viewer.cameraIndex;
  $('camera-select').value = String(i);
  viewer.setCamera(i);
}

function bindKeys(step) {
  document.addEventListener('keydown', (e) => {
    const tag = (e.target.tagName || '').toLowerCase();
    if (tag === 'input' || tag === 'select' || tag === 'textarea') return;
    const k = e.key;
    const ctrl = e.ctrlKey || e.metaKey;
    let handled = true;
    if (ctrl && (k === 'z' || k === 'Z')) (e.shiftKey ? panels.redo() : panels.undo());
    else if (ctrl && (k === 'y' || k === 'Y')) panels.redo();
    else if (ctrl) handled = false;
    else if (k === 'z') panels.undo();
    else if (k === 'Z') panels.redo();
    else if (k === 'ArrowLeft') step(-1);
    else if (k === 'ArrowRight') step(1);
    else if (k === 'o' || k === 'O') viewer.setFree(!viewer.free);
    else if (k === 'n' || k === 'N') nearest();
    else if (k === 'f' || k === 'F') viewer.setFly(!viewer.fly);
    else if (k === 'h' || k === 'H') viewer.render('full');
    else if (k === 'Delete' || k === 'Backspace') { if (status && status.edit.selected > 0) panels.edit('remove'); }
    else if (k === 'i' || k === 'I') panels.select('invert');
    else if (k === 'Escape') { if (!$('help').classList.contains('hidden')) $('help').classList.add('hidden'); else panels.select('clear'); }
    else if (k === 'c' || k === 'C') { if (status && status.edit.selected > 0) panels.edit('copy', panels.transform()); }
    else if (k === '+' || k === '=') granularity(1);
    else if (k === '-') granularity(-1);
    else if (k === '?') $('help').classList.toggle('hidden');
    else handled = false;
    if (handled) e.preventDefault();
  });
  $('btn-help').addEventListener('click', () => $('help').classList.remove('hidden'));
  $('btn-help-close').addEventListener('click', () => $('help').classList.add('hidden'));
}

async function main() {
  try {
    scene = await api.get('/api/scene');
  } catch (e) {
    $('status-pill').textContent = `cannot load the scene: ${e.message}`;
    $('status-pill').className = 'pill err';
    return;
  }
  document.title = `isegman · ${scene.name}`;
  $('scene-name').textContent = scene.name;
  $('out-dir').textContent = `server folder: ${scene.out_dir}`;
  viewer = new Viewer({
    stage: $('stage'), frame: $('frame'), img: $('view-img'), glCanvas: $('view-gl'), canvas: $('view-marks'), caption: $('view-caption'), scene,
    onClick: click, onError: showError,
    onLook: (cam) => api.post('/api/focus', { view: cam }).catch(() => {}),  // a hint: failures do not matter
    onModeChange: () => {
      $('btn-orbit').classList.toggle('on', viewer.free); $('btn-fly').classList.toggle('on', viewer.fly);
      $('btn-nearest').disabled = !viewer.free; if (status) strip.update(status.segmentation, viewer.free ? -1 : viewer.cameraIndex);
    },
  });
  strip = new Strip($('strip'), (cam) => { $('camera-select').value = String(cam); viewer.setCamera(cam); });
  panels = new Panels({ api, run, runJob, scene, onClickWalked: clickWalked });
  new SelectionTools({ api, run, scene, frame: $('frame'), bar: $('tool-bar'), card: $('card-seltools'),
    target: () => viewer.shown && viewer.shown.target, mode: () => panels.selMode, flying: () => viewer.fly });
  new Files({ api, run, scene, transform: () => panels.transform() });
  display = bindDisplay({ api, run, viewer });
  initLayout();
  const step = populateCameras();
  bindKeys(step);
  viewer.fit();
  viewer.render();
  poll();
}

main();
