#!/usr/bin/env bash
# Quick start 2: set up, build, and run the whole test suite with ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
cd "${ISEGMAN_BUILD_DIR:-build}"
ctest --output-on-failure -j 2 "$@"
