// The main view. Training cameras are server renders (the rasteriser the evidence uses);
// the free camera is drawn by the page's WebGL2 splat renderer (splat_renderer.js) when
// the browser has WebGL2, else it is a stream of server renders, progressive: low
// resolution while dragging, the displayed size once still. Clicks become segmentation
// prompts (the free camera is sent as eye/target/up/fov so the server renders the same
// view), a double click picks the surface point to orbit around, drags orbit/pan (or look
// around in fly mode, WASD/QE to move), the wheel zooms.
import { Orbit } from './orbit.js';
import { SplatRenderer, lookAt } from './splat_renderer.js';

const DOUBLE_CLICK_MS = 300;

export class Viewer {
  constructor({ stage, frame, img, glCanvas, canvas, caption, scene, onClick, onError, onModeChange, onFocus, onLook }) {
    Object.assign(this, { stage, frame, img, glCanvas, canvas, caption, scene, onClick, onError, onModeChange, onFocus, onLook });
    this.cameraIndex = 0;
    this.free = false;
    this.fly = false;
    this.orbit = new Orbit(scene.up);
    // The orbit pivot: the centre of the robust (percentile) bounds from /api/scene, not
    // of the bounding box, which far outlier Gaussians make huge.
    const lo = scene.bounds.lo, hi = scene.bounds.hi;
    this.sceneCenter = scene.pivot || lo.map((v, i) => (v + hi[i]) / 2);
    this.orbitDistance = scene.orbit_distance || 0;
    this.flySpeed = Math.max(1e-3, (scene.robust_bounds && scene.robust_bounds.radius) || this.orbitDistance || 1) * 0.5;
    this.inFlight = false;
    this.queued = null;
    this.shown = null;
    this.marks = [];
    this.objectUrl = null;
    this.highlight = { on: true, opacity: 0.5 };
    this.gl = null;
    try {
      this.gl = new URLSearchParams(location.search).has('nogl') ? null : SplatRenderer.create(glCanvas, scene.background || [0, 0, 0]);
    } catch (e) {
      onError?.(`WebGL renderer unavailable, using server renders: ${e.message || e}`);
    }
    document.body.dataset.renderer = this.gl ? 'webgl' : 'server';
    // ?full: draw every splat while moving too (for measuring, tests/e2e/bench_orbit.mjs).
    if (this.gl && new URLSearchParams(location.search).has('full')) this.gl.subsetWhileMoving = false;
    if (this.gl) {
      this.gl.onDraw = () => this.glDrawn();
      this.gl.load().then(() => this.gl.loadMask()).catch((e) => { onError?.(`splats: ${e.message || e}`); });
    }
    this.bindPointer();
    this.bindFlyKeys();
    new ResizeObserver(() => { this.fit(); this.render(); }).observe(stage);
  }

  usesGl() { return this.free && this.gl !== null; }

  key() { return this.free ? 'f' + JSON.stringify(this.orbit.spec(0, 0)) : 'v' + this.cameraIndex; }

  aspect() {
    if (!this.free) { const c = this.scene.cameras[this.cameraIndex]; return c.width / c.height; }
    const w = this.stage.clientWidth, h = this.stage.clientHeight;
    return w > 0 && h > 0 ? w / h : 4 / 3;
  }

  fit() {
    const a = this.aspect();
    const W = Math.max(this.stage.clientWidth - 2, 10), H = Math.max(this.stage.clientHeight - 2, 10);
    let w = W, h = W / a;
    if (h > H) { h = H; w = H * a; }
    this.frame.style.width = `${Math.round(w)}px`;
    this.frame.style.height = `${Math.round(h)}px`;
    this.canvas.width = Math.round(w); this.canvas.height = Math.round(h);
    this.img.classList.toggle('hidden', this.usesGl());
    this.glCanvas.classList.toggle('hidden', !this.usesGl());
    this.drawMarks();
  }

  setCamera(index) {
    this.cameraIndex = index;
    this.free = false;
    this.onModeChange?.();
    this.fit();
    this.render();
  }

