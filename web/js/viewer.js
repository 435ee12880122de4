// The main view: a server-side render of a training camera or of the free camera, with
// the selection highlighted; clicks become segmentation prompts, drags orbit/pan, the
// wheel zooms. Renders are requested latest-wins so navigation stays responsive.
import { Orbit } from './orbit.js';

export class Viewer {
  constructor({ stage, frame, img, canvas, caption, scene, onClick, onError, onModeChange }) {
    Object.assign(this, { stage, frame, img, canvas, caption, scene, onClick, onError, onModeChange });
    this.cameraIndex = 0;
    this.free = false;
    this.orbit = new Orbit(scene.up);
    // The orbit pivot: the centre of the robust (percentile) bounds from /api/scene, not
    // of the bounding box, which far outlier Gaussians make huge.
    const lo = scene.bounds.lo, hi = scene.bounds.hi;
    this.sceneCenter = scene.pivot || lo.map((v, i) => (v + hi[i]) / 2);
    this.orbitDistance = scene.orbit_distance || 0;
    this.inFlight = false;
    this.queued = null;
    this.shown = null;
    this.marks = [];
    this.objectUrl = null;
    this.bindPointer();
    new ResizeObserver(() => { this.fit(); this.render(); }).observe(stage);
  }

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

  // Builds the render URL for the current camera; `quality`: 'fast' | 'preview' | 'full'.
  request(quality) {
    const side = this.scene.preview_side;
    if (!this.free) {
      const size = quality === 'full' ? 'full' : quality === 'fast' ? Math.max(64, Math.round(side / 2)) : side;
      return { url: `/api/render?view=${this.cameraIndex}&size=${size}`, target: { view: this.cameraIndex }, key: this.key() };
    }
    const a = this.aspect();
    let s = quality === 'full' ? Math.min(4096, side * 2) : quality === 'fast' ? Math.round(side / 2) : side;
    const w = a >= 1 ? s : Math.max(16, Math.round(s * a));
    const h = a >= 1 ? Math.max(16, Math.round(s / a)) : s;
    const spec = this.orbit.spec(w, h);
    const q = new URLSearchParams({ eye: spec.eye.join(','), target: spec.target.join(','), up: spec.up.join(','),
      fov: String(spec.fov), width: String(w), height: String(h) });
    return { url: `/api/render?${q}`, target: { camera: spec }, key: this.key() };
  }

  render(quality = 'preview') {
    this.queued = this.request(quality);
    if (!this.inFlight) this.pump();
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
        const url = URL.createObjectURL(blob);
        await new Promise((resolve, reject) => { this.img.onload = resolve; this.img.onerror = reject; this.img.src = url; });
        if (this.objectUrl) URL.revokeObjectURL(this.objectUrl);
        this.objectUrl = url;
        this.shown = r;
        this.img.dataset.key = r.key;
        this.img.dataset.rendered = String(Date.now());
        const c = this.free ? null : this.scene.cameras[this.cameraIndex];
        this.caption.textContent = this.free
          ? `free camera · ${this.img.naturalWidth}×${this.img.naturalHeight}`
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
    const g = this.canvas.getContext('2d');
    g.clearRect(0, 0, this.canvas.width, this.canvas.height);
    const key = this.shown ? this.shown.key : null;
    for (const m of this.marks) {
      if (m.key !== key) continue;
      const x = m.x * this.canvas.width, y = m.y * this.canvas.height;
      g.beginPath(); g.arc(x, y, 7, 0, 2 * Math.PI);
      g.fillStyle = m.label ? 'rgba(47,191,113,0.95)' : 'rgba(229,72,77,0.95)'; g.fill();
      g.lineWidth = 2; g.strokeStyle = '#fff'; g.stroke();
      g.fillStyle = '#fff'; g.font = 'bold 12px system-ui'; g.textAlign = 'center'; g.textBaseline = 'middle';
      g.fillText(m.label ? '+' : '−', x, y + 0.5);
    }
  }

  bindPointer() {
    const img = this.img;
    let start = null;
    img.addEventListener('contextmenu', (e) => e.preventDefault());
    img.addEventListener('pointerdown', (e) => {
      img.setPointerCapture(e.pointerId);
      start = { x: e.clientX, y: e.clientY, lastX: e.clientX, lastY: e.clientY, button: e.button, shift: e.shiftKey, dragged: false };
    });
    img.addEventListener('pointermove', (e) => {
      if (!start) return;
      const dx = e.clientX - start.lastX, dy = e.clientY - start.lastY;
      if (!start.dragged && Math.hypot(e.clientX - start.x, e.clientY - start.y) < 5) return;
      if (!start.dragged) { start.dragged = true; this.stage.classList.add('dragging'); this.setFree(true); }
      start.lastX = e.clientX; start.lastY = e.clientY;
      if (start.button === 0 && !start.shift) this.orbit.rotate(dx, dy);
      else this.orbit.pan(dx, dy, this.canvas.height);
      this.render('fast');
    });
    img.addEventListener('pointerup', (e) => {
      if (!start) return;
      const s = start;
      start = null;
      this.stage.classList.remove('dragging');
      if (s.dragged) { this.render(); return; }
      if (!this.shown || s.button > 2) return;
      const rect = img.getBoundingClientRect();
      const x = Math.min(Math.max((e.clientX - rect.left) / rect.width, 0), 0.9999);
      const y = Math.min(Math.max((e.clientY - rect.top) / rect.height, 0), 0.9999);
      const label = s.button === 2 || s.shift || e.shiftKey ? 0 : 1;
      // A double click is one click: drop a repeat at the same spot within 400 ms.
      const now = performance.now(), last = this.lastClick;
      this.lastClick = { t: now, x: e.clientX, y: e.clientY, label };
      if (last && now - last.t < 400 && Math.hypot(e.clientX - last.x, e.clientY - last.y) < 6 && last.label === label) return;
      this.onClick?.({ ...this.shown.target, x, y, label, key: this.shown.key });
    });
    img.addEventListener('wheel', (e) => {
      e.preventDefault();
      this.setFree(true);
      this.orbit.zoom(Math.exp(e.deltaY * 0.0015));
      this.render('fast');
      clearTimeout(this.wheelTimer);
      this.wheelTimer = setTimeout(() => this.render(), 250);
    }, { passive: false });
  }
}
