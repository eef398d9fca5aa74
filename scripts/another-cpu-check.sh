#!/bin/bash
# Runs this build's portable binaries on another machine's CPU: the same bits on every SIMD target
# there as here, and the bench's figures. Two steps:
#   scripts/another-cpu-check.sh pack [BUILD_DIR]   # here: BUILD_DIR/devcheck with the binaries,
#                                                   # their libraries and the loader
#   bash BUILD_DIR/devcheck/another-cpu-check.sh run  # there, from the repository root
# It prints, per SIMD target, the SHA-256 of the default scene's strands after 120 steps (wind and
# volume on): compare them with `scripts/another-cpu-check.sh hashes` here; they should be equal.
set -euo pipefail
mode=${1:-}
if [[ "$mode" == pack ]]; then
    build=${2:-build-portable}
    out="$build/devcheck"
    rm -rf "$out" && mkdir -p "$out/lib"
    cp "$build/app/wisp-cli" "$build/tests/wisp_sim_tests" "$out/"
    cp "$0" "$out/another-cpu-check.sh"
    # Every library the binaries load, and the loader itself, so a machine with another system runs them.
    for lib in $(ldd "$build/app/wisp-cli" "$build/tests/wisp_sim_tests" | awk '/=>/ {print $3}' | sort -u); do
        cp -L "$lib" "$out/lib/"
    done
    cp -L /lib64/ld-linux-x86-64.so.2 "$out/lib/"
    echo "packed $out ($(du -sh "$out" | cut -f1)); run there: bash $out/another-cpu-check.sh run"
    exit 0
fi
hashes() { # $1: how to run wisp-cli
    local out
    out=$(mktemp --suffix=.hair)
    for target in "" AVX2 SSE4; do
        # shellcheck disable=SC2086 # $1 is a command and its arguments
        $1 simulate --steps 120 --threads 2 --wind_speed 6 --volume 0.5 --export "$out" ${target:+--target $target} >/dev/null
        echo "${target:-best} $(sha256sum "$out" | cut -d' ' -f1)"
    done
    rm -f "$out"
}
if [[ "$mode" == hashes ]]; then
    hashes "${2:-build-portable}/app/wisp-cli"
    exit 0
fi
if [[ "$mode" != run ]]; then
    echo "usage: $0 pack [BUILD_DIR] | run | hashes [BUILD_DIR]" >&2
    exit 2
fi
dir=$(cd "$(dirname "$0")" && pwd)
lib="$dir/lib"
run() { "$lib/ld-linux-x86-64.so.2" --library-path "$lib" "$@"; }
echo "== the default scene's strands after 120 steps, per target (SHA-256)"
hashes "$lib/ld-linux-x86-64.so.2 --library-path $lib $dir/wisp-cli"
lscpu | grep -E "Model name|^CPU\(s\)" || true
grep -m1 flags /proc/cpuinfo | tr ' ' '\n' | grep -E '^(sse4_2|avx2|fma|avx512f|avx512bw|avx512vl)$' | tr '\n' ' '
echo
echo "== the same bits on every target (and thread count)"
run "$dir/wisp_sim_tests" --gtest_filter='SimdTarget*:*Thread*' 2>&1 | grep -E "PASSED|FAILED|SKIPPED" || true
echo "== bench: ms a step, x floor"
for target in "" AVX2 SSE4; do
    for workload in "sphere --strands 66667" "sphere --strands 2450" "groom-1m"; do
        # shellcheck disable=SC2086 # the workload's words are its arguments
        run "$dir/wisp-cli" bench --workload $workload --threads 2 ${target:+--target $target} 2>&1 \
            | grep -E '^(target|sphere|groom)' || true
    done
done
