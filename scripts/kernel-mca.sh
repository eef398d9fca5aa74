#!/usr/bin/env bash
# What the solver's particle loop costs on paper: takes groom-1m's block kernel (bending and gusts,
# a still head: advanceBlockAs<false, false, true, true>) for one SIMD target out of a wisp-cli
# binary, cuts out its particle loop (the longest backward conditional jump in the function), and
# runs LLVM's machine-code analyser over it for a CPU model. llvm-mca assumes every load hits L1 and
# every branch is predicted, so its cycles an iteration are what the loop would cost with no stall:
# the floor under what tuning the present instructions can reach (docs/performance-log.md, "What the
# particle loop costs on paper"). An iteration is one particle of one register's lanes (16 at
# AVX-512, 8 at AVX2, 4 at SSE4); the loop's body holds the rarely taken paths laid out in line too.
#
#   scripts/kernel-mca.sh [--target AVX3|AVX2|SSE4] [--mcpu CPU] [BINARY]
#   scripts/kernel-mca.sh --target AVX2 --mcpu znver3 build/app/wisp-cli
#
# Defaults: AVX3 (Highway's name for AVX-512), icelake-server, build/app/wisp-cli. Needs objdump,
# nm, python3 and llvm-mca (Debian: binutils, python3 and llvm-14; a developer's tool, not a build need).
set -euo pipefail

target=AVX3
mcpu=icelake-server
binary=build/app/wisp-cli
while [[ $# -gt 0 ]]; do
    case "$1" in
        --target)
            [[ $# -ge 2 ]] || { echo "kernel-mca: --target needs AVX3, AVX2 or SSE4" >&2; exit 2; }
            target=$2
            shift 2
            ;;
        --mcpu)
            [[ $# -ge 2 ]] || { echo "kernel-mca: --mcpu needs a CPU name (llvm-mca -mcpu=help lists them)" >&2; exit 2; }
            mcpu=$2
            shift 2
            ;;
        --help | -h)
            sed -n '2,15p' "$0" | sed 's/^# \{0,1\}//' >&2
            exit 2
            ;;
        *)
            binary=$1
            shift
            ;;
    esac
done
case "$target" in
    AVX3) lanes=16 ;;
    AVX2) lanes=8 ;;
    SSE4) lanes=4 ;;
    *) echo "kernel-mca: no target '$target' (there are: AVX3, AVX2, SSE4)" >&2; exit 2 ;;
esac
mca=$(command -v llvm-mca || command -v llvm-mca-14 || true)
[[ -n "$mca" ]] || { echo "kernel-mca: llvm-mca not found (Debian: apt-get install llvm-14)" >&2; exit 2; }
[[ -f "$binary" ]] || { echo "kernel-mca: no binary at $binary (build first: scripts/setup.sh)" >&2; exit 2; }

symbol="wisp::N_${target}::(anonymous namespace)::advanceBlockAs<false, false, true, true>"
read -r start size < <(nm -S -C "$binary" | grep -F "$symbol" | awk '{ print $1, $2; exit }') || true
[[ -n "${start:-}" ]] || { echo "kernel-mca: $binary has no $symbol" >&2; exit 1; }

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
objdump -d --no-show-raw-insn --start-address=$((16#$start)) --stop-address=$((16#$start + 16#$size)) \
    "$binary" > "$work/function.s"

python3 - "$work/function.s" "$work/loop.s" <<'EOF'
import re
import sys

instructions = []
for line in open(sys.argv[1]):
    m = re.match(r'\s+([0-9a-f]+):\s+(\S+)\s*(.*)', line)
    if m:
        instructions.append((int(m.group(1), 16), m.group(2), m.group(3)))
# The particle loop: the backward conditional jump that spans the most code.
best = None
for address, op, args in instructions:
    m = re.match(r'([0-9a-f]+) <', args)
    if op.startswith('j') and op != 'jmp' and m:
        to = int(m.group(1), 16)
        if to < address and (best is None or address - to > best[1] - best[0]):
            best = (to, address)
if best is None:
    sys.exit('kernel-mca: no loop found in the function')
body = []
for address, op, args in instructions:
    if best[0] <= address <= best[1] and not op.startswith('j') and not op.startswith('call'):
        text = re.sub(r'#.*', '', op + ' ' + args)
        body.append(re.sub(r'<[^>]*>', '', text).strip())
open(sys.argv[2], 'w').write('\n'.join(body) + '\n')
print(f'particle loop: {best[0]:#x}..{best[1]:#x}, {len(body)} instructions (jumps left out)')
EOF

report=$("$mca" -mcpu="$mcpu" -iterations=200 -bottleneck-analysis "$work/loop.s" 2>&1)
cycles=$(awk '/^Total Cycles:/ { print $3 }' <<<"$report")
count=$(awk '/^Instructions:/ { print $2 }' <<<"$report")
echo "target $target ($lanes lanes a register), CPU model $mcpu:"
grep -E '^(IPC|Block RThroughput):' <<<"$report"
awk -v c="$cycles" -v n="$count" -v l="$lanes" 'BEGIN {
    printf "%.0f instructions and %.0f cycles an iteration; %.0f cycles a particle of 16 lanes\n",
        n / 200, c / 200, c / 200 * 16 / l }'
sed -n '/^Throughput Bottlenecks:/,/^  - Memory Dependencies/p' <<<"$report"
