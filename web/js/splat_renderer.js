// Client-side WebGL2 renderer of the scene's Gaussians for navigation (the server's
// rasteriser stays the reference for evidence, clicked views and exports). It follows
// the INRIA rasteriser: EWA projection with the perspective Jacobian (x/z, y/z clamped to
// 1.3x the half field of view), +0.3 px on the 2D covariance diagonal, alpha =
// min(0.99, o exp(-d^2/2)) cut at 1/255, colour from the SH (degrees 0-3, evaluated per
// splat and view in sort_worker.js), splats blended far to near (sorted there too).
// Camera convention: OpenCV axes, p_cam = R p + t.
//
// Data: /api/splats (src/server/scene_binary.h) becomes a RGBA32UI texture, three texels
// per splat (centre + packed colour, covariance xx xy xz yy, yz zz); /api/selection/mask
// a R8UI texture (bit 0 selected, bit 1 hidden); each sort a RG32UI texture (per drawn
// splat, far to near: its index and its view-dependent RGBA8 colour).
import { NEAR, NOTHING_FS, ORDER_ROW, PROJ_ROW, QUAD_VS, SPLAT_FS, projectVS } from './splat_shaders.js';

const ROW = 1024;  // splats per texture row (3 texels each)
const SORT_INTERVAL_MS = 80;  // least time between two sorts while moving
// While moving, quality steps down until a frame takes under ~50 ms (SwiftShader, the
// software WebGL of a machine without GPU, draws all of fern at 960x540 in ~0.8 s):
// [resolution divisor, share of the splats drawn, most important first]. Frames drawn
// while moving go straight into a WebGL canvas of the step's resolution, scaled to the
// view by the compositor: drawing into a framebuffer and blitting it onto a full-size
// canvas cost SwiftShader ~30 ms a frame with nothing drawn (16 instead of 31 frames/s).
// That canvas is resized only while the still frame is shown (a resize makes Chromium
// wait for the GPU process), so within a drag only the share of splats adapts and the
// resolution follows at the next drag. The still frame is drawn at full resolution into a
// framebuffer, read back without stalling (a pixel-pack buffer and a fence) and shown by
// a 2D canvas.
const LADDER = [[2, 1], [2, 1 / 2], [2, 1 / 4], [3, 1 / 4], [3, 1 / 8], [4, 1 / 8], [4, 1 / 16], [6, 1 / 16], [6, 1 / 32]];
const STILL = [1, 1];

function compile(gl, type, src) {
  const s = gl.createShader(type);
  gl.shaderSource(s, src); gl.compileShader(s);
  if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(`splat shader: ${gl.getShaderInfoLog(s)}`);
  return s;
}

// A linked program and its uniform locations; `feedback`: varyings written by transform feedback.
function program(gl, vs, fs, uniforms, feedback = null) {
  const p = gl.createProgram();
  gl.attachShader(p, compile(gl, gl.VERTEX_SHADER, vs));
  gl.attachShader(p, compile(gl, gl.FRAGMENT_SHADER, fs));
  if (feedback) gl.transformFeedbackVaryings(p, feedback, gl.INTERLEAVED_ATTRIBS);
  gl.linkProgram(p);
  if (!gl.getProgramParameter(p, gl.LINK_STATUS)) throw new Error(`splat program: ${gl.getProgramInfoLog(p)}`);
  return { p, loc: Object.fromEntries(uniforms.map((n) => [n, gl.getUniformLocation(p, n)])) };
}

function readHeader(buf, magic) {
  const dv = new DataView(buf);
  const got = String.fromCharCode(...new Uint8Array(buf, 0, 4));
  if (buf.byteLength < 32 || got !== magic) throw new Error(`bad ${magic} data from the server`);
  const hex = (o) => dv.getUint32(o + 4, true).toString(16).padStart(8, '0') + dv.getUint32(o, true).toString(16).padStart(8, '0');
  return { count: dv.getUint32(8, true), third: dv.getUint32(12, true), a: hex(16), b: dv.getUint32(24, true) + 2 ** 32 * dv.getUint32(28, true) };
}

