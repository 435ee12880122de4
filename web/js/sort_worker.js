// Depth sort and view-dependent colour for the WebGL splat renderer, off the main thread.
// Keeps the splat centres, base colours, SH rest coefficients and an importance order
// (opacity x size, largest first); each request gives the view and how many of the most
// important splats to draw, and gets back, far to near (a 16-bit counting sort of the view
// depths), frustum-culled and hidden ones left out, per drawn splat its index and its
// colour seen from the camera (the SH DC colour plus degrees 1-3, sh.js). One message
// per sort; the main thread hands the buffer back after uploading it.
import { shBasisRest } from './sh.js';

let positions = null;   // Float32Array, 3 per splat
let importance = null;  // Uint32Array: splat indices, most important first
let colors = null;      // Uint32Array: r | g << 8 | b << 16 | a << 24 (DC colour, opacity)
// A colour byte q of `colors` is the base colour lo + span q / 255; drawn colours are bytes
// over [0, hi] (the shaders scale them by hi: colours above 1 blend as in the rasteriser).
let lo = 0, span = 1, hi = 1;
let baseColors = null;  // the base colours as drawn without SH, when `colors` are not already
let shRest = null;      // Int8Array: per splat (K - 1) x 3 quantised coefficients, or null
let shDegree = 0, shCount = 0, shStride = 0;  // degree drawn, its rest coefficients, bytes per splat
let sceneDegree = 0;
const shScale = new Float32Array(15);  // per rest coefficient: its band's scale / 127
let hidden = null;      // Uint8Array of flags (bit 1 hidden), or null
let depths = null, keys = null, candidates = null;
const counts = new Uint32Array(65536), starts = new Uint32Array(65536);
const pool = [];        // answer buffers handed back by the main thread
const basis = new Float32Array(15), weighted = new Float32Array(15);

function sort({ rot, t, tanX, tanY, near, limit, id }) {
  const t0 = performance.now();
  const n = Math.min(limit, importance.length);
  const [r00, r01, r02, r10, r11, r12, r20, r21, r22] = rot;
  const lx = 1.3 * tanX, ly = 1.3 * tanY;
  let m = 0, zmin = Infinity, zmax = -Infinity;
  for (let k = 0; k < n; ++k) {
    const i = importance[k];
    if (hidden && (hidden[i] & 2)) continue;
    const x = positions[3 * i], y = positions[3 * i + 1], z = positions[3 * i + 2];
    const cz = r20 * x + r21 * y + r22 * z + t[2];
    if (cz < near) continue;
    // Culled like the rasteriser's frustum test (centre beyond 1.3x the half field of view).
    const cx = r00 * x + r01 * y + r02 * z + t[0], cy = r10 * x + r11 * y + r12 * z + t[1];
    if (Math.abs(cx) > lx * cz || Math.abs(cy) > ly * cz) continue;
    candidates[m] = i; depths[m] = cz; ++m;
    if (cz < zmin) zmin = cz;
    if (cz > zmax) zmax = cz;
  }
  const scale = zmax > zmin ? 65535 / (zmax - zmin) : 0;
  counts.fill(0);
  for (let k = 0; k < m; ++k) {
    // Far first: the key grows as the depth shrinks.
    const key = 65535 - Math.min(65535, Math.floor((depths[k] - zmin) * scale));
    keys[k] = key; counts[key]++;
  }
  starts[0] = 0;
  for (let b = 1; b < 65536; ++b) starts[b] = starts[b - 1] + counts[b - 1];
  let out = pool.pop();
  if (!out || out.length < 2 * m) out = new Uint32Array(2 * importance.length);
  for (let k = 0; k < m; ++k) out[2 * starts[keys[k]]++] = candidates[k];
  const tSort = performance.now();
  shade(out, m, rot, t);
  postMessage({ order: out, id, drawn: m, considered: n, ms: performance.now() - t0, msShade: performance.now() - tSort },
    [out.buffer]);
}

