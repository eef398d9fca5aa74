#!/usr/bin/env bash
# Compares builds of wisp-cli on one bench workload, run in turns so that a shared machine's
# changes of speed (this project's VMs switch between two for minutes at a time) fall on every
# build alike: each round runs every binary once, in the opposite order the round after.
# Prints, per binary, the median and least ms a step and the median, least and most ratio to the
# floor (the ratio is the figure to judge a change by: the floor is timed beside the workload).
#
#   scripts/bench-ab.sh [--rounds N] BINARY... -- BENCH_OPTIONS...
#   scripts/bench-ab.sh --rounds 8 /tmp/before/wisp-cli build/app/wisp-cli -- --workload groom-1m --threads 2
#   scripts/bench-ab.sh all=build/app/wisp-cli 'no-gusts=build/app/wisp-cli --without gusts' -- --workload groom-1m
#
# On a host that does not always run both vCPUs at once, compare one thread pinned to a CPU as
# well (taskset applies to every run): taskset -c 0 scripts/bench-ab.sh ... -- ... --threads 1
#
# A binary may be given as LABEL=PATH, and PATH may be followed by bench options of its own (one
# argument, quoted: the same binary run several ways; words split at spaces, so neither the path nor
# those options may hold one). Every run also gets --json (and --steps 50 unless the options name
# --steps). Needs only bash, awk and sort.
set -euo pipefail

usage() {
    sed -n '2,18p' "$0" | sed 's/^# \{0,1\}//' >&2
    exit 2
}

rounds=6
binaries=()
while [[ $# -gt 0 ]]; do
    case "$1" in
        --rounds)
            [[ $# -ge 2 && "$2" =~ ^[1-9][0-9]*$ ]] || { echo "bench-ab: --rounds needs a positive number" >&2; exit 2; }
            rounds=$2
            shift 2
            ;;
        --help | -h) usage ;;
        --)
            shift
            break
            ;;
        *)
            binaries+=("$1")
            shift
            ;;
    esac
done
options=("$@")
[[ ${#binaries[@]} -ge 1 && ${#options[@]} -ge 1 ]] || usage
[[ " ${options[*]} " == *" --workload "* ]] || { echo "bench-ab: name one --workload after --" >&2; exit 2; }
[[ " ${options[*]} " == *" --steps "* ]] || options+=(--steps 50)

labels=()
paths=()
own=() # each binary's own bench options, space-separated
for b in "${binaries[@]}"; do
    spec=$b
    if [[ "$b" =~ ^([^[:space:]=]+)=(.*)$ ]]; then # (a label has no spaces: --opt=value is an option)
        labels+=("${BASH_REMATCH[1]}")
        spec=${BASH_REMATCH[2]}
    else
        labels+=("$b")
    fi
    read -r -a words <<< "$spec"
    [[ ${#words[@]} -ge 1 ]] || { echo "bench-ab: '$b': no binary" >&2; exit 2; }
    paths+=("${words[0]}")
    own+=("${words[*]:1}")
    [[ -x "${paths[-1]}" ]] || { echo "bench-ab: ${paths[-1]}: not an executable" >&2; exit 2; }
done

results=$(mktemp)
trap 'rm -f "$results"' EXIT
count=${#paths[@]}
for ((r = 0; r < rounds; ++r)); do
    for ((k = 0; k < count; ++k)); do
        i=$((r % 2 == 0 ? k : count - 1 - k))
        # The workload's row: the first JSON line (the floor's is the second). Read whole, not
        # through `head`, whose early exit would end the bench with SIGPIPE (and, with pipefail, this).
        read -r -a more <<< "${own[$i]}"
        out=$("${paths[$i]}" bench --json "${options[@]}" "${more[@]}")
        line=${out%%$'\n'*}
        ms=$(sed -n 's/.*"ms_per_step": \([0-9.]*\).*/\1/p' <<< "$line")
        ratio=$(sed -n 's/.*"ratio_to_floor": \([0-9.]*\).*/\1/p' <<< "$line")
        target=$(sed -n 's/.*"target": "\([^"]*\)".*/\1/p' <<< "$line")
        [[ -n "$ms" && -n "$ratio" ]] || { echo "bench-ab: ${labels[$i]} printed no row: $line" >&2; exit 1; }
        printf '%d\t%s\t%s\t%s\n' "$i" "$ms" "$ratio" "$target" >> "$results"
    done
    echo "bench-ab: round $((r + 1)) of $rounds done" >&2
done

median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2) }'; }
printf '%-28s %-8s %12s %10s %12s %8s %8s\n' binary target "median ms" "least ms" "median x" "least x" "most x"
for ((i = 0; i < count; ++i)); do
    mine=$(awk -F'\t' -v i="$i" '$1 == i' "$results")
    target=$(cut -f4 <<< "$mine" | head -n 1)
    printf '%-28s %-8s %12.4f %10.4f %12.2f %8.2f %8.2f\n' "${labels[$i]}" "$target" \
        "$(cut -f2 <<< "$mine" | median)" "$(cut -f2 <<< "$mine" | sort -g | head -n 1)" \
        "$(cut -f3 <<< "$mine" | median)" "$(cut -f3 <<< "$mine" | sort -g | head -n 1)" \
        "$(cut -f3 <<< "$mine" | sort -g | tail -n 1)"
done
