// Writes a small deterministic INRIA-layout PLY (SH degree 3) for the format oracles:
// a few hundred Gaussians on two blobs, values inside every format's range.
//   node make_source_ply.mjs OUT.ply [count]
import { writeFileSync } from 'fs';

const out = process.argv[2];
const n = Number(process.argv[3] ?? 300);
let s = 0x9e3779b97f4a7c15n;
const next = () => {  // SplitMix64
  s = (s + 0x9e3779b97f4a7c15n) & 0xffffffffffffffffn;
  let z = s;
  z = ((z ^ (z >> 30n)) * 0xbf58476d1ce4e5b9n) & 0xffffffffffffffffn;
  z = ((z ^ (z >> 27n)) * 0x94d049bb133111ebn) & 0xffffffffffffffffn;
  return Number((z ^ (z >> 31n)) >> 11n) / 9007199254740992;
};
const range = (a, b) => a + (b - a) * next();
const props = ['x', 'y', 'z', 'nx', 'ny', 'nz', 'f_dc_0', 'f_dc_1', 'f_dc_2'];
for (let i = 0; i < 45; i++) props.push(`f_rest_${i}`);
props.push('opacity', 'scale_0', 'scale_1', 'scale_2', 'rot_0', 'rot_1', 'rot_2', 'rot_3');
const header = `ply\nformat binary_little_endian 1.0\nelement vertex ${n}\n` +
  props.map((p) => `property float ${p}`).join('\n') + '\nend_header\n';
const body = new Float32Array(n * props.length);
for (let i = 0; i < n; i++) {
  const r = body.subarray(i * props.length, (i + 1) * props.length);
  const c = i % 2 ? [0.8, -0.3, 2.5] : [-0.6, 0.2, 3.0];
  for (let a = 0; a < 3; a++) r[a] = c[a] + range(-0.5, 0.5);
  for (let k = 0; k < 3; k++) r[6 + k] = range(-1.5, 1.5);
  for (let k = 0; k < 45; k++) r[9 + k] = range(-0.3, 0.3);
  r[54] = range(-3, 4);
  for (let k = 0; k < 3; k++) r[55 + k] = range(-5, -2);
  for (let k = 0; k < 4; k++) r[58 + k] = range(-1, 1);
}
writeFileSync(out, Buffer.concat([Buffer.from(header, 'latin1'), Buffer.from(body.buffer)]));
