#!/usr/bin/env bash
# spindriftBench -quick on the dam break over three combinations: one that runs, one naming a
# model that is not built (an "unavailable" row) and one whose input is wrong (a "failed" row);
# the bench finishes, writes the table with the case's figure and the Pareto flag, and the plot.
#   benchQuick.sh <spindriftBench> <damBreak2D case>
set -euo pipefail
bench=$1 case=$2
fail() { echo "FAIL: $*"; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$bench" -case "$case" -quick -output "$work/out" -timeout 300 \
    -vary "kernel.type=wendlandC2,noSuchKernel" -combination "pressure.gamma=-1" | tee "$work/log"
csv=$work/out/bench.csv
[ -f "$csv" ] || fail "no bench.csv"
[ "$(wc -l < "$csv")" -eq 4 ] || fail "expected 3 rows: $(cat "$csv")"
grep -q "^wendlandC2,wendlandC2,,ok," "$csv" || fail "the wendlandC2 row: $(cat "$csv")"
grep "^wendlandC2," "$csv" | grep -q ",frontRMS,[0-9.]*,yes," || fail "no figure or Pareto flag: $(grep ^wendlandC2 "$csv")"
grep -q "^noSuchKernel,noSuchKernel,,unavailable,.*kernel 'noSuchKernel' is not built" "$csv" || fail "unavailable row: $(cat "$csv")"
grep "^-1," "$csv" | grep -q ",failed," || fail "the gamma -1 row must fail: $(grep '^-1,' "$csv")"
grep "^-1," "$csv" | grep -q "gamma must be positive" || fail "the failed row keeps the solver's message"
[ "$(head -c 4 "$work/out/bench.png" | tail -c 3)" = PNG ] || fail "no bench.png"
grep -q "^| kernel.type=wendlandC2 | ok |" "$work/log" || fail "no markdown table"
[ ! -d "$work/out/runs" ] || fail "run directories are kept without -keep"
echo "spindriftBench quick: OK"