// Colour of every drawn splat (out[2k] its index) into out[2k + 1]: the DC colour plus
// sum_k basis_k(d) c_k along d = centre - eye (world space, as the rasteriser), clamped.
function shade(out, m, rot, t) {
  if (!shDegree) {
    const base = baseColors || colors;
    for (let k = 0; k < m; ++k) out[2 * k + 1] = base[out[2 * k]];
    return;
  }
  const [r00, r01, r02, r10, r11, r12, r20, r21, r22] = rot;
  const ex = -(r00 * t[0] + r10 * t[1] + r20 * t[2]), ey = -(r01 * t[0] + r11 * t[1] + r21 * t[2]),
    ez = -(r02 * t[0] + r12 * t[1] + r22 * t[2]);
  const K = shCount, stride = shStride, step = span / 255, toByte = 1 / hi;
  for (let k = 0; k < m; ++k) {
    const i = out[2 * k];
    let dx = positions[3 * i] - ex, dy = positions[3 * i + 1] - ey, dz = positions[3 * i + 2] - ez;
    const inv = 1 / (Math.sqrt(dx * dx + dy * dy + dz * dz) || 1);  // Math.hypot is several times slower
    dx *= inv; dy *= inv; dz *= inv;
    shBasisRest(shDegree, dx, dy, dz, basis);
    for (let j = 0; j < K; ++j) weighted[j] = basis[j] * shScale[j];
    const c = colors[i];
    let r = lo + step * (c & 255), g = lo + step * ((c >>> 8) & 255), b = lo + step * ((c >>> 16) & 255);
    for (let j = 0, s = i * stride; j < K; ++j, s += 3) {
      const w = weighted[j];
      r += w * shRest[s]; g += w * shRest[s + 1]; b += w * shRest[s + 2];
    }
    out[2 * k + 1] = (byte(r * toByte) | (byte(g * toByte) << 8) | (byte(b * toByte) << 16) | (c & 0xff000000)) >>> 0;
  }
}

function capDegree(max) { shDegree = Math.min(sceneDegree, max); shCount = (shDegree + 1) ** 2 - 1; }

function byte(v) { return v <= 0 ? 0 : v >= 1 ? 255 : (v * 255 + 0.5) | 0; }

onmessage = (e) => {
  const msg = e.data;
  if (msg.type === 'init') {
    positions = msg.positions; importance = msg.importance; colors = msg.colors; hidden = null;
    [lo, hi] = msg.colourRange; span = hi - lo;
    // Without SH a colour is max(base, 0): re-encoded over [0, hi] unless already so.
    baseColors = lo === 0 ? null : colors.map((c) => {
      const ch = (s) => byte((lo + span * ((c >>> s) & 255) / 255) / hi);
      return (ch(0) | (ch(8) << 8) | (ch(16) << 16) | (c & 0xff000000)) >>> 0;
    });
    // msg.shDegree: the scene's; msg.maxDegree: a cap (?sh=D), read as a prefix (as the rasteriser's sh_degree).
    shStride = 3 * ((msg.shDegree + 1) ** 2 - 1); shRest = msg.shRest; sceneDegree = msg.shDegree;
    capDegree(msg.maxDegree);
    for (let j = 0; j < shCount; ++j) shScale[j] = msg.shScales[j < 3 ? 0 : j < 8 ? 1 : 2] / 127;
    const n = importance.length;
    depths = new Float32Array(n); keys = new Uint16Array(n); candidates = new Uint32Array(n);
    pool.length = 0;
  } else if (msg.type === 'maxDegree') {
    capDegree(msg.max);
  } else if (msg.type === 'hidden') {
    hidden = msg.flags;
  } else if (msg.type === 'recycle') {
    if (importance && msg.buffer.length === 2 * importance.length) pool.push(msg.buffer);
  } else if (msg.type === 'sort' && positions) {
    sort(msg);
  }
};