// The camera of an orbit spec ({eye, target, up, fov (horizontal, degrees)}) as
// Camera::look_at builds it: z forward, x = z cross up, y = z cross x (image down).
export function lookAt(spec, width, height) {
  const sub = (p, q) => p.map((v, i) => v - q[i]);
  const cross = (p, q) => [p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0]];
  const norm = (p) => { const l = Math.hypot(...p) || 1; return p.map((v) => v / l); };
  const z = norm(sub(spec.target, spec.eye)), x = norm(cross(z, spec.up)), y = cross(z, x);
  const R = [...x, ...y, ...z];
  const t = [0, 1, 2].map((r) => -(R[3 * r] * spec.eye[0] + R[3 * r + 1] * spec.eye[1] + R[3 * r + 2] * spec.eye[2]));
  const f = (0.5 * width) / Math.tan((spec.fov * Math.PI) / 360);
  return { R, t, fx: f, fy: f, width, height };
}

export class SplatRenderer {
  // Null when the browser has no WebGL2 (the page falls back to server renders). Puts its
  // two canvases into `container`: the still frame (2D) and the frames while moving (WebGL).
  static create(container, background) {
    const canvas = document.createElement('canvas');
    const gl = canvas.getContext('webgl2', { antialias: false, alpha: false, depth: false, stencil: false, powerPreference: 'high-performance' });
    if (!gl) return null;
    const still = document.createElement('canvas');
    canvas.className = 'moving hidden'; still.className = 'still';
    container.replaceChildren(still, canvas);
    return new SplatRenderer(canvas, gl, background, still);
  }

  constructor(canvas, gl, background, still) {
    Object.assign(this, { canvas, gl, background, still });
    this.count = 0; this.drawCount = 0; this.camera = null; this.tint = 0.5; this.drawnSize = [0, 0];
    this.targets = {}; this.readback = null; this.pbo = null; this.pboBytes = 0;
    this.moving = false; this.level = 5; this.canvasDiv = LADDER[5][0]; this.window = null; this.moves = 0; this.fingerprint = null; this.maskRevision = -1;
    this.frames = 0; this.lastFrame = 0; this.colourScale = 1; this.dirty = false; this.onDraw = null;
    this.subsetWhileMoving = true;
    this.project = program(gl, projectVS(ROW), NOTHING_FS,
      ['u_splats', 'u_mask', 'u_order', 'u_R', 'u_t', 'u_focal', 'u_size', 'u_tan', 'u_tint', 'u_colour_scale'],
      ['v_a', 'v_b']);
    this.quads = program(gl, QUAD_VS, SPLAT_FS, ['u_proj', 'u_size', 'u_colour_scale']);
    this.feedback = gl.createTransformFeedback();
    this.projBuf = gl.createBuffer();  // footprints, 32 bytes per drawn splat
    this.projTex = gl.createTexture();  // the same as a RGBA32F texture, 2 texels per splat
    this.projRows = 0;
    this.vao = gl.createVertexArray();  // no attributes: everything comes from textures
    this.orderTex = gl.createTexture();
    this.splatTex = gl.createTexture();
    this.maskTex = gl.createTexture();
    this.worker = new Worker('/js/sort_worker.js', { type: 'module' });
    this.sortId = 0; this.sortBusy = false; this.sortWanted = false; this.sortSent = 0; this.firstSortOfScene = 0;
    this.worker.onmessage = (e) => this.sorted(e.data);
    // Running totals for profiling (tests/e2e/profile_orbit.mjs reads them); the tests read
    // the exact picture through window.__splatRenderer.snapshot().
    this.stats = { sorts: 0, sortMs: 0, shadeMs: 0, roundTripMs: 0, uploadMs: 0, drawMs: 0, frames: 0 };
    // ?sh=D draws at most SH degree D.
    const cap = new URLSearchParams(location.search).get('sh');
    this.maxShDegree = cap !== null && /^[0-3]$/.test(cap) ? Number(cap) : 3;
    window.__splatRenderer = this;
  }

