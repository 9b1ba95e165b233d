#!/usr/bin/env bash
# One model swapped into a tutorial, run briefly: the solver must finish, every fluid particle
# must stay in the tank and the maximum density error must stay below a bound.
#   modelCombination.sh <spindrift> <spindriftFluidInBox> <tutorial dir> <kind> <type> <endTime>
#                       <max density error %> <xmin> <ymin> <xmax> <wallTop> <ceiling> <tolerance>
# (the tank arguments are passed on to spindriftFluidInBox, see FluidInBox.cpp)
# kind is a sphSchemes entry (kernel, pressure, viscosity, integrator). For pressure the
# tutorial's entry is kept under the name pressureReference and the new one copies it with
# only the type changed (the Tait options gamma/soundSpeed/clampNegativePressure are shared;
# wcsph's gradientCorrection is dropped for another type);
# the other entries are replaced by `{ type <type>; }` (the model's defaults). Either form of
# entry works: a block, or `kind $someDict;`. kind `none` runs the tutorial's own models.
set -euo pipefail
. "$(dirname "$0")/../../etc/RunFunctions" # cloneCase: a tutorial's input, never its results
solver=$1 inBox=$2 tutorial=$3 kind=$4 type=$5 endTime=$6 maxError=$7
shift 7
box=("$@")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cloneCase "$tutorial" "$work/case"
cd "$work/case"
schemes=system/sphSchemes
if [ "$kind" = none ]; then
    :   # the tutorial's own models
elif ! grep -qE "^$kind(\s|\$)" $schemes; then
    echo "FAIL: no '$kind' entry in $schemes"; exit 1
elif [ "$kind" = pressure ]; then
    sed -i -E "s/^pressure(\s|\$)/pressureReference\1/" $schemes
    # wcsph's own option (its kernel-corrected gradient) is not a Tait option the others share
    [ "$type" = wcsph ] || sed -i -E "/^\s*gradientCorrection\s/d" $schemes
    printf '\npressure\n{\n    $pressureReference;\n    type        %s;\n}\n' "$type" >> $schemes
elif grep -qE "^$kind\s+\\$" $schemes; then
    sed -i -E "s/^$kind\s+\\$.*/$kind { type $type; }/" $schemes
else
    sed -i "/^$kind\$/,/^}/c\\$kind\n{\n    type        $type;\n}" $schemes
fi
sed -i -E "s/^endTime .*/endTime $endTime;/; s/^writeInterval .*/writeInterval $endTime;/" system/controlDict

if ! "$solver" -case . -threads 1 > log.spindrift 2>&1; then
    echo "FAIL: the solver failed with $kind $type"
    tail -n 5 log.spindrift
    exit 1
fi
[ "$kind" = none ] || grep -q "$kind $type" log.spindrift || { echo "FAIL: the log does not report '$kind $type'"; head -n 30 log.spindrift; exit 1; }
last=$(tail -n 1 log.spindrift)
echo "$kind $type: $last"
error=$(sed -n -E 's/.*max density error ([0-9.eE+-]+)%.*/\1/p' <<< "$last")
[ -n "$error" ] || { echo "FAIL: no 'max density error' in the last log line"; exit 1; }
latest=$(ls -d [0-9]* | sort -g | tail -n 1)
[ "$(awk -v t="$latest" -v e="$endTime" 'BEGIN { print (t + 1e-12 >= e) ? 1 : 0 }')" = 1 ] \
    || { echo "FAIL: the last time written is $latest, not $endTime"; exit 1; }
"$inBox" "$latest/fluid.vtp" "${box[@]}" || { echo "FAIL: fluid left the tank with $kind $type"; exit 1; }
if awk -v e="$error" -v m="$maxError" 'BEGIN { exit !(e > m) }'; then
    echo "FAIL: max density error $error% exceeds $maxError% with $kind $type"
    exit 1
fi
echo "OK: $kind $type stays in the tank, max density error $error% (bound $maxError%)"