  setFree(on) {
    if (on === this.free) return;
    if (on) this.orbit.fromCamera(this.scene.cameras[this.cameraIndex], this.sceneCenter, this.orbitDistance);
    this.free = on;
    this.onModeChange?.();
    this.fit();
    this.render();
  }

  setFly(on) { this.fly = on; this.onModeChange?.(); }

  // Highlight of the selection: on/off and its opacity, in the WebGL view and in server renders.
  setHighlight(on, opacity) {
    this.highlight = { on, opacity };
    this.gl?.setTint(on ? opacity : 0);
    if (!this.usesGl()) this.render();
  }

  // The scene or the selection changed on the server (status revision).
  refresh() {
    if (this.gl) {
      this.gl.loadMask().then((m) => { if (m) document.body.dataset.hidden = String(m.hidden); })
        .catch((e) => this.onError?.(`selection mask: ${e.message || e}`));
    }
    this.render();
  }

  // The training camera nearest the free camera (position, then viewing direction).
  nearestCamera() {
    const eye = this.orbit.eye(), t = this.orbit.target;
    const f = t.map((v, i) => v - eye[i]), fl = Math.hypot(...f) || 1;
    let best = this.cameraIndex, bestScore = Infinity;
    const scale = Math.max(this.orbit.distance, 1e-6);
    this.scene.cameras.forEach((c, i) => {
      const d = Math.hypot(...c.center.map((v, k) => v - eye[k])) / scale;
      const cos = c.forward.reduce((a, v, k) => a + v * f[k], 0) / fl;
      const score = d + (1 - cos);
      if (score < bestScore) { bestScore = score; best = i; }
    });
    return best;
  }

  // The free camera's server size for a longest side `s` (clicks and server renders).
  freeSize(s) {
    const a = this.aspect();
    return a >= 1 ? [s, Math.max(16, Math.round(s / a))] : [Math.max(16, Math.round(s * a)), s];
  }

  // The render URL for the current camera; `quality`: 'fast' | 'preview' | 'display' | 'full'.
  request(quality) {
    const side = this.scene.preview_side;
    const shownSide = Math.round(Math.max(this.frame.clientWidth, this.frame.clientHeight) * (window.devicePixelRatio || 1));
    const hl = this.highlight.on ? `&tint=${this.highlight.opacity}` : '&highlight=0';
    if (!this.free) {
      const size = quality === 'full' ? 'full' : quality === 'fast' ? Math.max(64, Math.round(side / 2))
        : quality === 'display' ? Math.max(side, Math.min(4096, shownSide)) : side;
      return { url: `/api/render?view=${this.cameraIndex}&size=${size}${hl}`, target: { view: this.cameraIndex }, key: this.key() };
    }
    const s = quality === 'full' ? Math.min(4096, side * 2) : quality === 'fast' ? Math.round(side / 2)
      : quality === 'display' ? Math.max(side, Math.min(4096, shownSide)) : side;
    const [w, h] = this.freeSize(s);
    const spec = this.orbit.spec(w, h);
    const q = new URLSearchParams({ eye: spec.eye.join(','), target: spec.target.join(','), up: spec.up.join(','),
      fov: String(spec.fov), width: String(w), height: String(h) });
    return { url: `/api/render?${q}${hl}`, target: { camera: this.clickSpec() }, key: this.key() };
  }

  // The free camera as a click sends it: the preview size (any size of this aspect maps
  // the same clicked fraction to the same ray).
  clickSpec() { const [w, h] = this.freeSize(this.scene.preview_side); return this.orbit.spec(w, h); }

  // Once the camera has been still a moment: the training camera looked at (the nearest
  // one to the free camera), so the server can build the views a click there would use.
  lookedAt() {
    clearTimeout(this.lookTimer);
    this.lookTimer = setTimeout(() => {
      const cam = this.free ? this.nearestCamera() : this.cameraIndex;
      if (cam !== this.lookSent) { this.lookSent = cam; this.onLook?.(cam); }
    }, 800);
  }

