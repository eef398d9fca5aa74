#!/usr/bin/env bash
# Installs the npm package tinyusdz (a USD parser as WebAssembly), pinned, into a build-local
# folder (DIR/node_modules/tinyusdz) for tests/usd/check-usda.mjs. Safe to run twice: an
# installed copy of the pinned version is kept. Exit 77 (CTest's "skipped") without npm or node, 1 under CI=true.
#
#   tests/usd/install-tinyusdz.sh DIR
set -euo pipefail
dir=$1
version=0.9.0-rc10
if ! command -v node > /dev/null || ! command -v npm > /dev/null; then
  if [ "${CI:-}" = true ]; then
    echo "install-tinyusdz: node and npm are needed for the independent USD reader (scripts/setup.sh installs them); under CI=true that fails" >&2
    exit 1
  fi
  echo "install-tinyusdz: node and npm are needed for the independent USD reader; skipped" >&2
  exit 77
fi
installed=$(node -e "try{console.log(require('$dir/node_modules/tinyusdz/package.json').version)}catch{}" 2>/dev/null || true)
if [ "$installed" != "$version" ]; then
  mkdir -p "$dir"
  npm install --prefix "$dir" --no-audit --no-fund --no-save --loglevel=error "tinyusdz@$version" >&2
fi
