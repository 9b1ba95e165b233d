#!/usr/bin/env bash
# The run log, as a tutorial's Allrun leaves it in log.spindrift: a line per written time with
# the time of day, the wall time so far and an ETA; step lines every step for a short run,
# thinned for a long one (every 50th of 10,000 steps), every N-th with controlDict
# `logInterval N`; the first and the last step always.
#   solverLog.sh <spindrift> <source dir>
set -euo pipefail
solver=$1 source=$2
export SPINDRIFT_DIR=$source SPINDRIFT_BIN
SPINDRIFT_BIN=$(dirname "$solver")
. "$source/etc/RunFunctions" # cloneCase: a tutorial's input, never its results
fail() { echo "FAIL: $*"; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
setEntry() { sed -i -E "s/^$2 .*/$2 $3;/" "$1/system/controlDict"; } # setEntry <case> <keyword> <value>
stepsOf() { sed -n 's/^End: \([0-9]*\) steps.*/\1/p' "$1"; }
stepLines() { grep '^Time = ' "$1" | sed 's/.*  step \([0-9]*\) .*/\1/'; }

# a short run through the tutorial's Allrun: a coarse dam break, 200 steps of fixed deltaT
cloneCase "$source/tutorials/damBreak2D" "$work/short"
sed -i -E "s/^particleSpacing .*/particleSpacing 0.0047625;/" "$work/short/constant/fluidProperties" # a/12
setEntry "$work/short" adjustTimeStep no
setEntry "$work/short" deltaT 5e-05
setEntry "$work/short" endTime 0.01
setEntry "$work/short" writeInterval 0.005
"$work/short/Allrun" > /dev/null
log=$work/short/log.spindrift
head -n 12 "$log"
grep -q "^Spindrift : " "$log" || fail "no version line"
grep -Eq "^Started   : [0-9]{4}-[0-9]{2}-[0-9]{2} [0-9:]{8} on " "$log" || fail "no start date line"
steps=$(stepsOf "$log")
[ -n "$steps" ] || fail "no End line"
for t in 0 0.005 0.01; do
    line=$(grep "^Wrote time $t " "$log") || fail "no line for the write of time $t"
    echo "$line"
    [[ "$line" =~ ^Wrote\ time\ $t\ \(step\ ([0-9]+)\)\ at\ [0-9]{2}:[0-9]{2}:[0-9]{2},\ [0-9.]+\ s\ wall(,\ ETA\ .+)?$ ]] \
        || fail "write line '$line'"
    step=${BASH_REMATCH[1]}
    if [ "$t" = 0 ] || [ "$t" = 0.01 ]; then
        [ -z "${BASH_REMATCH[2]}" ] || fail "an ETA at the first or the last time: '$line'"
    else
        [ -n "${BASH_REMATCH[2]}" ] || fail "no ETA: '$line'"
    fi
    [ "$t" != 0.01 ] || [ "$step" = "$steps" ] || fail "the last write is not at the last step $steps: '$line'"
done
[ "$(grep -c '^Wrote time ' "$log")" -eq 3 ] || fail "not one line per written time"
[ "$steps" -eq 200 ] || fail "the short run took $steps steps, not 200"
[ "$(stepLines "$log" | tr '\n' ' ')" = "$(seq 1 200 | tr '\n' ' ')" ] || fail "not every step of a 200-step run logged"
tail -n 3 "$log"
echo "ok short run: 200 steps, every one logged, 3 write lines"

# logInterval 7: every 7th step, and the first and the last
cleanCase() { rm -rf "$1"/[0-9]* "$1"/*.pvd "$1"/log.*; }
cleanCase "$work/short"
echo "logInterval 7;" >> "$work/short/system/controlDict"
"$solver" -case "$work/short" > "$log"
steps=$(stepsOf "$log")
expected=$( (echo 1; seq 7 7 "$steps"; echo "$steps") | sort -nu | tr '\n' ' ')
[ "$(stepLines "$log" | tr '\n' ' ')" = "$expected" ] || fail "logInterval 7: steps logged $(stepLines "$log" | tr '\n' ' ')"
echo "ok logInterval 7: $(stepLines "$log" | wc -l) step lines for $steps steps"

# 10,000 steps (a coarse dam break, fixed deltaT): about 200 step lines, every 50th step
cloneCase "$source/tutorials/damBreak2D" "$work/long"
sed -i -E "s/^particleSpacing .*/particleSpacing 0.0142875;/" "$work/long/constant/fluidProperties" # a/4: 32 particles
setEntry "$work/long" adjustTimeStep no
setEntry "$work/long" deltaT 1e-05
setEntry "$work/long" endTime 0.1
setEntry "$work/long" writeInterval 0.05
"$solver" -case "$work/long" > "$work/long/log" || { tail "$work/long/log"; fail "the long run failed"; }
steps=$(stepsOf "$work/long/log")
[ "$steps" -eq 10000 ] || fail "the long run took $steps steps, not 10000"
expected=$( (echo 1; seq 50 50 10000) | tr '\n' ' ')
[ "$(stepLines "$work/long/log" | tr '\n' ' ')" = "$expected" ] \
    || fail "10,000 steps: steps logged $(stepLines "$work/long/log" | head -n 20 | tr '\n' ' ')..."
echo "ok 10,000 steps: $(stepLines "$work/long/log" | wc -l) step lines"
echo "solver log: OK"
