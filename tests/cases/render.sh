#!/usr/bin/env bash
# spindriftRender (etc/python/spindriftRender.py with pvbatch, without a display): a short dam
# break rendered at every written time, coloured by velocity and by pressure: one PNG per field
# and time, of the size asked for, holding coloured fluid particles and grey wall particles on
# white. Skipped (77) without pvbatch.
#   render.sh <spindrift> <tutorials dir>
set -euo pipefail
. "$(dirname "$0")/../../etc/RunFunctions" # cloneCase: a tutorial's input, never its results
solver=$1 tutorials=$2
render=$(dirname "$solver")/spindriftRender
fail() { echo "FAIL: $*"; exit 1; }
command -v pvbatch > /dev/null || { echo "pvbatch not found: skipped"; exit 77; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cloneCase "$tutorials/damBreak2D" "$work/damBreak2D"
sed -i -E 's/^endTime .*/endTime 0.02;/; s/^writeInterval .*/writeInterval 0.01;/' "$work/damBreak2D/system/controlDict"
"$solver" -case "$work/damBreak2D" > "$work/log" 2>&1 || { tail "$work/log"; fail "the run failed"; }
env -u DISPLAY "$render" -case "$work/damBreak2D" -times all -size 400x200 > "$work/render.log" 2>&1 \
    || { grep -av '^ *[0-9]* *0x' "$work/render.log" | tail -n 20; fail "spindriftRender failed"; }
grep "^Wrote" "$work/render.log"
for f in velocity pressure; do
    for t in 0 0.01 0.02; do
        png=$work/damBreak2D/screenshots/damBreak2D_${f}_$t.png
        [ -f "$png" ] || fail "no $png"
    done
done
# the pictures: 400 x 200, white background, grey walls, coloured fluid (several colours: a
# field that varies); the velocity at t = 0 is zero everywhere (one colour), later it is not
/usr/bin/python3 - "$work/damBreak2D/screenshots" <<'PY'
import sys, numpy as np
from matplotlib import image
d = sys.argv[1]
for f in ("velocity", "pressure"):
    for t in ("0", "0.01", "0.02"):
        a = image.imread("%s/damBreak2D_%s_%s.png" % (d, f, t))[:, :, :3]
        if a.shape[:2] != (200, 400): sys.exit("%s %s: %s pixels" % (f, t, a.shape))
        white = (a > 0.95).all(axis=2).mean()
        grey = ((abs(a[:, :, 0] - a[:, :, 1]) < 0.03) & (abs(a[:, :, 1] - a[:, :, 2]) < 0.03) & (abs(a[:, :, 0] - 0.55) < 0.15)).mean()
        colour = a.max(axis=2) - a.min(axis=2) > 0.25
        hues = len({tuple(p) for p in (a[colour] * 8).astype(int)})
        print("%s t = %s: %.0f %% white, %.1f %% grey (walls), %.1f %% coloured in %d colours" % (f, t, 100 * white, 100 * grey, 100 * colour.mean(), hues))
        if not (0.3 < white < 0.98): sys.exit("%s %s: %.2f white" % (f, t, white))
        if grey < 0.002: sys.exit("%s %s: no wall particles (grey)" % (f, t))
        if colour.mean() < 0.01: sys.exit("%s %s: no coloured fluid" % (f, t))
        if (f == "pressure" or t != "0") and hues < 4: sys.exit("%s %s: the colour does not vary (%d colours)" % (f, t, hues))
PY
echo "spindriftRender: OK"
