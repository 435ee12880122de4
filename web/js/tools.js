// Selection tools drawn on the view (SuperSplat's are the reference): rectangle, lasso
// and brush in the screen space of the shown camera (a training view or the free
// camera), the eyedropper, and the panel's grow/shrink and attribute ranges. A drawing
// tool lays a canvas over the view that takes the pointer; the segmentation click
// ("Pick") leaves the view to the viewer. Each request is one step of the one history.
//
// Coordinates go to the server as clicks do: continuous pixels of the camera's
// full-size image (the shown fraction times the camera's width and height).
const $ = (id) => document.getElementById(id);

const TOOLS = [
  { id: 'pick', key: 'q', label: 'Pick', title: 'Click to segment an object (Q)' },
  { id: 'rect', key: 'r', label: 'Rect', title: 'Rectangle selection (R)' },
  { id: 'lasso', key: 'l', label: 'Lasso', title: 'Lasso selection (L)' },
  { id: 'brush', key: 'b', label: 'Brush', title: 'Brush selection; [ and ] change its size (B)' },
  { id: 'color', key: 'e', label: 'Eyedropper', title: 'Select Gaussians of a similar colour to the one clicked (E)' },
];

function el(tag, props = {}, children = []) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(props)) {
    if (k === 'dataset') Object.assign(e.dataset, v);
    else if (k in e) e[k] = v;
    else e.setAttribute(k, v);
  }
  e.append(...children);
  return e;
}

export class SelectionTools {
  // frame: the element the view is drawn in; bar: where the tool buttons go; card: the
  // panel card for options, grow/shrink and ranges; target(): what the view shows,
  // {view} or {camera: spec} (null before the first frame); mode(): the panel's combine
  // mode; run(fn): runs a request, showing its result or error.
  constructor({ api, run, scene, frame, bar, card, target, mode, flying = () => false }) {
    Object.assign(this, { api, run, scene, frame, target, mode, flying });
    this.tool = 'pick';
    this.brushPx = 24;
    this.points = null;
    this.buildBar(bar);
    this.buildCard(card);
    this.overlay = el('canvas', { id: 'tool-overlay', className: 'tool-overlay' });
    frame.append(this.overlay);
    new ResizeObserver(() => this.resize()).observe(frame);
    this.bindPointer();
    this.bindKeys();
    this.setTool('pick');
  }

  buildBar(bar) {
    this.buttons = {};
    for (const t of TOOLS) {
      const b = el('button', { className: 'tool', title: t.title, dataset: { tool: t.id } }, [t.label]);
      b.addEventListener('click', () => this.setTool(t.id));
      this.buttons[t.id] = b;
      bar.append(b);
    }
  }

  buildCard(card) {
    const num = (id, value, step, title) => el('input', { id, type: 'number', value: String(value), step: String(step), title });
    card.append(
      el('h2', {}, ['Selection tools ', el('span', { className: 'muted small' }, ['keys R L B E, ? for all'])]),
      el('label', { className: 'check', title: 'Only Gaussians that show in the drawn pixels, not those hidden behind them' },
        [el('input', { id: 'tool-visible', type: 'checkbox' }), 'Visible surface only']),
      el('label', { className: 'field' }, ['Brush size ', el('output', { id: 'brush-out' }, [`${this.brushPx} px`]),
        el('input', { id: 'brush-size', type: 'range', min: '4', max: '120', step: '1', value: String(this.brushPx) })]),
      el('label', { className: 'field' }, ['Eyedropper tolerance ', el('output', { id: 'tol-out' }, ['0.10']),
        el('input', { id: 'tolerance', type: 'range', min: '0', max: '0.6', step: '0.01', value: '0.1' })]),
      el('div', { className: 'muted small' }, ['Shift while drawing: add · Ctrl: subtract · otherwise the mode above']),
      el('div', { className: 'sub' }, ['Grow / shrink']),
      el('div', { className: 'row' }, [
        el('select', { id: 'grow-by', title: 'k nearest neighbours, or every neighbour within a radius (scene units)' }, [
          el('option', { value: 'k' }, ['k neighbours']), el('option', { value: 'radius' }, ['radius'])]),
        el('span', { className: 'grow' }, [num('grow-amount', 8, 'any', 'k, or the radius in scene units')]),
        el('button', { id: 'btn-grow', title: 'Add the neighbours of the selection (G)' }, ['Grow']),
        el('button', { id: 'btn-shrink', title: 'Drop selected Gaussians with an unselected neighbour (Shift+G)' }, ['Shrink'])]),
      el('div', { className: 'sub' }, ['Attribute ranges']),
      el('div', { className: 'range-row' }, [el('span', {}, ['opacity']), num('op-min', 0, 0.05, 'minimum opacity (0..1)'),
        num('op-max', 0.2, 0.05, 'maximum opacity (0..1)'), el('button', { id: 'btn-opacity' }, ['Select'])]),
      el('div', { className: 'range-row' }, [el('span', {}, ['size']), num('size-min', 0, 'any', 'minimum largest-axis scale (scene units)'),
        num('size-max', 0.05, 'any', 'maximum largest-axis scale (scene units)'), el('button', { id: 'btn-size' }, ['Select'])]),
    );
    $('brush-size').addEventListener('input', () => this.setBrush(Number($('brush-size').value)));
    $('tolerance').addEventListener('input', () => { $('tol-out').textContent = Number($('tolerance').value).toFixed(2); });
    $('btn-grow').addEventListener('click', () => this.growShrink('grow'));
    $('btn-shrink').addEventListener('click', () => this.growShrink('shrink'));
    $('btn-opacity').addEventListener('click', () => this.range('opacity', 'op'));
    $('btn-size').addEventListener('click', () => this.range('size', 'size'));
  }

