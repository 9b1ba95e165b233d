#!/usr/bin/env bash
# A validation case in -quick mode through spindriftBench (which runs the case's Allrun on a
# copy): the run finishes, the case's error figure stays within its bound, the plot is drawn.
#   validationCase.sh <spindriftBench> <case dir> <figure name> <bound> <plot file> [<figure>:<bound> ...]
set -euo pipefail
bench=$1 case=$2 figure=$3 bound=$4 plot=$5
shift 5 # then <figure>:<bound> pairs checked in the case's evaluate.py output
fail() { echo "FAIL: $*"; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$bench" -case "$case" -quick -output "$work/out" -keep -casePlots -noPlot -timeout 300
csv=$work/out/bench.csv
[ -f "$csv" ] || fail "no bench.csv"
col() { head -1 "$csv" | tr ',' '\n' | grep -nx "$1" | cut -d: -f1; }
row=$(sed -n 2p "$csv")
status=$(cut -d, -f"$(col status)" <<< "$row")
name=$(cut -d, -f"$(col figureName)" <<< "$row")
value=$(cut -d, -f"$(col figure)" <<< "$row")
[ "$status" = ok ] || { cat "$work"/out/runs/*/log.Allrun || true; fail "status $status"; }
[ "$name" = "$figure" ] || fail "the case's figure is '$name', expected '$figure'"
echo "$figure = $value (bound $bound)"
awk -v v="$value" -v b="$bound" 'BEGIN { exit !(v != "" && v + 0 == v && (v < 0 ? -v : v) <= b) }' \
    || fail "$figure = $value exceeds its bound $bound"
for check in "$@"; do
    extraFigure=${check%%:*} extraBound=${check#*:}
    extraValue=$(sed -n "s/^Figure: $extraFigure = \([-0-9.eE+]*\).*/\1/p" "$work/out/runs/base/log.evaluate" | head -1)
    echo "$extraFigure = $extraValue (bound $extraBound)"
    awk -v v="$extraValue" -v b="$extraBound" 'BEGIN { exit !(v != "" && v + 0 == v && (v < 0 ? -v : v) <= b) }' \
        || fail "$extraFigure = '$extraValue' exceeds its bound $extraBound"
done
[ -s "$work/out/runs/base/$plot" ] || fail "no plot $plot"
[ "$(head -c 4 "$work/out/runs/base/$plot" | tail -c 3)" = PNG ] || fail "$plot is not a PNG"
echo "validation $(basename "$case"): OK"
