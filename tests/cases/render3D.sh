#!/usr/bin/env bash
# spindriftRender in 3D (issue 36): a coarse breakingWave3D (1,000 fluid particles, 0.8 s, diffuse
# particles made easier to generate) rendered at its written times: the tank seen obliquely with
# the walls facing the camera left out (the fluid shows at t = 0), and at 0.8 s the spray, foam
# and bubbles in their colours (magenta, white, black) where the picture without them differs,
# and the surface mesh changing the picture. Skipped (77) without pvbatch.
#   render3D.sh <spindrift> <tutorials dir>
set -euo pipefail
. "$(dirname "$0")/../../etc/RunFunctions" # cloneCase: a tutorial's input, never its results
solver=$1 tutorials=$2
render=$(dirname "$solver")/spindriftRender
fail() { echo "FAIL: $*"; exit 1; }
command -v pvbatch > /dev/null || { echo "pvbatch not found: skipped"; exit 77; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
case=$work/breakingWave3D
cloneCase "$tutorials/breakingWave3D" "$case"
sed -i -E 's/^endTime .*/endTime 0.8;/; s/^writeInterval .*/writeInterval 0.4;/' "$case/system/controlDict"
sed -i -E 's/^particleSpacing .*/particleSpacing 0.04;/' "$case/constant/fluidProperties"
# lower thresholds and rates: all three types at 0.8 s on this coarse lattice (34 spray, 3502
# foam, 63 bubbles when written)
sed -i -E 's/^(\s*)trappedAir .*/\1trappedAir (1 5);/; s/^(\s*)waveCrest .*/\1waveCrest (0.5 4);/;
           s/^(\s*)kineticEnergy .*/\1kineticEnergy (0.5 4);/; s/^(\s*)kTrappedAir .*/\1kTrappedAir 100;/;
           s/^(\s*)kWaveCrest .*/\1kWaveCrest 1000;/' "$case/system/sphSchemes"
"$solver" -case "$case" > "$work/log" 2>&1 || { tail "$work/log"; fail "the run failed"; }
for t in 0 0.4 0.8; do
    for f in diffuse.vtp surface.vtp; do [ -f "$case/$t/$f" ] || fail "the run wrote no $t/$f"; done
done
run() {
    env -u DISPLAY "$render" -case "$case" -fields velocity -size 400x200 "$@" > "$work/render.log" 2>&1 \
        || { grep -av '^ *[0-9]* *0x' "$work/render.log" | tail -n 20; fail "spindriftRender $* failed"; }
    grep "^Wrote" "$work/render.log"
}
run -times all
run -times 0.8 -diffuse no -output "$work/noDiffuse"
run -times 0.8 -diffuse no -surface no -output "$work/plain"
/usr/bin/python3 - "$case/screenshots" "$work/noDiffuse" "$work/plain" <<'PY'
import sys, numpy as np
from matplotlib import image
shots, no_diffuse, plain = sys.argv[1:]
def read(d, t):
    a = image.imread("%s/breakingWave3D_velocity_%s.png" % (d, t))[:, :, :3]
    if a.shape[:2] != (200, 400): sys.exit("t = %s: %s pixels" % (t, a.shape))
    return a[25:, :320]  # the tank: below the title, left of the colour bars
a = read(shots, "0")
white = (a > 0.95).all(axis=2).mean()
grey = ((abs(a[:, :, 0] - a[:, :, 1]) < 0.03) & (abs(a[:, :, 1] - a[:, :, 2]) < 0.03) & (abs(a[:, :, 0] - 0.55) < 0.15)).mean()
colour = (a.max(axis=2) - a.min(axis=2) > 0.1).mean()
print("t = 0: %.0f %% white, %.0f %% grey (walls), %.1f %% fluid" % (100 * white, 100 * grey, 100 * colour))
if not 0.2 < white < 0.9: sys.exit("t = 0: %.2f white" % white)
if grey < 0.1: sys.exit("t = 0: no walls (grey)")
if colour < 0.02: sys.exit("t = 0: the fluid does not show (the walls facing the camera drawn?)")
a, b, c = read(shots, "0.8"), read(no_diffuse, "0.8"), read(plain, "0.8")
new = (abs(a - b) > 0.05).any(axis=2)  # where the diffuse particles are drawn
spray = (new & (a[:, :, 0] > 0.7) & (a[:, :, 1] < 0.3) & (a[:, :, 2] > 0.6)).sum()
foam = (new & (a > 0.95).all(axis=2)).sum()
bubbles = (new & (a < 0.15).all(axis=2)).sum()
surface = (abs(b - c) > 0.02).any(axis=2).mean()
print("t = 0.8: %d pixels of spray (magenta), %d of foam (white), %d of bubbles (black); the surface "
      "mesh changes %.1f %% of the picture" % (spray, foam, bubbles, 100 * surface))
if spray < 5 or foam < 50 or bubbles < 5: sys.exit("t = 0.8: a type of diffuse particle does not show")
if surface < 0.01: sys.exit("t = 0.8: the surface mesh does not show")
PY
echo "spindriftRender 3D: OK"
