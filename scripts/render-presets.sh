#!/usr/bin/env bash
# Renders every bundled preset on the built-in head into docs/presets/NAME.png with the editor's
# own renderer (`wisp --render`, headless under xvfb-run), as shown in the README.
#   scripts/render-presets.sh [SIZE] [SETTLE_SECONDS]      defaults: 320x320, 2 s
set -euo pipefail
cd "$(dirname "$0")/.."
size="${1:-320x320}"
settle="${2:-2}"
wisp="build/app/wisp"
[ -x "$wisp" ] || { echo "build the editor first: cmake --build build --target wisp" >&2; exit 1; }
mkdir -p docs/presets
for preset in resources/presets/*.json; do
    name="$(basename "$preset" .json)"
    xvfb-run -a -s "-screen 0 1600x1000x24" "$wisp" --render "docs/presets/$name.png" \
        --preset "$preset" --size "$size" --settle "$settle"
done