  render(quality = 'preview') {
    this.lookedAt();
    if (this.usesGl()) { this.renderGl(); return; }
    this.queued = this.request(quality);
    if (!this.inFlight) this.pump();
    // Progressive: once still for a moment, the displayed size (when larger than the preview).
    clearTimeout(this.refineTimer);
    if (quality === 'preview') this.refineTimer = setTimeout(() => this.render('display'), 500);
  }

  renderGl() {
    const w = this.glCanvas.clientWidth || this.canvas.width, h = this.glCanvas.clientHeight || this.canvas.height;
    const dpr = window.devicePixelRatio || 1;
    const W = Math.max(16, Math.round(w * dpr)), H = Math.max(16, Math.round(h * dpr));
    this.gl.setCamera(lookAt(this.orbit.spec(W, H), W, H));
    const key = this.key();
    this.shown = { target: { camera: this.clickSpec() }, key };
    this.frame.dataset.key = key;
    this.img.dataset.key = key;
    this.drawMarks();
  }

  glDrawn() {
    const g = this.gl;
    this.frame.dataset.rendered = String(g.frames);
    if (!this.usesGl()) return;
    // While moving, the caption changes at most twice a second: each change is a relayout,
    // repaint and raster of its layer, CPU time a software-GL frame needs.
    const now = performance.now();
    if (g.moving && now - (this.captionAt || 0) < 500) return;
    this.captionAt = now;
    const text = `free camera · WebGL · ${g.drawCount.toLocaleString()} of ${g.count.toLocaleString()} splats` +
      ` · ${g.drawnSize[0]}×${g.drawnSize[1]}` + (g.moving ? ' (moving: reduced)' : '') + (this.fly ? ' · fly (WASD/QE)' : '');
    if (this.caption.textContent !== text) this.caption.textContent = text;  // no relayout per frame
  }

  // Dragging or flying: the WebGL view draws a subset; server renders a low resolution.
  moving(on) {
    this.gl?.setMoving(on);
    clearTimeout(this.stillTimer);
    if (!on) this.stillTimer = setTimeout(() => { this.gl?.setMoving(false); this.render(); }, 0);
  }

  async pump() {
    while (this.queued) {
      const r = this.queued;
      this.queued = null;
      this.inFlight = true;
      try {
        const res = await fetch(r.url, { cache: 'no-store' });
        if (!res.ok) {
          let msg = `render failed (${res.status})`;
          try { msg = (await res.json()).error || msg; } catch (_) { /* keep */ }
          throw new Error(msg);
        }
        const blob = await res.blob();
        if (this.usesGl()) continue;  // switched to the WebGL view meanwhile
        const url = URL.createObjectURL(blob);
        await new Promise((resolve, reject) => { this.img.onload = resolve; this.img.onerror = reject; this.img.src = url; });
        // A double click may have switched to the WebGL view while the image decoded: the
        // training view's render must not take over the free view's key, caption and marks.
        if (this.usesGl()) { URL.revokeObjectURL(url); continue; }
        if (this.objectUrl) URL.revokeObjectURL(this.objectUrl);
        this.objectUrl = url;
        this.shown = r;
        this.img.dataset.key = r.key;
        this.frame.dataset.key = r.key;
        this.img.dataset.rendered = String(Date.now());
        this.img.dataset.loads = String(Number(this.img.dataset.loads || 0) + 1);
        const c = this.free ? null : this.scene.cameras[this.cameraIndex];
        this.caption.textContent = this.free
          ? `free camera · server render ${this.img.naturalWidth}×${this.img.naturalHeight}`
          : `camera ${this.cameraIndex} · ${c.name} · ${this.img.naturalWidth}×${this.img.naturalHeight}` +
            (this.img.naturalWidth < c.width ? ` (full: ${c.width}×${c.height})` : '');
        this.drawMarks();
      } catch (e) {
        this.onError?.(e.message || String(e));
      } finally {
        this.inFlight = false;
      }
    }
  }

