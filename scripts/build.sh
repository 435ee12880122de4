#!/usr/bin/env bash
# Configures (once) and builds isegman into build/ with Ninja on both cores.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR="${ISEGMAN_BUILD_DIR:-build}"
# ccache (installed by setup.sh) makes rebuilds in fresh clones and worktrees cheap; the
# base dir lets clones at different paths share cache entries.
LAUNCHER=()
if command -v ccache >/dev/null 2>&1; then
  export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$(cd .. && pwd)}"
  LAUNCHER=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
if [ ! -f "$BUILD_DIR/build.ninja" ]; then
  cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=Release "${LAUNCHER[@]}"
fi
cmake --build "$BUILD_DIR" -j "${ISEGMAN_JOBS:-2}"
