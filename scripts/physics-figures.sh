#!/usr/bin/env bash
# Prints the settling and drawn-strand figures of the README's "Physics figures" table: the
# settling tests' set-ups, with their measured values (build first: scripts/setup.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
build/tests/wisp_sim_tests --gtest_filter='*Settl*:*DrawnStrands*:Stability*' 2>&1 | grep '^figure'
