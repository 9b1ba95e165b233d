#!/usr/bin/env bash
# A short dam-break run whose .pvd ParaView (pvpython) opens, seeing every written time, a block
# for the fluid and one for the wall system, and the arrays velocity, pressure, density, id; the
# wall's own pressure (adami) is that of each time, not t = 0's (issue 34, item 2).
#   damBreakParaView.sh <spindrift> <tutorial dir> <pvpython_check.py> <pvpython>
set -euo pipefail
. "$(dirname "$0")/../../etc/RunFunctions" # cloneCase: a tutorial's input, never its results
solver=$1 tutorial=$2 check=$3 pvpython=${4:-pvpython}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cloneCase "$tutorial" "$work/damBreak2D"
cd "$work/damBreak2D"
sed -i -E 's/^endTime .*/endTime 0.05;/; s/^writeInterval .*/writeInterval 0.01;/' system/controlDict
"$solver" -case . > log.spindrift 2>&1 || { tail -n 20 log.spindrift; exit 1; }
tail -n 1 log.spindrift
for t in 0 0.01 0.02 0.03 0.04 0.05; do
    [ -f "$t/fluid.vtp" ] || { echo "missing $t/fluid.vtp"; ls; exit 1; }
done
for t in 0 0.01 0.02 0.03 0.04 0.05; do
    [ -f "$t/tank.vtp" ] || { echo "missing $t/tank.vtp (the wall system 'tank', written at every time)"; exit 1; }
done
if ls -a | grep -q '\.tmp$'; then echo "temporary files left behind"; ls -a; exit 1; fi
"$pvpython" "$check" --blocks 2 --changing tank:pressure damBreak2D.pvd 6 velocity pressure density id