  setMarks(marks) { this.marks = marks; this.drawMarks(); }

  drawMarks() {
    const key = this.shown ? this.shown.key : null;
    const shown = this.marks.filter((m) => m.key === key);
    // Nothing to draw and nothing drawn: leave the overlay alone (repainting it every
    // frame of a drag costs software compositing time).
    const sig = `${this.canvas.width}x${this.canvas.height}:${JSON.stringify(shown)}`;
    if (!shown.length && this.marksEmpty === sig) return;
    this.marksEmpty = shown.length ? null : sig;
    // An empty overlay is not displayed: a transparent layer over the view still costs
    // blending every frame in software compositing.
    this.canvas.classList.toggle('hidden', !shown.length);
    const g = this.canvas.getContext('2d');
    g.clearRect(0, 0, this.canvas.width, this.canvas.height);
    for (const m of shown) {
      const x = m.x * this.canvas.width, y = m.y * this.canvas.height;
      g.beginPath(); g.arc(x, y, 7, 0, 2 * Math.PI);
      g.fillStyle = m.label ? 'rgba(47,191,113,0.95)' : 'rgba(229,72,77,0.95)'; g.fill();
      g.lineWidth = 2; g.strokeStyle = '#fff'; g.stroke();
      g.fillStyle = '#fff'; g.font = 'bold 12px system-ui'; g.textAlign = 'center'; g.textBaseline = 'middle';
      g.fillText(m.label ? '+' : '−', x, y + 0.5);
    }
  }

  // Double click: the surface point under the pointer (the server's render with depth)
  // becomes the orbit pivot; from a training camera this switches to the free camera.
  async focusAt(fx, fy) {
    let q;
    if (this.free) {
      const spec = this.clickSpec();
      q = new URLSearchParams({ eye: spec.eye.join(','), target: spec.target.join(','), up: spec.up.join(','),
        fov: String(spec.fov), width: String(spec.width), height: String(spec.height),
        x: String(fx * spec.width), y: String(fy * spec.height) });
    } else {
      const c = this.scene.cameras[this.cameraIndex];
      q = new URLSearchParams({ view: String(this.cameraIndex), x: String(fx * c.width), y: String(fy * c.height) });
    }
    try {
      const res = await fetch(`/api/pick?${q}`, { cache: 'no-store' });
      const r = await res.json();
      if (!res.ok) throw new Error(r.error || `pick failed (${res.status})`);
      if (!r.hit) { this.onError?.('no surface under the pointer to focus on'); return; }
      this.setFree(true);
      this.orbit.focus(r.point);
      document.body.dataset.focus = r.point.map((v) => v.toFixed(4)).join(',');
      this.render();
      this.onFocus?.(r.point);
    } catch (e) {
      this.onError?.(e.message || String(e));
    }
  }

