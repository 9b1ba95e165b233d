#!/usr/bin/env bash
# spindriftBench and spindriftStress refuse what cannot run, before running anything, with exit
# status 1 and a message naming the option: -threads 0 or beyond the cores, a negative -timeout,
# an -output that is the case itself, a -vary key that names no entry of the case, spindriftStress
# -stillWaterTime -1, -resolution -4; and spindriftBench exits 1 when every combination failed
# (a -vary key that adds a keyword the model does not know: the solver refuses each run).
#   utilityOptions.sh <spindriftBench> <spindriftStress> <hydrostaticTank2D validation case>
set -euo pipefail
bench=$1 stress=$2 source=$3
. "$(dirname "$0")/../../etc/RunFunctions"
fail() { echo "FAIL: $*"; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cloneCase "$source" "$work/tank"
sed -i -E 's/^(\s*endTime\s+).*/\10.01;/' "$work/tank/system/benchDict"
cores=$(env -u OMP_NUM_THREADS -u OMP_THREAD_LIMIT nproc) # the CPUs of its affinity mask
expectError() { # expectError <pattern> <command...>: exit 1, the message, no run
    local pattern=$1 status=0; shift
    (cd "$work" && "$@") > "$work/out" 2>&1 || status=$?
    [ $status -eq 1 ] || fail "'$*': exit status $status, not 1: $(tail -3 "$work/out")"
    grep -q -- "$pattern" "$work/out" || fail "'$*': '$(tail -3 "$work/out")' lacks '$pattern'"
    [ ! -d "$work/out.d/runs" ] || fail "'$*' ran something"
    echo "ok $(basename "$1") ${*:2}: $(grep -- "$pattern" "$work/out" | head -n 1)"
}
b=("$bench" -case "$work/tank" -quick -noPlot -output "$work/out.d")
expectError "-threads 0: give 1 to $cores" "${b[@]}" -threads 0
expectError "-threads 100000: give 1 to $cores" "${b[@]}" -threads 100000
expectError "-timeout -5: give the seconds" "${b[@]}" -timeout -5
expectError "-output $work/tank is the case itself" "$bench" -case "$work/tank" -quick -output "$work/tank"
expectError "lies inside the case" "$bench" -case "$work/tank" -quick -output "$work/tank/bench"
expectError "override 'endTim': no case dictionary" "${b[@]}" -vary "endTim=0.1,0.2"
expectError "-threads 100000: give 1 to $cores" "$bench" -case "$work/tank" -soak 2 -threads 100000
[ -z "$(ls "$work/tank" | grep -vxE 'Allrun|Allclean|README.md|system|constant|evaluate.py')" ] \
    || fail "the case holds more than its input: $(ls "$work/tank")"
# every combination fails (a misspelt model keyword, which the solver refuses): the table, then exit 1
status=0
"${b[@]}" -vary "pressure.gama=7,8" > "$work/failed.log" 2>&1 || status=$?
[ $status -eq 1 ] || fail "every combination failed, exit status $status: $(tail -3 "$work/failed.log")"
grep -q "none of the 2 combination(s) ran to the end" "$work/failed.log" || fail "no message: $(tail -3 "$work/failed.log")"
[ "$(grep -c ',failed,' "$work/out.d/bench.csv")" = 2 ] || fail "bench.csv: $(cat "$work/out.d/bench.csv")"
echo "ok every combination failed: exit 1, $(grep 'none of' "$work/failed.log")"
rm -rf "$work/out.d"
s=("$stress" -quick -noPlot -output "$work/out.d" -tests stillWater)
expectError "-stillWaterTime -1: give the physical time" "${s[@]}" -stillWaterTime -1
expectError "-resolution -4: give the particles across" "${s[@]}" -resolution -4
expectError "-threads 100000: give 1 to $cores" "${s[@]}" -threads 100000
expectError "-timeout -5: give the seconds" "${s[@]}" -timeout -5
echo "utility options: OK"
