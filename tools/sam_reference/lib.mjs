// Shared helpers of the SAM reference and benchmark scripts (dev-only).
import { execFileSync } from 'node:child_process';
import { readFileSync, mkdtempSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import ort from 'onnxruntime-node';

export const ROOT = resolve(dirname(fileURLToPath(import.meta.url)), '../..');

export function parseArgs(defaults) {
  const a = { ...defaults };
  const argv = process.argv.slice(2);
  for (let i = 0; i < argv.length; i++) {
    const k = argv[i];
    if (!k.startsWith('--')) throw new Error(`unexpected argument ${k}`);
    a[k.slice(2)] = argv[++i];
  }
  return a;
}

export function findBench(explicit) {
  const candidates = explicit ? [explicit] : [join(ROOT, 'build-models/sam_bench'), join(ROOT, 'build/sam_bench')];
  for (const c of candidates) {
    try { readFileSync(c); return c; } catch { /* next */ }
  }
  throw new Error(`sam_bench not found (tried ${candidates.join(', ')}); build it first`);
}

// SAM's preprocessed input for an image, made by the C++ side (the engines are compared on the same tensor).
export function preprocessed(bench, image, transpose) {
  const dir = mkdtempSync(join(tmpdir(), 'samref-'));
  const out = join(dir, 'input.f32');
  const args = ['dump-input', image, out];
  if (transpose) args.push('--transpose');
  const meta = JSON.parse(execFileSync(bench, args, { encoding: 'utf8' }));
  const buf = readFileSync(out);
  meta.input = new Float32Array(buf.buffer, buf.byteOffset, buf.byteLength / 4);
  return meta;
}

export async function sessions(modelsDir, threads) {
  const opts = { intraOpNumThreads: threads, interOpNumThreads: 1, graphOptimizationLevel: 'all', executionMode: 'sequential' };
  const encoder = await ort.InferenceSession.create(join(modelsDir, 'encoder.onnx'), opts);
  const decoder = await ort.InferenceSession.create(join(modelsDir, 'sam.onnx'), opts);
  return { encoder, decoder };
}

export async function encode(s, meta) {
  const size = meta.size;
  const feeds = { [s.encoder.inputNames[0]]: new ort.Tensor('float32', meta.input, [1, 3, size, size]) };
  const out = await s.encoder.run(feeds);
  return out[s.encoder.outputNames[0]];
}

// points: [[x, y, label], ...] in image pixels (SAM convention); previous: Float32Array(256*256) or null.
export async function decode(s, meta, embedding, points, previous) {
  const sx = meta.resized_width / meta.width, sy = meta.resized_height / meta.height;
  const n = points.length + 1;
  const coords = new Float32Array(2 * n), labels = new Float32Array(n);
  points.forEach(([x, y, l], i) => { coords[2 * i] = x * sx; coords[2 * i + 1] = y * sy; labels[i] = l; });
  labels[n - 1] = -1;  // the padding point (0, 0) of the no-box export
  const feeds = {
    image_embeddings: embedding,
    point_coords: new ort.Tensor('float32', coords, [1, n, 2]),
    point_labels: new ort.Tensor('float32', labels, [1, n]),
    mask_input: new ort.Tensor('float32', previous ?? new Float32Array(256 * 256), [1, 1, 256, 256]),
    has_mask_input: new ort.Tensor('float32', new Float32Array([previous ? 1 : 0]), [1]),
    orig_im_size: new ort.Tensor('float32', new Float32Array([meta.height, meta.width]), [2]),
  };
  const out = await s.decoder.run(feeds);
  const iou = out.iou_predictions.data;
  const k = out.masks.dims[1];
  let best = 0;
  for (let i = 1; i < k; i++) if (iou[i] > iou[best]) best = i;
  const hw = meta.width * meta.height;
  const logits = out.masks.data.subarray(best * hw, (best + 1) * hw);
  const low = out.low_res_masks.data.slice(best * 65536, (best + 1) * 65536);
  return { iou: iou[best], best, k, mask: Uint8Array.from(logits, (v) => (v > 0 ? 1 : 0)), low };
}

export function median(v) {
  const s = [...v].sort((a, b) => a - b);
  return s[Math.floor(s.length / 2)];
}
