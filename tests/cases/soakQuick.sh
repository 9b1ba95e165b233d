#!/usr/bin/env bash
# A short soak (issue 33): movingPaddle2D (a moving wall) with leapfrog and continuity density,
# killed (SIGKILL) at a random moment and restarted 4 times, each end state bit-identical to the
# uninterrupted run's (spindriftBench -soak; the full 200 runs are a manual check, minutes).
#   soakQuick.sh <spindriftBench> <tutorials dir>
set -euo pipefail
bench=$1 tutorials=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
status=0
"$bench" -case "$tutorials/movingPaddle2D" -output "$work/bench" -soak 4 -seed 7 \
    -combination "integrator.type=leapfrog particleSpacing=0.01 endTime=0.03 writeInterval=0.01" > "$work/log" 2>&1 || status=$?
cat "$work/log"
[ $status -eq 0 ] || { echo "FAIL: exit status $status"; exit 1; }
grep -q "^soak: 4/4 bit-identical" "$work/log" || { echo "FAIL: not 4/4 bit-identical"; exit 1; }
