#!/usr/bin/env bash
# The force on a wall from the reactions (the `forces` function object) against the pressure on
# it (probes integrated over its height): damBreakColagrossi2D with its far wall a wall of its
# own, at H/20 up to T = 7 (tutorials/validation/damBreakColagrossi2D/farWallForce.py). Once water
# stands against the wall (T >= 4) their means agree within 15 % at H/20 (measured 10.0 %; 4.9 %
# at H/40: docs/VALIDATION.md §0b); the force is positive (it pushes the wall out) and rises on
# impact.
#   farWallForceQuick.sh <spindrift> <pvpython> <case dir>
set -euo pipefail
solver=$1 pvpython=$2 source=$3
. "$(dirname "$0")/figures.sh" # fail, within
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$pvpython" "$source/farWallForce.py" --res 20 --endT 7 --work "$work/run" --spindrift "$solver" --no-plot \
    > "$work/figures" 2>&1 || { cat "$work/figures"; fail "farWallForce.py failed"; }
grep -v "^Warning" "$work/figures"
figures="$work/figures"
within forceDifference -15 15
within forceMean 0.2 0.6      # rho0 g H^2 (measured 0.37): the water standing against the wall
within forcePeak 0.3 3
echo "far-wall force: OK"
