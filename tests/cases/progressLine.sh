#!/usr/bin/env bash
# The progress line on a terminal (the solver run under script(1), which gives it a pseudo
# terminal) is redrawn at most 4 times a second, however short the steps: a 10,000-step run of a
# few seconds draws it a handful of times, not 10,000 (issue 34: 2,455 redraws, 150 kB, in a 2.3 s
# run). It is shown (the test sees it), log lines still go above it, and it is gone at the end.
#   progressLine.sh <spindrift> <tutorials dir>
set -euo pipefail
. "$(dirname "$0")/../../etc/RunFunctions" # cloneCase: a tutorial's input, never its results
solver=$1 tutorials=$2
fail() { echo "FAIL: $*"; exit 1; }
command -v script > /dev/null || { echo "script(1) not found (util-linux): skipped"; exit 77; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cloneCase "$tutorials/damBreak2D" "$work/case"
sed -i -E "s/^particleSpacing .*/particleSpacing 0.0142875;/" "$work/case/constant/fluidProperties" # a/4: 32 particles
sed -i -E 's/^adjustTimeStep .*/adjustTimeStep no;/; s/^deltaT .*/deltaT 1e-05;/; s/^endTime .*/endTime 0.1;/;
           s/^writeInterval .*/writeInterval 0.05;/' "$work/case/system/controlDict"
echo "logInterval 100000;" >> "$work/case/system/controlDict" # the first and the last step lines only
script -qefc "'$solver' -case '$work/case'" "$work/typescript" > /dev/null || fail "the run failed: $(tail -5 "$work/typescript")"
out=$work/typescript
steps=$(sed -n 's/^End: \([0-9]*\) steps .* in \([0-9.e+-]*\) s wall time.*/\1/p' "$out" | tr -d '\r')
wall=$(sed -n 's/^End: [0-9]* steps .* in \([0-9.e+-]*\) s wall time.*/\1/p' "$out" | tr -d '\r')
[ "$steps" = 10000 ] || fail "the run took '$steps' steps, not 10000"
# a redraw: the progress text ("[12.3%] t = ...") after a carriage return; the log lines printed
# while it is shown each redraw it once below them
draws=$(grep -ao '\[[0-9.]*%\] t = ' "$out" | wc -l)
lines=$(grep -acE 'Time = |Wrote time ' "$out")
bound=$(awk -v w="$wall" -v l="$lines" 'BEGIN { print int(4 * w) + 1 + l + 1 }')
echo "10000 steps in $wall s: $draws progress redraws, $lines log lines while it showed; at most $bound allowed"
[ "$draws" -ge 1 ] || fail "no progress line on the terminal"
[ "$draws" -le "$bound" ] || fail "$draws redraws in $wall s: more than 4 a second (+ one per log line)"
# the last thing on the terminal is the End line, not a progress line
grep -av '^Script done' "$out" | tail -c 300 | tr '\r' '\n' | grep -av '^\s*$' | tail -n 1 | grep -q "peak memory" \
    || fail "the progress line is left at the end: $(tail -c 200 "$out" | cat -v)"
echo "progress line: OK"
