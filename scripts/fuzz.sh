#!/usr/bin/env bash
# Builds the libFuzzer targets (scripts/setup.sh --fuzz: clang, ASan + UBSan + float-cast-overflow,
# in build-fuzz/), writes their seeds (scripts/fuzz-corpus.sh) and runs each target in turn.
#
#   scripts/fuzz.sh [--ci] [seconds] [target ...]
#
#   --ci       each target for `seconds` (default 20) on a fresh corpus grown from the seeds, so a
#              run depends only on the commit; CI runs this after the tests (scripts/test.sh).
#   (default)  the longer run: each target for `seconds` (default 600), keeping what it learns in
#              build-fuzz/corpus/<target>/ for the next run.
#   targets    mesh gltf hair preset project params (default: all).
#   WISP_FUZZ_ARGS  more libFuzzer options, e.g. -runs=1000000 to stop a target at a million inputs.
#
# A finding (crash, sanitizer report, leak, an input slower than 10 s or one that needs more than
# 2 GB) stops that target; the input is kept as build-fuzz/findings/<target>-crash-… and printed,
# the other targets still run, and the script fails. Replay one with
#   build-fuzz/fuzz/fuzz_<target> build-fuzz/findings/<file>
# The figures (executions, executions a second, corpus) are printed for each target.
set -euo pipefail

cd "$(dirname "$0")/.."
ci=0
if [ "${1:-}" = "--ci" ]; then ci=1; shift; fi
seconds=$((ci ? 20 : 600))
if [[ "${1:-}" =~ ^[0-9]+$ ]]; then seconds=$1; shift; fi
targets=("$@")
((${#targets[@]})) || targets=(mesh gltf hair preset project params)

build_started=$SECONDS
scripts/setup.sh --fuzz
echo "== fuzz build: $((SECONDS - build_started)) s"
scripts/fuzz-corpus.sh build-fuzz/seeds build-fuzz/fuzz/wisp_fuzz_seeds

# The targets write each input to a file (the readers take paths): in memory where possible.
scratch=$(mktemp -d /dev/shm/wisp-fuzz.XXXXXX 2>/dev/null || mktemp -d)
trap 'rm -rf "$scratch"' EXIT
export TMPDIR=$scratch
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
mkdir -p build-fuzz/findings

# Inputs per target in a CI run: about 20 s each at the rates measured on a 2-core AMD EPYC.
ci_runs() {
  case $1 in
    mesh) echo 60000 ;; gltf) echo 50000 ;; project) echo 100000 ;; preset) echo 150000 ;;
    *) echo 300000 ;;
  esac
}

failed=()
for t in "${targets[@]}"; do
  limits=(-max_total_time="$seconds")
  if ((ci)); then
    corpus=$scratch/corpus-$t
    # CI follows one path for one commit: a fixed seed and a fixed number of inputs (about
    # `seconds` on a 2-core machine; the time stays a cap), so a run that passed before landing
    # passes in CI, and a finding there replays.
    limits=(-seed=1 -runs="$(ci_runs "$t")" -max_total_time=$((seconds * 3)))
  else
    corpus=build-fuzz/corpus/$t
  fi
  mkdir -p "$corpus"
  log=build-fuzz/fuzz-$t.log
  echo "== fuzz_$t: ${seconds} s"
  status=0
  build-fuzz/fuzz/fuzz_"$t" "$corpus" build-fuzz/seeds/"$t" "${limits[@]}" -max_len=16384 -timeout=10 \
    -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix=build-fuzz/findings/"$t"- ${WISP_FUZZ_ARGS:-} > "$log" 2>&1 || status=$?
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log")
  corp=$(grep -a -o 'corp: [0-9]*/[0-9]*[a-zA-Z]*' "$log" | tail -1)
  echo "   ${runs:-?} executions, ${rate:-?} a second, $(grep -a -o 'cov: [0-9]*' "$log" | tail -1), ${corp:-corp: ?} (inputs/bytes)"
  if ((status != 0)); then
    failed+=("$t")
    echo "!! fuzz_$t found a problem (exit $status); the end of its log ($log):"
    grep -a -v '^#[0-9]' "$log" | tail -40
    for a in $(sed -n 's/.*Test unit written to //p' "$log"); do
      echo "!! the input, $a ($(stat -c %s "$a") bytes; replay: build-fuzz/fuzz/fuzz_$t $a):"
      head -c 2048 "$a" | od -A d -c | head -40
    done
  fi
done
if ((${#failed[@]})); then
  echo "== fuzzing found problems in: ${failed[*]}"
  exit 1
fi
echo "== fuzzing: no findings (${targets[*]})"
