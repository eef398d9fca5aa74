#!/usr/bin/env bash
# The USD export, read back by an independent reader (TinyUSDZ, tests/usd/check-usda.mjs):
#   - the issue's example: 48 frames of a shaking head, 48 time samples whose point counts match
#     curveVertexCounts, tips moving, the head a Mesh under an animated Xform;
#   - a bake as .usda and as a .hair sequence (with another thread count) agree to 1e-6 m;
#   - the same bake twice gives byte-identical files; a single frame is a still.
#
#   tests/usd/check-usda.sh WISP_CLI TINYUSDZ_DIR
set -euo pipefail
cli=$1
modules=$2
here=$(cd "$(dirname "$0")" && pwd)
"$here/install-tinyusdz.sh" "$modules" || exit $?
export WISP_TINYUSDZ_DIR=$modules
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

"$cli" bake --frames 1:48 --fps 24 --motion shake --out "$work/c.usda" 2> /dev/null
node "$here/check-usda.mjs" "$work/c.usda" --frames 1:48 --head
rm "$work/c.usda"

"$cli" bake --frames 5:8 --motion walk --threads 1 --out "$work/w.usda" 2> /dev/null
"$cli" bake --frames 5:8 --motion walk --threads 2 --out "$work/w.usda.####.hair" 2> /dev/null
node "$here/check-usda.mjs" "$work/w.usda" --frames 5:8 --hair "$work/w.usda.####.hair" --head
"$cli" bake --frames 5:8 --motion walk --threads 2 --out "$work/again.usda" 2> /dev/null
cmp "$work/w.usda" "$work/again.usda"

"$cli" bake --frames 3:3 --motion nod --out "$work/still.usda" 2> /dev/null
node "$here/check-usda.mjs" "$work/still.usda" --frames 3:3 --head
echo "check-usda.sh: all checks passed"
