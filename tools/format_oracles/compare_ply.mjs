// Compares two INRIA-layout float PLYs Gaussian by Gaussian (matched by nearest centre,
// since tools may reorder) and checks per-attribute tolerances.
//   node compare_ply.mjs SOURCE.ply OTHER.ply pos,logscale,alpha,rot,dc,sh [flip]
// `flip`: OTHER holds y and z negated (a reader that skipped SPZ's RUB -> RDF step); it is
// flipped back (positions, rotations, odd SH coefficients) before comparing.
// Prints the maximum errors; exits 1 when one exceeds its tolerance.
import { readFileSync } from 'fs';

const readPly = (path) => {
  const buf = readFileSync(path);
  const end = buf.indexOf('end_header\n');
  const head = buf.subarray(0, end).toString('latin1').split('\n');
  if (!head.some((l) => l.startsWith('format binary_little_endian'))) throw new Error(`${path}: not binary LE`);
  let n = 0;
  const props = [];
  let inVertex = false;
  for (const l of head) {
    const t = l.trim().split(/\s+/);
    if (t[0] === 'element') { inVertex = t[1] === 'vertex'; if (inVertex) n = Number(t[2]); }
    else if (t[0] === 'property' && inVertex) {
      if (t[1] !== 'float') throw new Error(`${path}: property ${t[2]} is ${t[1]}, expected float`);
      props.push(t[2]);
    }
  }
  const body = new Float32Array(buf.buffer.slice(buf.byteOffset + end + 11, buf.byteOffset + end + 11 + n * props.length * 4));
  const col = (name) => { const k = props.indexOf(name); return k < 0 ? null : (i) => body[i * props.length + k]; };
  return { n, props, col };
};

const [srcPath, otherPath, tolText, flipArg] = process.argv.slice(2);
const tol = tolText.split(',').map(Number);
const a = readPly(srcPath), b0 = readPly(otherPath);
// Signs of SH basis functions 1..15 under (x, y, z) -> (x, -y, -z).
const shSign = [-1, -1, 1, -1, 1, 1, -1, 1, -1, 1, -1, -1, 1, -1, 1];
const b = flipArg !== 'flip' ? b0 : {
  n: b0.n, props: b0.props,
  col: (name) => {
    const c = b0.col(name);
    if (!c) return c;
    if (['y', 'z', 'rot_2', 'rot_3'].includes(name)) return (i) => -c(i);
    const m = /^f_rest_(\d+)$/.exec(name);
    if (m) { const per = b0.props.filter((p) => p.startsWith('f_rest_')).length / 3; const s = shSign[Number(m[1]) % per]; return (i) => s * c(i); }
    return c;
  },
};
if (a.n !== b.n) { console.log(`count ${a.n} vs ${b.n}`); process.exit(1); }
const ax = ['x', 'y', 'z'].map(a.col), bx = ['x', 'y', 'z'].map(b.col);
const sig = (v) => 1 / (1 + Math.exp(-v));
const err = [0, 0, 0, 0, 0, 0];
const rest = a.props.filter((p) => p.startsWith('f_rest_'));
for (let j = 0; j < b.n; j++) {
  let best = Infinity, i = -1;
  for (let k = 0; k < a.n; k++) {
    const d = (ax[0](k) - bx[0](j)) ** 2 + (ax[1](k) - bx[1](j)) ** 2 + (ax[2](k) - bx[2](j)) ** 2;
    if (d < best) { best = d; i = k; }
  }
  const up = (k, c) => { err[k] = Math.max(err[k], c); };
  for (let c = 0; c < 3; c++) {
    up(0, Math.abs(ax[c](i) - bx[c](j)));
    up(1, Math.abs(a.col(`scale_${c}`)(i) - b.col(`scale_${c}`)(j)));
    up(4, Math.abs(a.col(`f_dc_${c}`)(i) - b.col(`f_dc_${c}`)(j)));
  }
  up(2, Math.abs(sig(a.col('opacity')(i)) - sig(b.col('opacity')(j))));
  const qa = [0, 1, 2, 3].map((c) => a.col(`rot_${c}`)(i)), qb = [0, 1, 2, 3].map((c) => b.col(`rot_${c}`)(j));
  const na = Math.hypot(...qa), nb = Math.hypot(...qb);
  const dot = Math.min(1, Math.abs(qa.reduce((s, v, c) => s + v * qb[c], 0) / (na * nb)));
  up(3, 2 * Math.acos(dot));
  for (const p of rest) { const bc = b.col(p); if (bc) up(5, Math.abs(a.col(p)(i) - bc(j))); }
}
const names = ['position', 'log-scale', 'alpha', 'rotation', 'f_dc', 'f_rest'];
let ok = true;
console.log(names.map((nm, k) => {
  const bad = err[k] > tol[k];
  ok &&= !bad;
  return `${nm} ${err[k].toPrecision(3)}${bad ? ` (> ${tol[k]})` : ''}`;
}).join(', '));
process.exit(ok ? 0 : 1);
