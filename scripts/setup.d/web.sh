#!/usr/bin/env bash
# Installs the npm dependency of the end-to-end browser test (playwright-core, which
# drives Debian's /usr/bin/chromium from scripts/apt-packages.d/web.txt) into
# tests/e2e/node_modules (git-ignored). Idempotent: nothing happens when the pinned
# version is present. No browser is downloaded (playwright-core has no install script).
set -euo pipefail
cd "$(dirname "$0")/../../tests/e2e"

want="$(node -e 'console.log(require("./package.json").dependencies["playwright-core"])')"
have=""
if [ -f node_modules/playwright-core/package.json ]; then
  have="$(node -e 'console.log(require("./node_modules/playwright-core/package.json").version)')"
fi
if [ "$have" = "$want" ]; then
  echo "web: playwright-core $have present"
  exit 0
fi
command -v npm >/dev/null || { echo "web: npm is needed for the browser test" >&2; exit 1; }
echo "web: installing playwright-core $want into tests/e2e/node_modules"
npm install --no-audit --no-fund --ignore-scripts --no-package-lock --silent
echo "web: playwright-core installed"
