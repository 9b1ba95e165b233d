#!/usr/bin/env bash
# spindriftBench -pick: the fastest combination meeting "FIGURE<=VALUE" is written into a copy of
# the hydrostatic tank's sphSchemes, citing its bench.csv row, the original kept as .orig; a
# bound no combination meets and a malformed request leave the case unchanged (exit 1).
#   benchPick.sh <spindriftBench> <hydrostaticTank2D validation case>
set -euo pipefail
bench=$1 source=$2
. "$(dirname "$0")/../../etc/RunFunctions"
fail() { echo "FAIL: $*"; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cloneCase "$source" "$work/tank"
sed -i -E 's/^(\s*endTime\s+).*/\10.3;/' "$work/tank/system/benchDict"
cp "$work/tank/system/sphSchemes" "$work/original"
vary=(-vary "kernel.type=wendlandC2,cubicSpline" -vary "viscosity.alpha=0.1,0.05")

# malformed: stops before running anything
if "$bench" -case "$work/tank" -quick -output "$work/bad" "${vary[@]}" -pick "bottomPressureError<0.1" > "$work/bad.log" 2>&1; then
    fail "a malformed -pick must fail"
fi
grep -q "expected FIGURE<=VALUE" "$work/bad.log" || fail "malformed -pick message: $(cat "$work/bad.log")"
[ ! -e "$work/bad/bench.csv" ] || fail "a malformed -pick ran the bench"

# a bound no combination meets: the runs happen, the case is unchanged
if "$bench" -case "$work/tank" -quick -output "$work/none" -noPlot "${vary[@]}" -pick "bottomPressureError<=0" > "$work/none.log" 2>&1; then
    fail "an unmet bound must exit 1"
fi
grep -q "no combination meets it" "$work/none.log" || fail "unmet bound message: $(tail -3 "$work/none.log")"
cmp -s "$work/original" "$work/tank/system/sphSchemes" || fail "an unmet bound changed sphSchemes"
[ ! -e "$work/tank/system/sphSchemes.orig" ] || fail "an unmet bound left a .orig"

# a bound every combination meets: the fastest one of the table is written, citing its row
"$bench" -case "$work/tank" -quick -output "$work/out" -noPlot "${vary[@]}" -pick "bottomPressureError<=50" | tee "$work/log"
csv=$work/out/bench.csv
col() { head -1 "$csv" | tr ',' '\n' | grep -nx "$1" | cut -d: -f1; }
# the fastest rows at the table's precision (two runs may tie there: any of them is right)
ok=$(tail -n +2 "$csv" | awk -F, -v s="$(col status)" '$s == "ok"')
[ -n "$ok" ] || fail "no ok row: $(cat "$csv")"
fastestTime=$(cut -d, -f"$(col wallTime_s)" <<< "$ok" | sort -g | head -1)
fastest=$(awk -F, -v w="$(col wallTime_s)" -v t="$fastestTime" '$w == t' <<< "$ok")
schemes=$work/tank/system/sphSchemes
cmp -s "$work/original" "$schemes.orig" || fail "the replaced sphSchemes is not kept as sphSchemes.orig"
grep -q '^// spindriftBench -pick "bottomPressureError<=50": the fastest of 4 measured' "$schemes" \
    || fail "no comment citing the pick: $(head -3 "$schemes")"
kernel= alpha=
while IFS= read -r row; do
    k=$(cut -d, -f"$(col kernel.type)" <<< "$row") a=$(cut -d, -f"$(col viscosity.alpha)" <<< "$row")
    if grep -q "row [1-4]: kernel.type=$k viscosity.alpha=$a," "$schemes"; then kernel=$k alpha=$a; fi
done <<< "$fastest"
[ -n "$kernel" ] || fail "the comment names another row than the fastest ($fastestTime s): $(head -3 "$schemes")"
tr -s ' \n' ' ' < "$schemes" | grep -Eq "kernel \{ type $kernel; \}" || fail "sphSchemes does not have kernel $kernel"
tr -s ' \n' ' ' < "$schemes" | grep -Eq "alpha $alpha;" || fail "sphSchemes does not have alpha $alpha"
# the picked case runs
(cd "$work/tank" && sed -i -E 's/^endTime .*/endTime 0.01;/' system/controlDict && spindrift > log 2>&1) \
    || { tail -5 "$work/tank/log"; fail "the picked case does not run"; }
echo "spindriftBench -pick: OK ($kernel, alpha $alpha)"