  setBrush(px) {
    this.brushPx = Math.max(4, Math.min(120, Math.round(px)));
    $('brush-size').value = String(this.brushPx);
    $('brush-out').textContent = `${this.brushPx} px`;
  }

  setTool(id) {
    this.tool = id;
    for (const [k, b] of Object.entries(this.buttons)) b.classList.toggle('on', k === id);
    this.overlay.classList.toggle('active', id !== 'pick');
    this.overlay.dataset.tool = id;
    document.body.dataset.tool = id;
    this.points = null;
    this.draw();
  }

  resize() {
    const r = this.frame.getBoundingClientRect();
    this.overlay.width = Math.max(1, Math.round(r.width));
    this.overlay.height = Math.max(1, Math.round(r.height));
    this.draw();
  }

  // The camera the request refers to and the factor from overlay pixels to its pixels.
  cameraOf(t) {
    const cam = t.view !== undefined ? this.scene.cameras[t.view] : t.camera;
    const ref = t.view !== undefined ? { view: t.view } : { camera: t.camera };
    return { ref, sx: cam.width / this.overlay.width, sy: cam.height / this.overlay.height };
  }

  modeFor(e) {
    if (e.shiftKey) return 'add';
    if (e.ctrlKey || e.metaKey || e.altKey) return 'subtract';
    return this.mode();
  }

  bindPointer() {
    const o = this.overlay;
    const at = (e) => { const r = o.getBoundingClientRect(); return [e.clientX - r.left, e.clientY - r.top]; };
    o.addEventListener('contextmenu', (e) => e.preventDefault());
    // The viewer orbits on the frame's pointer events: a stroke of a drawing tool is not
    // an orbit, so the overlay keeps its events to itself.
    for (const ev of ['pointerdown', 'pointermove', 'pointerup', 'dblclick'])
      o.addEventListener(ev, (e) => e.stopPropagation());
    o.addEventListener('pointerdown', (e) => {
      if (e.button !== 0) return;
      o.setPointerCapture(e.pointerId);
      this.points = [at(e)];
      this.draw();
    });
    o.addEventListener('pointermove', (e) => {
      this.hover = at(e);
      if (!this.points) { if (this.tool === 'brush') this.draw(); return; }
      const p = at(e), last = this.points[this.points.length - 1];
      if (this.tool === 'rect') this.points[1] = p;
      else if (Math.hypot(p[0] - last[0], p[1] - last[1]) >= 2) this.points.push(p);
      this.draw();
    });
    o.addEventListener('pointerleave', () => { this.hover = null; if (!this.points) this.draw(); });
    o.addEventListener('pointerup', (e) => {
      if (!this.points) return;
      const pts = this.points;
      this.points = null;
      this.finish(pts, this.modeFor(e));
    });
    // The wheel is left to bubble to the frame: it still zooms the view under a drawing tool.
  }