  // Fetches the scene's splats when its fingerprint is not the one loaded (one fetch at a
  // time: the status poll and a display action may both ask).
  load(fingerprint = null) {
    if (fingerprint && fingerprint === this.fingerprint) return Promise.resolve();
    if (this.loading && (!fingerprint || fingerprint === this.loadingFingerprint)) return this.loading;
    this.loadingFingerprint = fingerprint;
    this.loading = this.fetchSplats().finally(() => { this.loading = null; });
    return this.loading;
  }

  async fetchSplats() {
    const res = await fetch('/api/splats', { cache: 'no-store' });
    if (!res.ok) throw new Error(`splats: ${res.status}`);
    const buf = await res.arrayBuffer();
    const h = readHeader(buf, 'ISGS'), dv = new DataView(buf);
    const n = h.count, shDegree = dv.getUint32(24, true), shBytes = dv.getUint32(28, true);
    const rangeAt = 32 + 40 * n, shAt = rangeAt + 8;
    if (dv.getUint32(4, true) !== 3 || h.third !== 40 || shDegree > 3 || shBytes !== 3 * ((shDegree + 1) ** 2 - 1) ||
        buf.byteLength !== shAt + (shDegree ? 16 + shBytes * n : 0)) throw new Error('splats: unexpected record layout');
    // The colour bytes' range [lo, hi]: base colours above 1 blend as such (as in the
    // rasteriser), so the drawn colours are bytes over [0, hi] and the shaders scale by hi.
    const colourRange = Array.from(new Float32Array(buf, rangeAt, 2));
    this.colourScale = colourRange[1];
    const src = new Uint32Array(buf, 32, 10 * n), f = new Float32Array(buf, 32, 10 * n);
    const colors = new Uint32Array(n);
    // The SH rest as signed bytes (q - 128, the server's q = round(127 c / s) + 128).
    const shScales = shDegree ? Array.from(new Float32Array(buf, shAt, 3)) : [0, 0, 0];
    const shRest = shDegree ? new Int8Array(buf.slice(shAt + 16)) : null;
    if (shRest) for (let k = 0; k < shRest.length; ++k) shRest[k] ^= -128;
    this.shDegree = shDegree; this.bytes = buf.byteLength;
    const rows = Math.max(1, Math.ceil(n / ROW));
    const texels = new Uint32Array(ROW * 3 * 4 * rows);
    const positions = new Float32Array(3 * n), score = new Float32Array(n);
    for (let i = 0; i < n; ++i) {
      const s = 10 * i, d = 12 * i;
      texels.set(src.subarray(s, s + 4), d);
      texels.set(src.subarray(s + 4, s + 8), d + 4);
      texels[d + 8] = src[s + 8]; texels[d + 9] = src[s + 9];
      positions[3 * i] = f[s]; positions[3 * i + 1] = f[s + 1]; positions[3 * i + 2] = f[s + 2];
      colors[i] = src[s + 3];
      // Importance for drawing a subset while moving: opacity x (squared) size.
      score[i] = (src[s + 3] >>> 24) * (f[s + 4] + f[s + 7] + f[s + 9]);
    }
    const importance = new Uint32Array(n).map((_, i) => i).sort((a, b) => score[b] - score[a]);
    const gl = this.gl;
    gl.bindTexture(gl.TEXTURE_2D, this.splatTex);
    gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA32UI, ROW * 3, rows, 0, gl.RGBA_INTEGER, gl.UNSIGNED_INT, texels);
    for (const p of [gl.TEXTURE_MIN_FILTER, gl.TEXTURE_MAG_FILTER]) gl.texParameteri(gl.TEXTURE_2D, p, gl.NEAREST);
    this.count = n; this.drawCount = 0; this.fingerprint = h.a;
    this.setMaskBytes(new Uint8Array(n), -1);  // nothing selected until the mask arrives
    const transfer = [positions.buffer, importance.buffer, colors.buffer].concat(shRest ? [shRest.buffer] : []);
    this.worker.postMessage({ type: 'init', positions, importance, colors, colourRange, shDegree, maxDegree: this.maxShDegree, shRest,
      shScales },
      transfer);
    this.firstSortOfScene = this.sortId + 1;  // earlier answers index the previous scene
    this.requestSort();
  }

  // Selection and hidden flags (/api/selection/mask); reloads the splats first when the
  // mask is of another scene.
  async loadMask() {
    const res = await fetch('/api/selection/mask', { cache: 'no-store' });
    if (!res.ok) throw new Error(`selection mask: ${res.status}`);
    const buf = await res.arrayBuffer();
    const h = readHeader(buf, 'ISGM');
    if (h.a !== this.fingerprint || h.count !== this.count) await this.load(h.a);
    if (h.count !== this.count) return null;  // the scene changed again meanwhile
    this.setMaskBytes(new Uint8Array(buf, 32, h.count), h.b);
    this.worker.postMessage({ type: 'hidden', flags: h.third > 0 ? new Uint8Array(buf.slice(32)) : null });
    this.requestSort();
    return { hidden: h.third, revision: h.b };
  }

  setMaskBytes(bytes, revision) {
    const gl = this.gl, rows = Math.max(1, Math.ceil(bytes.length / 2048));
    const data = new Uint8Array(2048 * rows);
    data.set(bytes);
    gl.bindTexture(gl.TEXTURE_2D, this.maskTex);
    gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
    gl.texImage2D(gl.TEXTURE_2D, 0, gl.R8UI, 2048, rows, 0, gl.RED_INTEGER, gl.UNSIGNED_BYTE, data);
    for (const p of [gl.TEXTURE_MIN_FILTER, gl.TEXTURE_MAG_FILTER]) gl.texParameteri(gl.TEXTURE_2D, p, gl.NEAREST);
    this.maskRevision = revision;
    this.redraw();
  }

  // `tint`: 0 (highlight off) to 1 (selection drawn magenta).
  setTint(tint) { this.tint = tint; this.redraw(); }

  // The highest SH degree drawn (0: base colour only; tests/e2e/sh_steps.mjs compares).
  setMaxShDegree(max) {
    this.maxShDegree = max;
    this.worker.postMessage({ type: 'maxDegree', max });
    this.requestSort();
  }

  // `camera`: {R (row-major world-to-camera), t, fx, fy, width, height}.
  setCamera(camera) {
    this.camera = camera;
    this.moves = (this.moves || 0) + 1;
    this.requestSort();
    this.redraw();
  }

  // The quality step in use: full when still (or with subsetWhileMoving off).
  step() { return this.moving && this.subsetWhileMoving ? [this.canvasDiv, LADDER[this.level][1]] : STILL; }

  // While moving, a lower resolution and the most important splats only (the step the last
  // movement settled on); when still, everything at full resolution.
  setMoving(on) {
    if (on === this.moving) return;
    this.moving = on;
    this.window = null;
    this.requestSort();
    this.redraw();
  }

  // A sort is sent from the next frame, at most one in flight: sorting (and uploading the
  // answer) once per pointer event instead ran ~15 sorts and uploads per drawn frame,
  // which kept SwiftShader's GPU thread busy with uploads (tests/e2e/profile_orbit.mjs).
  requestSort() {
    this.sortWanted = true;
    this.redraw();
  }

  sendSort() {
    if (!this.sortWanted || this.sortBusy || !this.camera || !this.count) return;
    // While moving, at most ~12 sorts a second: between them the order of a few degrees
    // ago is still nearly right, and the worker's CPU time is the page's to draw with.
    const wait = this.sortSent + SORT_INTERVAL_MS - performance.now();
    if (this.moving && wait > 0) {
      if (!this.sortTimer) this.sortTimer = setTimeout(() => { this.sortTimer = null; this.sendSort(); }, wait);
      return;
    }
    this.sortBusy = true; this.sortWanted = false;
    this.sortSent = performance.now();
    const c = this.camera;
    this.worker.postMessage({ type: 'sort', rot: c.R, t: c.t, tanX: c.width / (2 * c.fx), tanY: c.height / (2 * c.fy),
      near: NEAR, limit: Math.max(1, Math.round(this.count * this.step()[1])), id: ++this.sortId });
  }

  sorted({ order, drawn, ms, msShade, id }) {
    this.sortBusy = false;
    const st = this.stats, t0 = performance.now();
    st.sorts++; st.sortMs += ms; st.shadeMs += msShade; st.roundTripMs += t0 - this.sortSent;
    if (id < this.firstSortOfScene) { this.sendSort(); return; }
    this.sortMs = ms;
    const gl = this.gl, rows = Math.max(1, Math.ceil(this.count / ORDER_ROW));
    gl.bindTexture(gl.TEXTURE_2D, this.orderTex);
    if (this.orderRows !== rows) {  // sized for every splat once per scene, then updated in place
      gl.texImage2D(gl.TEXTURE_2D, 0, gl.RG32UI, ORDER_ROW, rows, 0, gl.RG_INTEGER, gl.UNSIGNED_INT, null);
      for (const p of [gl.TEXTURE_MIN_FILTER, gl.TEXTURE_MAG_FILTER]) gl.texParameteri(gl.TEXTURE_2D, p, gl.NEAREST);
      this.orderRows = rows;
    }
    // Only the drawn entries (two words each) are uploaded.
    const full = Math.floor(drawn / ORDER_ROW), rest = drawn - ORDER_ROW * full;
    if (full) gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, 0, ORDER_ROW, full, gl.RG_INTEGER, gl.UNSIGNED_INT, order, 0);
    if (rest) gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, full, rest, 1, gl.RG_INTEGER, gl.UNSIGNED_INT, order, 2 * ORDER_ROW * full);
    this.worker.postMessage({ type: 'recycle', buffer: order }, [order.buffer]);
    st.uploadMs += performance.now() - t0;
    this.drawCount = drawn;
    this.redraw();
  }

  redraw() {
    if (this.dirty) return;
    this.dirty = true;
    requestAnimationFrame(() => this.frame());
  }

  // One frame in flight: while the GPU (SwiftShader's thread, on a machine without GPU)
  // has not finished the previous frame, check again a few ms later instead of queueing
  // another; frames queued behind it were drawn and then never shown. (Waiting for the
  // next animation frame instead rounded every frame up to a multiple of the display's
  // interval: a 40 ms frame took 50.)
  frame() {
    const gl = this.gl;
    if (!this.gpuIdle()) {
      this.stats.waits = (this.stats.waits || 0) + 1;
      setTimeout(() => this.frame(), 3);
      return;
    }
    this.dirty = false;
    // A drag just started: the order still holds every splat (hundreds of ms to draw in
    // software GL); keep the still frame shown until the sort of the subset arrives.
    const wanted = Math.round(this.count * this.step()[1]);
    if (this.moving && this.drawCount > 2 * wanted && (this.sortBusy || this.sortWanted)) { this.sendSort(); return; }
    const t0 = performance.now();
    this.draw();
    this.fence = gl.fenceSync(gl.SYNC_GPU_COMMANDS_COMPLETE, 0);
    gl.flush();
    this.stats.drawMs += performance.now() - t0; this.stats.frames++;
    this.sendSort();
    this.adapt();
    this.lastFrame = performance.now();
    this.frames++;
    this.onDraw?.();
    if (this.readback) this.pollReadback();
  }

  // Whether the last frame is done on the GPU (its fence signalled); finishes the still
  // frame's read back then.
  gpuIdle() {
    const gl = this.gl;
    if (!this.fence) return true;
    if (gl.getSyncParameter(this.fence, gl.SYNC_STATUS) !== gl.SIGNALED) return false;
    gl.deleteSync(this.fence);
    this.fence = null;
    if (this.readback) this.finishReadback();
    return true;
  }

  // The still frame's pixels arrive without a redraw asking for them: check every animation frame.
  pollReadback() {
    if (this.polling) return;
    this.polling = true;
    const poll = () => {
      if (!this.readback) { this.polling = false; return; }
      if (this.gpuIdle()) { this.polling = false; return; }
      requestAnimationFrame(poll);
    };
    requestAnimationFrame(poll);
  }

  // The still frame (read into the pixel-pack buffer) onto the 2D canvas, which then
  // replaces the moving canvas in the view.
  finishReadback() {
    const gl = this.gl, { w, h } = this.readback;
    this.readback = null;
    if (!this.pixels || this.pixels.length !== 4 * w * h) this.pixels = new Uint8Array(4 * w * h);
    gl.bindBuffer(gl.PIXEL_PACK_BUFFER, this.pbo);
    gl.getBufferSubData(gl.PIXEL_PACK_BUFFER, 0, this.pixels, 0, 4 * w * h);
    gl.bindBuffer(gl.PIXEL_PACK_BUFFER, null);
    if (this.still.width !== w || this.still.height !== h) { this.still.width = w; this.still.height = h; this.stillCtx = null; }
    this.stillCtx ||= this.still.getContext('2d', { alpha: false });
    if (!this.image || this.image.width !== w || this.image.height !== h) this.image = new ImageData(w, h);
    const row = 4 * w, img = this.image.data, px = this.pixels;
    for (let y = 0; y < h; ++y) img.set(px.subarray((h - 1 - y) * row, (h - y) * row), y * row);  // bottom row first
    this.stillCtx.putImageData(this.image, 0, 0);
    this.show(true);
    // The moving canvas, hidden now, takes the resolution the last drag settled on.
    this.canvasDiv = LADDER[this.level][0];
    this.fitCanvas(this.subsetWhileMoving ? this.canvasDiv : 1);
    this.onDraw?.();
  }

  // Which canvas the view shows: the still frame (2D) or the frames drawn while moving.
  show(still) {
    if (this.showing === still) return;
    this.showing = still;
    this.still.classList.toggle('hidden', !still);
    this.canvas.classList.toggle('hidden', still);
  }

  // While moving, every ~0.4 s: when the camera moved more often than frames were drawn
  // (drawing is the bottleneck) and under 20 frames/s, one step down the ladder; when
  // drawing kept up and at 25 frames/s or more, one step up.
  adapt() {
    const now = performance.now();
    if (!this.moving || !this.subsetWhileMoving) { this.window = null; return; }
    if (!this.window) { this.window = { t0: now, frames: 0, moves: this.moves }; return; }
    const w = this.window;
    w.frames++;
    const elapsed = now - w.t0;
    if (elapsed < 400) return;
    const fps = (1000 * w.frames) / elapsed, moves = this.moves - w.moves;
    const was = this.level;
    if (moves > 1.2 * w.frames && fps < 20 && this.level < LADDER.length - 1) this.level++;
    else if (moves <= 1.2 * w.frames && fps >= 25 && this.level > 0) this.level--;
    if (this.level !== was) this.requestSort();
    this.window = { t0: now, frames: 0, moves: this.moves };
  }

  // Still (or ?full): every splat at the camera's resolution into a framebuffer, read back
  // into the 2D canvas once done (finishReadback). Moving: the step's resolution into the
  // WebGL canvas (half the camera's size), directly or through a smaller framebuffer
  // blitted (scaled) onto it. The canvas is resized only when the camera's size changes:
  // a resize makes Chromium wait for the GPU process (~170 ms on SwiftShader).
  draw() {
    const c = this.camera;
    if (!c) return;
    if (!this.moving) {
      this.renderInto(this.target('full', c.width, c.height), c);
      this.startReadback(c.width, c.height);
      return;
    }
    this.fitCanvas(this.subsetWhileMoving ? this.canvasDiv : 1);
    const w = this.canvas.width, h = this.canvas.height;
    this.renderInto(null, { ...c, width: w, height: h, fx: (c.fx * w) / c.width, fy: (c.fy * h) / c.height });
    this.readback = null;  // a still frame still on its way is no longer the view
    this.show(false);
  }

  // The moving canvas at the camera's size / div (unchanged when it already is).
  fitCanvas(div) {
    const c = this.camera;
    if (!c) return;
    const w = Math.max(16, Math.round(c.width / div)), h = Math.max(16, Math.round(c.height / div));
    if (this.canvas.width !== w || this.canvas.height !== h) { this.canvas.width = w; this.canvas.height = h; }
  }

  // Clears framebuffer `fb` (null: the canvas) and draws the splats for camera `c` (its size).
  renderInto(fb, c) {
    const gl = this.gl, bg = this.background;
    this.drawnSize = [c.width, c.height];
    gl.bindFramebuffer(gl.FRAMEBUFFER, fb);
    gl.viewport(0, 0, c.width, c.height);
    gl.clearColor(bg[0], bg[1], bg[2], 1);
    gl.clear(gl.COLOR_BUFFER_BIT);
    if (this.drawCount) this.drawSplats(c);
  }

  // The pixels of the 'full' framebuffer into the pixel-pack buffer (on the GPU, no wait).
  startReadback(w, h) {
    const gl = this.gl;
    if (!this.pbo) this.pbo = gl.createBuffer();
    gl.bindBuffer(gl.PIXEL_PACK_BUFFER, this.pbo);
    if (this.pboBytes !== 4 * w * h) { gl.bufferData(gl.PIXEL_PACK_BUFFER, 4 * w * h, gl.STREAM_READ); this.pboBytes = 4 * w * h; }
    gl.bindFramebuffer(gl.READ_FRAMEBUFFER, this.targets.full.fb);
    gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, 0);
    gl.bindBuffer(gl.PIXEL_PACK_BUFFER, null);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    this.readback = { w, h };
  }

  // A framebuffer by name (its renderbuffer reallocated when the size changes).
  target(name, w, h) {
    const gl = this.gl;
    const L = (this.targets[name] ||= { fb: gl.createFramebuffer(), rb: gl.createRenderbuffer(), w: 0, h: 0 });
    if (L.w !== w || L.h !== h) {
      gl.bindRenderbuffer(gl.RENDERBUFFER, L.rb);
      gl.renderbufferStorage(gl.RENDERBUFFER, gl.RGBA8, w, h);
      gl.bindFramebuffer(gl.FRAMEBUFFER, L.fb);
      gl.framebufferRenderbuffer(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.RENDERBUFFER, L.rb);
      Object.assign(L, { w, h });
    }
    return L.fb;
  }

  // The two passes (footprints, then quads) into the bound framebuffer for camera `c`.
  drawSplats(c) {
    const gl = this.gl;
    const n = this.drawCount;
    gl.bindVertexArray(this.vao);
    // 1. Footprints: one vertex per splat into projBuf, nothing rasterised.
    const rows = Math.max(1, Math.ceil(this.count / PROJ_ROW));
    if (this.projRows !== rows) {  // sized for every splat once per scene
      gl.bindBuffer(gl.ARRAY_BUFFER, this.projBuf);
      gl.bufferData(gl.ARRAY_BUFFER, 32 * PROJ_ROW * rows, gl.DYNAMIC_COPY);
      gl.bindBuffer(gl.ARRAY_BUFFER, null);
      // Immutable storage: ANGLE copies a pixel-unpack buffer into it on the GPU.
      gl.deleteTexture(this.projTex);
      this.projTex = gl.createTexture();
      gl.activeTexture(gl.TEXTURE3); gl.bindTexture(gl.TEXTURE_2D, this.projTex);
      gl.texStorage2D(gl.TEXTURE_2D, 1, gl.RGBA32F, 2 * PROJ_ROW, rows);
      for (const p of [gl.TEXTURE_MIN_FILTER, gl.TEXTURE_MAG_FILTER]) gl.texParameteri(gl.TEXTURE_2D, p, gl.NEAREST);
      this.projRows = rows;
    }
    const P = this.project, L = P.loc;
    gl.useProgram(P.p);
    gl.activeTexture(gl.TEXTURE0); gl.bindTexture(gl.TEXTURE_2D, this.splatTex);
    gl.activeTexture(gl.TEXTURE1); gl.bindTexture(gl.TEXTURE_2D, this.maskTex);
    gl.activeTexture(gl.TEXTURE2); gl.bindTexture(gl.TEXTURE_2D, this.orderTex);
    gl.uniform1i(L.u_splats, 0); gl.uniform1i(L.u_mask, 1); gl.uniform1i(L.u_order, 2);
    gl.uniformMatrix3fv(L.u_R, true, c.R);
    gl.uniform3fv(L.u_t, c.t);
    gl.uniform2f(L.u_focal, c.fx, c.fy);
    gl.uniform2f(L.u_size, c.width, c.height);
    gl.uniform2f(L.u_tan, c.width / (2 * c.fx), c.height / (2 * c.fy));
    gl.uniform1f(L.u_tint, this.tint);
    gl.uniform1f(L.u_colour_scale, this.colourScale);
    gl.enable(gl.RASTERIZER_DISCARD);
    gl.bindTransformFeedback(gl.TRANSFORM_FEEDBACK, this.feedback);
    gl.bindBufferBase(gl.TRANSFORM_FEEDBACK_BUFFER, 0, this.projBuf);
    gl.beginTransformFeedback(gl.POINTS);
    gl.drawArrays(gl.POINTS, 0, n);
    gl.endTransformFeedback();
    gl.bindBufferBase(gl.TRANSFORM_FEEDBACK_BUFFER, 0, null);
    gl.bindTransformFeedback(gl.TRANSFORM_FEEDBACK, null);
    gl.disable(gl.RASTERIZER_DISCARD);
    // The footprints into the float texture (a copy between GPU buffers, no read back).
    gl.activeTexture(gl.TEXTURE3); gl.bindTexture(gl.TEXTURE_2D, this.projTex);
    gl.bindBuffer(gl.PIXEL_UNPACK_BUFFER, this.projBuf);
    const full = Math.floor(n / PROJ_ROW), rest = n - PROJ_ROW * full;
    if (full) gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, 0, 2 * PROJ_ROW, full, gl.RGBA, gl.FLOAT, 0);
    if (rest) gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, full, 2 * rest, 1, gl.RGBA, gl.FLOAT, 32 * PROJ_ROW * full);
    gl.bindBuffer(gl.PIXEL_UNPACK_BUFFER, null);
    // 2. Quads, blended far to near.
    const Q = this.quads;
    gl.useProgram(Q.p);
    gl.uniform1i(Q.loc.u_proj, 3);
    gl.uniform2f(Q.loc.u_size, c.width, c.height);
    gl.uniform1f(Q.loc.u_colour_scale, this.colourScale);
    gl.enable(gl.BLEND);
    gl.blendFunc(gl.ONE, gl.ONE_MINUS_SRC_ALPHA);
    gl.drawArrays(gl.TRIANGLES, 0, 6 * n);
    gl.bindVertexArray(null);
  }

  // The still picture at the camera's size as RGBA bytes (drawn and read at once).
  snapshot() {
    const gl = this.gl, c = this.camera, w = c.width, h = c.height, px = new Uint8Array(4 * w * h);
    this.renderInto(this.target('full', w, h), c);
    gl.bindFramebuffer(gl.READ_FRAMEBUFFER, this.targets.full.fb);
    gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, px);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    return { width: w, height: h, data: px };  // bottom row first
  }
}
