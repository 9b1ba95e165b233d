#!/usr/bin/env bash
# Every pressure solver at walls, through the tutorials' one-word swap (issues 34.4 and 35; the
# quick versions of tutorials/validation/solverTargets.py's tables, full runs in
# docs/VALIDATION.md §0a):
#   tank         hydrostaticTank2D with damBreak2D's pressureSolvers entry swapped in, 2 s of
#                still water: the bottom row rests half a spacing over the floor's face (0.5 dx:
#                not on it), no pair closer than 0.5 dx, the bottom probe's mean pressure (every
#                step over 1.5-2 s) within 2 % (measured 0.25-0.84 %, wcsph's plain gradient 1.63 %),
#                and still where it is (wcsph, pcisph: a standard deviation of 0.005 %; iisph, dfsph,
#                pbf and relaxedPbf ring at 14-80 %, issue 35)
#   damBreakBox  damBreak2D with a box on the floor, to t = 0.3 s: no fluid particle centre past a
#                wall's face, at most 5 % of the first row on the floor's face (0.26 for dfsph,
#                pbf and relaxedPbf before their walls had a pressure of their own), no pair
#                closer than 0.5 dx
#   solverWalls.sh <spindrift> <pvpython>
set -euo pipefail
solver=$1 pvpython=$2
root=$(cd "$(dirname "$0")/../.." && pwd)
fail() { echo "FAIL: $*"; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

"$pvpython" "$root/tutorials/validation/solverTargets.py" --cases tank,damBreakBox --spindrift "$solver" \
    --work "$work" --threads 1 --jobs 1 2>&1 | grep -v "^Warning" || fail "solverTargets.py failed"

# check <csv> <column> <lo> <hi> [solvers]: every solver's value (or those the regular expression
# 'solvers' matches) within [lo, hi] (a failed run or a nan fails)
status=0
check() {
    awk -F, -v col="$2" -v lo="$3" -v hi="$4" -v only="^(${5:-.*})$" -v file="$(basename "$1")" '
        NR == 1 { for (i = 1; i <= NF; i++) if ($i == col) c = i; if (!c) { print "FAIL: " file " has no column " col; exit 1 } next }
        $1 !~ only { next }
        { v = $c; ok = (v != "" && v + 0 == v && v >= lo && v <= hi)
          printf "%s %-10s %-20s %-8s in [%s, %s]: %s\n", file, $1, col, v, lo, hi, ok ? "ok" : "FAIL"
          if (!ok) bad = 1 }
        END { exit bad }' "$1" || status=1
}
check "$work/tank.csv" bottomRowHeight 0.45 0.55
check "$work/tank.csv" minPair 0.5 10
check "$work/tank.csv" bottomPressureError 0 2
check "$work/tank.csv" bottomPressureNoise 0 0.1 "wcsph|pcisph"
check "$work/damBreakBox.csv" penetration 0 0
check "$work/damBreakBox.csv" onFace 0 0.05
check "$work/damBreakBox.csv" minPair 0.5 10
[ $status = 0 ] || fail "a pressure solver does not hold at the walls (above)"
echo "every pressure solver holds at the walls"
