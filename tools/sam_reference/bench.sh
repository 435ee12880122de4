#!/usr/bin/env bash
# SAM benchmark: isegman's libtorch engine and ONNX Runtime (onnxruntime-node) on the same
# ONNX files, images, prompts and machine, one after the other; prints both and the ratio.
#   tools/sam_reference/bench.sh [--runs N] [image.png ...]
# Needs: the models (scripts/setup.sh), sam_bench built (build-models/ or build/), and
# `npm i --ignore-scripts` in tools/sam_reference (dev-only; never needed by the tests).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
runs=3
if [ "${1:-}" = "--runs" ]; then runs="$2"; shift 2; fi
images=("$@")
if [ ${#images[@]} -eq 0 ]; then
  images=("$root/../shared/fixtures/fern/images/image000.png" "$root/../shared/fixtures/dtu24/images/000000.png")
fi
bench=""
for b in "$root/build-models/sam_bench" "$root/build/sam_bench"; do [ -x "$b" ] && { bench="$b"; break; }; done
[ -n "$bench" ] || { echo "bench.sh: build sam_bench first (ninja -C build-models sam_bench)" >&2; exit 1; }
[ -d "$here/node_modules/onnxruntime-node" ] || (cd "$here" && npm i --ignore-scripts --no-audit --no-fund >/dev/null)
export OMP_WAIT_POLICY="${OMP_WAIT_POLICY:-PASSIVE}"
threads="$(nproc)"
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)"
echo "images: ${images[*]}"
cpp="$("$bench" time --runs "$runs" --threads "$threads" "${images[@]}")"
list="$(IFS=,; echo "${images[*]}")"
ort="$(node "$here/bench_ort.mjs" --bench "$bench" --images "$list" --runs "$runs" --threads "$threads")"
node -e '
const c = JSON.parse(process.argv[1]), o = JSON.parse(process.argv[2]);
const f = (v) => v.toFixed(1).padStart(9);
console.log("                     isegman (libtorch)   onnxruntime-node   ratio (isegman / ORT)");
console.log(`encoder ms / image  ${f(c.encoder_ms)}          ${f(o.encoder_ms)}          ${(c.encoder_ms / o.encoder_ms).toFixed(2)}`);
console.log(`decoder ms / prompt ${f(c.decoder_ms)}          ${f(o.decoder_ms)}          ${(c.decoder_ms / o.decoder_ms).toFixed(2)}`);
console.log(`(medians over ${c.encoder_runs} encoder runs and ${c.decoder_runs} decoder runs each; goal: encoder ratio <= 1.5, decoder < 50 ms)`);
' "$cpp" "$ort"
