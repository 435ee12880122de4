#!/usr/bin/env bash
# Dev-only format oracles (not run by the tests): npm @playcanvas/splat-transform and
# spz-js, installed with --ignore-scripts into a folder outside the repository.
#   tools/format_oracles/make_reference.sh [--write]
# 1. Makes the 300-Gaussian source PLY and has the tools write .spz (v3, v4; spz-js v2),
#    .compressed.ply and .sog from it; with --write they replace tests/data/formats/
#    (oracle_reference_test reads them back against the source).
# 2. Has isegman write .spz (v2, v3, v4), .compressed.ply and .splat from the source and
#    the tools read them back to PLY, compared with the source within the tolerances.
# Environment: ORACLES (default /tmp/oracles), ISEGMAN (default build/isegman).
set -euo pipefail
cd "$(dirname "$0")/../.."
repo="$PWD"
oracles="${ORACLES:-/tmp/oracles}"
isegman="${ISEGMAN:-$repo/build/isegman}"
here="$repo/tools/format_oracles"
mkdir -p "$oracles"
if [ ! -d "$oracles/node_modules/@playcanvas/splat-transform" ] || [ ! -d "$oracles/node_modules/spz-js" ]; then
  (cd "$oracles" && npm i --ignore-scripts --no-audit --no-fund @playcanvas/splat-transform@2.7.1 spz-js@1.2.5)
fi
cp "$here"/*.mjs "$oracles/"
st() { node "$oracles/node_modules/@playcanvas/splat-transform/bin/cli.mjs" -q -w "$@"; }
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# 1. Tool-written reference files.
node "$oracles/make_source_ply.mjs" "$work/source.ply" 300
st "$work/source.ply" "$work/splat-transform_v4.spz"
st --spz-version 3 "$work/source.ply" "$work/splat-transform_v3.spz"
st "$work/source.ply" "$work/splat-transform.compressed.ply"
st -g cpu "$work/source.ply" "$work/splat-transform.sog"
(cd "$oracles" && node spzjs_convert.mjs "$work/source.ply" "$work/spz-js_v2.spz")
if [ "${1:-}" = "--write" ]; then
  cp "$work"/source.ply "$work"/splat-transform* "$work"/spz-js_v2.spz "$repo/tests/data/formats/"
  echo "make_reference: wrote tests/data/formats/"
fi

# 2. isegman-written files read by the tools. Tolerances (position, log-scale, alpha,
#    rotation rad, f_dc, f_rest) are the formats' quantisation steps.
spz_tol=0.000123,0.0313,0.002,0.005,0.0131,0.0665
status=0
check() {  # check NAME TOLERANCES: compares $work/NAME.back.ply with the source
  printf '%-28s ' "$1"
  node "$oracles/compare_ply.mjs" "$work/source.ply" "$work/$1.back.ply" "$2" || status=1
}
for v in 3 4; do
  "$isegman" convert "$work/source.ply" --out "$work/isegman_v$v.spz" --spz-version $v >/dev/null
  st "$work/isegman_v$v.spz" "$work/isegman_v$v.spz.back.ply"
  check "isegman_v$v.spz" "$spz_tol"
done
"$isegman" convert "$work/source.ply" --out "$work/isegman_v2.spz" --spz-version 2 >/dev/null
(cd "$oracles" && node spzjs_convert.mjs "$work/isegman_v2.spz" "$work/isegman_v2.spz.back.ply")
# spz-js 1.2.5 reads SPZ without the RUB -> RDF step: its y and z come back negated.
printf '%-28s ' "isegman_v2.spz (spz-js)"
node "$oracles/compare_ply.mjs" "$work/source.ply" "$work/isegman_v2.spz.back.ply" \
  0.000123,0.0313,0.002,0.2,0.0131,0.0665 flip || status=1
"$isegman" convert "$work/source.ply" --out "$work/isegman.compressed.ply" >/dev/null
st "$work/isegman.compressed.ply" "$work/isegman.compressed.ply.back.ply"
check "isegman.compressed.ply" 0.0025,0.002,0.002,0.005,0.007,0.0157
"$isegman" convert "$work/source.ply" --out "$work/isegman.sog" >/dev/null
st "$work/isegman.sog" "$work/isegman.sog.back.ply"
check "isegman.sog" 0.0005,0.03,0.002,0.04,0.02,0.01
"$isegman" convert "$work/source.ply" --out "$work/isegman.splat" >/dev/null
st "$work/isegman.splat" "$work/isegman.splat.back.ply"
check "isegman.splat" 0.000001,0.00001,0.002,0.03,0.007,1e9
exit $status
