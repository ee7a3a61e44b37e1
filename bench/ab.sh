#!/bin/bash
# A/B of two builds in one run, binaries alternating (this machine drifts within the hour):
#   bench/ab.sh BUILD_A BUILD_B [ROUNDS]
# Prints the medians of bench_bind's whole solve (hand, armadillo) and bench_fast's iteration times,
# and B/A for each.
set -euo pipefail
A=$1 B=$2 N=${3:-3}
declare -A fig
record() {  # record LABEL KEY VALUE
  fig[$1.$2]="${fig[$1.$2]:-} $3"
}
run_one() {  # run_one LABEL BUILD
  local out
  out=$("$2/bench/bench_bind" hand)
  record "$1" "bind hand solve [s]" "$(sed -n 's/.*whole solve (assembly + factorization + bounded solve): \([0-9.]*\) s.*/\1/p' <<<"$out")"
  out=$("$2/bench/bench_bind" armadillo)
  record "$1" "bind armadillo solve [s]" "$(sed -n 's/.*whole solve (assembly + factorization + bounded solve): \([0-9.]*\) s.*/\1/p' <<<"$out")"
  record "$1" "bind armadillo total [s]" "$(sed -n 's/.*wall \[s\]:.* total \([0-9.]*\).*/\1/p' <<<"$out")"
  out=$("$2/bench/bench_fast")
  local i=0
  while read -r us; do
    record "$1" "fast iteration $i [us]" "$us"
    i=$((i + 1))
  done < <(sed -n 's/.*one iteration \([0-9.]*\) us (mean of 5000).*/\1/p' <<<"$out")
}
for r in $(seq "$N"); do
  run_one A "$A"
  run_one B "$B"
done
median() { tr ' ' '\n' | grep . | sort -g | awk '{v[NR]=$1} END {print v[int((NR+1)/2)]}'; }
for k in $(printf '%s\n' "${!fig[@]}" | sed -n 's/^A\.//p' | sort | tr ' ' '#'); do
  key=${k//#/ }
  a=$(median <<<"${fig[A.$key]}") b=$(median <<<"${fig[B.$key]}")
  printf '%-28s A %9s  B %9s  B/A %s\n' "$key" "$a" "$b" "$(awk -v a="$a" -v b="$b" 'BEGIN {printf "%.3f", b / a}')"
done
