// Depth sort for the WebGL splat renderer, off the main thread. Keeps the splat centres
// and an importance order (opacity x size, largest first); each request gives the view
// and how many of the most important splats to draw, and gets back their indices from
// far to near (a 16-bit counting sort of the view depths), frustum-culled, hidden ones
// left out.
let positions = null;   // Float32Array, 3 per splat
let importance = null;  // Uint32Array: splat indices, most important first
let hidden = null;      // Uint8Array of flags (bit 1 hidden), or null
let depths = null, keys = null, candidates = null;
const counts = new Uint32Array(65536), starts = new Uint32Array(65536);

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
  const order = new Uint32Array(m);
  for (let k = 0; k < m; ++k) order[starts[keys[k]]++] = candidates[k];
  postMessage({ order, id, drawn: m, considered: n, ms: performance.now() - t0 }, [order.buffer]);
}

onmessage = (e) => {
  const msg = e.data;
  if (msg.type === 'init') {
    positions = msg.positions; importance = msg.importance; hidden = null;
    const n = importance.length;
    depths = new Float32Array(n); keys = new Uint16Array(n); candidates = new Uint32Array(n);
  } else if (msg.type === 'hidden') {
    hidden = msg.flags;
  } else if (msg.type === 'sort' && positions) {
    sort(msg);
  }
};