  bindPointer() {
    const el = this.frame;
    let start = null;
    el.addEventListener('contextmenu', (e) => e.preventDefault());
    el.addEventListener('dblclick', (e) => e.preventDefault());
    el.addEventListener('pointerdown', (e) => {
      try { el.setPointerCapture(e.pointerId); } catch (_) { /* a synthetic pointer (scripts, tests) */ }
      start = { x: e.clientX, y: e.clientY, lastX: e.clientX, lastY: e.clientY, button: e.button, shift: e.shiftKey, dragged: false };
    });
    el.addEventListener('pointermove', (e) => {
      if (!start) return;
      const dx = e.clientX - start.lastX, dy = e.clientY - start.lastY;
      if (!start.dragged && Math.hypot(e.clientX - start.x, e.clientY - start.y) < 5) return;
      if (!start.dragged) {
        start.dragged = true; this.stage.classList.add('dragging'); this.setFree(true); this.moving(true);
      }
      start.lastX = e.clientX; start.lastY = e.clientY;
      if (start.button === 0 && !start.shift) (this.fly ? this.orbit.look(dx, dy) : this.orbit.rotate(dx, dy));
      else this.orbit.pan(dx, dy, this.canvas.height);
      this.render('fast');
    });
    el.addEventListener('pointerup', (e) => {
      if (!start) return;
      const s = start;
      start = null;
      this.stage.classList.remove('dragging');
      if (s.dragged) { this.moving(false); return; }
      if (!this.shown || s.button > 2) return;
      const rect = el.getBoundingClientRect();
      const x = Math.min(Math.max((e.clientX - rect.left) / rect.width, 0), 0.9999);
      const y = Math.min(Math.max((e.clientY - rect.top) / rect.height, 0), 0.9999);
      const label = s.button === 2 || s.shift || e.shiftKey ? 0 : 1;
      // A second click at the same spot within 300 ms makes a double click: focus there
      // instead of sending a segmentation click (the first one waits that long for it).
      const now = performance.now(), last = this.pendingClick;
      if (last && now - last.t < DOUBLE_CLICK_MS && Math.hypot(e.clientX - last.cx, e.clientY - last.cy) < 6) {
        clearTimeout(last.timer);
        this.pendingClick = null;
        this.focusAt(x, y);
        return;
      }
      const target = { ...this.shown.target, x, y, label, key: this.shown.key };
      const pending = { t: now, cx: e.clientX, cy: e.clientY };
      pending.timer = setTimeout(() => { if (this.pendingClick === pending) this.pendingClick = null; this.onClick?.(target); }, DOUBLE_CLICK_MS);
      this.pendingClick = pending;
    });
    el.addEventListener('wheel', (e) => {
      e.preventDefault();
      this.setFree(true);
      this.moving(true);
      this.orbit.zoom(Math.exp(e.deltaY * 0.0015));
      this.render('fast');
      clearTimeout(this.wheelTimer);
      this.wheelTimer = setTimeout(() => this.moving(false), 250);
    }, { passive: false });
  }

  // Fly mode: W/S forward/back, A/D left/right, Q/E down/up (Shift: faster), while held.
  // Movement follows the time held, not the frames drawn (a slow frame does not slow it).
  bindFlyKeys() {
    const held = new Set();
    const dirs = { w: [1, 0, 0], s: [-1, 0, 0], a: [0, -1, 0], d: [0, 1, 0], q: [0, 0, -1], e: [0, 0, 1] };
    let last = 0, fast = false, looping = false;
    const advance = () => {
      const now = performance.now();
      const dt = Math.min(0.25, (now - last) / 1000);
      last = now;
      const v = [0, 0, 0];
      for (const k of held) dirs[k].forEach((d, i) => { v[i] += d; });
      const s = this.flySpeed * dt * (fast ? 3 : 1);
      if (s > 0 && v.some((x) => x !== 0)) { this.orbit.move(v[0] * s, v[1] * s, v[2] * s); this.render('fast'); }
    };
    const step = () => {
      if (!held.size) { looping = false; this.moving(false); return; }
      advance();
      requestAnimationFrame(step);
    };
    document.addEventListener('keydown', (e) => {
      const tag = (e.target.tagName || '').toLowerCase();
      const k = e.key.toLowerCase();
      if (!this.fly || e.ctrlKey || e.metaKey || e.altKey || tag === 'input' || tag === 'select' || tag === 'textarea' || !dirs[k]) return;
      e.preventDefault();
      e.stopImmediatePropagation();
      fast = e.shiftKey;
      if (held.has(k)) return;  // key repeat
      if (held.size) advance(); else last = performance.now();
      held.add(k);
      if (!looping) { looping = true; this.setFree(true); this.moving(true); requestAnimationFrame(step); }
    }, { capture: true });
    document.addEventListener('keyup', (e) => {
      const k = e.key.toLowerCase();
      if (!held.has(k)) return;
      advance();
      held.delete(k);
      fast = e.shiftKey;
    });
    window.addEventListener('blur', () => held.clear());
  }
}
