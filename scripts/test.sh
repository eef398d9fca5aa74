#!/usr/bin/env bash
# Installs what is missing, builds, checks the formatting of the folders scripts/check-format.sh
# lists and the include graph (scripts/check-includes.py: no cycle, nothing upward), and runs the
# whole test suite (GUI tests under a virtual X server: Qt 6.4's offscreen platform cannot create
# QOpenGLWidget's context).
#
#   scripts/test.sh              Release build
#   scripts/test.sh --sanitize   Debug build with AddressSanitizer + UBSan
#   WISP_MARCH=x86-64-v3 scripts/test.sh [--sanitize]
#                                either build for that CPU instead of the portable default (scripts/setup.sh)
#
# After the tests, the Release mode also fuzzes every reader briefly (scripts/fuzz.sh --ci: its
# own clang build, about 20 s a target); WISP_CI_FUZZ=0 skips that.
# It also compiles sim/ for 64-bit ARM (scripts/arm64-check.sh: Debian's cross compiler, about
# 2 min), so the solver's NEON and SVE kernels, which no x86 build compiles, keep compiling;
# WISP_CI_ARM64=0 skips that.
set -euo pipefail

cd "$(dirname "$0")/.."
scripts/setup.sh "$@"

build_dir=build
[ "${1:-}" = "--sanitize" ] && build_dir=build-asan
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1}
scripts/check-format.sh
scripts/check-includes.py
# A test's hang limit: the sanitizer build runs about ten times slower (a 500-frame GUI test took
# 694 s there on a loaded 2-core machine), so it gets more room; a hang still ends the run.
timeout_s=600
[ "$build_dir" = build-asan ] && timeout_s=1800
cd "$build_dir"
xvfb-run -a -s "-screen 0 1600x1000x24" ctest --output-on-failure -j2 --timeout "$timeout_s"
cd ..
if [ "${1:-}" != "--sanitize" ] && [ "${WISP_CI_FUZZ:-1}" != 0 ]; then
  scripts/fuzz.sh --ci
fi
if [ "${1:-}" != "--sanitize" ] && [ "${WISP_CI_ARM64:-1}" != 0 ]; then
  scripts/arm64-check.sh
fi