  finish(pts, mode) {
    const t = this.target();
    if (!t) { this.draw(); return; }
    const { ref, sx, sy } = this.cameraOf(t);
    const px = (p) => [p[0] * sx, p[1] * sy];
    const visible = $('tool-visible').checked;
    let path = null, body = null;
    if (this.tool === 'color') {
      const [x, y] = px(pts[0]);
      path = '/api/select/color';
      body = { ...ref, x, y, tolerance: Number($('tolerance').value), mode };
    } else if (this.tool === 'rect') {
      if (pts.length < 2 || Math.abs(pts[1][0] - pts[0][0]) < 2 || Math.abs(pts[1][1] - pts[0][1]) < 2) { this.draw(); return; }
      path = '/api/select/rect';
      body = { ...ref, points: [px(pts[0]), px(pts[1])], mode, visible };
    } else if (this.tool === 'lasso') {
      if (pts.length < 3) { this.draw(); return; }
      path = '/api/select/lasso';
      body = { ...ref, points: pts.map(px), mode, visible };
    } else if (this.tool === 'brush') {
      path = '/api/select/brush';
      body = { ...ref, points: pts.map(px), radius: this.brushPx * sx, mode, visible };
    }
    // The drawn shape stays on screen until the server answered.
    this.pending = { tool: this.tool, pts };
    this.draw();
    this.run(async () => {
      try {
        const r = await this.api.post(path, body);
        return r.label;
      } finally {
        this.pending = null;
        this.draw();
      }
    });
  }

  growShrink(op) {
    const by = $('grow-by').value, v = Number($('grow-amount').value);
    const body = by === 'k' ? { k: Math.round(v) } : { radius: v };
    return this.run(async () => (await this.api.post(`/api/select/${op}`, body)).label);
  }

  range(attr, prefix) {
    const body = { min: Number($(`${prefix}-min`).value), max: Number($(`${prefix}-max`).value), mode: this.mode() };
    return this.run(async () => (await this.api.post(`/api/select/${attr}`, body)).label);
  }

  draw() {
    const o = this.overlay, g = o.getContext('2d');
    g.clearRect(0, 0, o.width, o.height);
    const shape = this.points ? { tool: this.tool, pts: this.points } : this.pending;
    g.lineWidth = 1.5;
    g.strokeStyle = '#ffd166';
    g.fillStyle = 'rgba(255, 209, 102, 0.18)';
    if (shape) {
      const p = shape.pts;
      if (shape.tool === 'rect' && p.length === 2) {
        g.setLineDash([5, 4]);
        g.fillRect(p[0][0], p[0][1], p[1][0] - p[0][0], p[1][1] - p[0][1]);
        g.strokeRect(p[0][0], p[0][1], p[1][0] - p[0][0], p[1][1] - p[0][1]);
      } else if (shape.tool === 'lasso' && p.length > 1) {
        g.setLineDash([5, 4]);
        g.beginPath();
        g.moveTo(p[0][0], p[0][1]);
        for (const q of p.slice(1)) g.lineTo(q[0], q[1]);
        g.closePath();
        g.fill();
        g.stroke();
      } else if (shape.tool === 'brush') {
        g.save();
        g.strokeStyle = 'rgba(255, 209, 102, 0.35)';
        g.lineCap = 'round';
        g.lineJoin = 'round';
        g.lineWidth = 2 * this.brushPx;
        g.beginPath();
        g.moveTo(p[0][0], p[0][1]);
        for (const q of p) g.lineTo(q[0], q[1]);
        g.stroke();
        g.restore();
      }
      g.setLineDash([]);
    }
    if (this.tool === 'brush' && this.hover) {
      g.beginPath();
      g.arc(this.hover[0], this.hover[1], this.brushPx, 0, 2 * Math.PI);
      g.stroke();
    }
  }

  bindKeys() {
    document.addEventListener('keydown', (e) => {
      // Typing fields keep their keys; sliders and check boxes (the tools' own options) do not.
      const tag = (e.target.tagName || '').toLowerCase();
      const typing = tag === 'select' || tag === 'textarea' ||
        (tag === 'input' && !['checkbox', 'range', 'radio', 'color'].includes(e.target.type));
      if (typing || e.ctrlKey || e.metaKey || e.altKey) return;
      if (this.flying()) return;  // fly mode moves with WASD/QE: its keys are not tool keys
      const k = e.key;
      const tool = TOOLS.find((t) => t.key === k.toLowerCase() && !e.shiftKey);
      let handled = true;
      if (tool) this.setTool(tool.id);
      else if (k === '[') this.setBrush(this.brushPx / 1.25);
      else if (k === ']') this.setBrush(this.brushPx * 1.25);
      else if (k === 'g') this.growShrink('grow');
      else if (k === 'G') this.growShrink('shrink');
      else if (k === 'Escape' && this.points) { this.points = null; this.draw(); }
      else handled = false;
      if (handled) { e.preventDefault(); e.stopImmediatePropagation(); }
      this.draw();
    }, { capture: true });
  }
}
