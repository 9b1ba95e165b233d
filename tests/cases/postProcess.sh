#!/usr/bin/env bash
# spindrift -postProcess [-func NAME] [-time RANGE]: the function objects run over the written
# times without solving reproduce, row for row, what the run itself wrote with `writeControl
# writeTime` (probes, fieldStats, waterLevel, surgeFront); -func runs one and leaves the others'
# output alone; -time selects times (the output folder named after the first); the time
# directories and the .pvd are not touched; bad requests exit 1 with a message.
#   postProcess.sh <spindrift> <tutorials dir>
set -euo pipefail
. "$(dirname "$0")/../../etc/RunFunctions" # cloneCase: a tutorial's input, never its results
solver=$1 tutorials=$2
fail() { echo "FAIL: $*"; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
case=$work/tank
cloneCase "$tutorials/hydrostaticTank2D" "$case"
sed -i -E 's/^endTime .*/endTime 0.04;/; s/^writeInterval .*/writeInterval 0.01;/' "$case/system/controlDict"
cat >> "$case/system/controlDict" <<'EOF'
functions
{
    probes { type probes; fields (pressure velocity density); probeLocations ((0.1 0.02 0) (0.05 0.15 0));
             writeControl writeTime; }
    stats  { type fieldStats; writeControl writeTime; }
    level  { type waterLevel; gaugeLocations ((0.1 0 0)); writeControl writeTime; }
    front  { type surgeFront; direction (1 0 0); writeControl writeTime; }
}
EOF
"$solver" -case "$case" > "$work/log.run" 2>&1 || { tail "$work/log.run"; fail "the run failed"; }
mv "$case/postProcessing" "$work/run"
ls "$case" | grep -vx postProcessing > "$work/before"
md5sum "$case"/*/fluid.vtp "$case/tank.pvd" > "$work/sums"

# compare <run file> <post-processed file> [first last]: same header (names and units), same
# times, values equal to 1e-9 (relative); with first and last, the run's rows between them
compare() {
    python3 - "$@" <<'PY'
import math, sys
run, post = open(sys.argv[1]).read().splitlines(), open(sys.argv[2]).read().splitlines()
first, last = (float(sys.argv[3]), float(sys.argv[4])) if len(sys.argv) > 4 else (-math.inf, math.inf)
if run[:2] != post[:2]: sys.exit("headers differ:\n%s\n%s" % ("\n".join(run[:2]), "\n".join(post[:2])))
if not run[1].startswith("# [s]"): sys.exit("no units line: %s" % run[1])
rows = lambda lines: [[float(v) for v in l.split()] for l in lines if not l.startswith("#")]
a = [r for r in rows(run) if first - 1e-12 <= r[0] <= last + 1e-12]
b = rows(post)
if [r[0] for r in a] != [r[0] for r in b]: sys.exit("times differ: %s against %s" % ([r[0] for r in a], [r[0] for r in b]))
for ra, rb in zip(a, b):
    for x, y in zip(ra, rb):
        if not (x == y or (math.isnan(x) and math.isnan(y)) or abs(x - y) <= 1e-9 * max(abs(x), abs(y))):
            sys.exit("t = %g: %r against %r" % (ra[0], ra, rb))
print("%d rows equal" % len(b))
PY
}

# every function object over every time
"$solver" -case "$case" -postProcess > "$work/log.post" 2>&1 || { cat "$work/log.post"; fail "-postProcess failed"; }
tail -n 6 "$work/log.post"
grep -q "^Post-processing 5 times (0 to 0.04) with probes, stats, level, front" "$work/log.post" \
    || fail "no summary line: $(grep -i post "$work/log.post")"
for f in probes stats level front; do
    [ -f "$case/postProcessing/$f/0/$f.dat" ] || fail "-postProcess wrote no postProcessing/$f/0/$f.dat"
    out=$(compare "$work/run/$f/0/$f.dat" "$case/postProcessing/$f/0/$f.dat") || fail "$f: $out"
    echo "ok $f: $out (the run's rows at 0, 0.01, ..., 0.04)"
done
[ "$(grep -vc '^#' "$work/run/probes/0/probes.dat")" -eq 5 ] || fail "the run's probes did not write 5 rows"

# one function object over some times: its folder is named after the first; the others untouched
cp -r "$case/postProcessing" "$work/post"
"$solver" -case "$case" -postProcess -func probes -time 0.015:0.03 > "$work/log.func" 2>&1 \
    || { cat "$work/log.func"; fail "-postProcess -func probes -time 0.015:0.03 failed"; }
out=$(compare "$work/run/probes/0/probes.dat" "$case/postProcessing/probes/0.02/probes.dat" 0.02 0.03) || fail "-func probes: $out"
echo "ok -func probes -time 0.015:0.03: $out (0.02, 0.03)"
for f in stats level front; do
    diff -r "$work/post/$f" "$case/postProcessing/$f" > /dev/null || fail "-func probes changed postProcessing/$f"
done
[ "$(ls "$case/postProcessing/probes")" = "$(printf '0\n0.02')" ] || fail "probes folders: $(ls "$case/postProcessing/probes")"

# the results are untouched
ls "$case" | grep -vx postProcessing > "$work/after"
diff "$work/before" "$work/after" || fail "-postProcess changed the case's entries"
md5sum -c --quiet "$work/sums" || fail "-postProcess changed a time directory or the .pvd"

# bad requests: exit 1, a message, nothing written
expectError() { # expectError <message pattern> <arguments...>
    local pattern=$1 status=0; shift
    "$solver" -case "$case" "$@" > "$work/out" 2> "$work/err" || status=$?
    [ $status -eq 1 ] || fail "'spindrift $*': exit status $status, not 1"
    grep -q -- "$pattern" "$work/err" || fail "'spindrift $*': '$(cat "$work/err")' lacks '$pattern'"
    echo "ok 'spindrift $*': $(head -n 1 "$work/err")"
}
rm -rf "$case/postProcessing"
expectError "controlDict:[0-9]*:[0-9]*: error: -func 'probe': no function object of that name.*(probes stats level front).*did you mean 'probes'" \
    -postProcess -func probe
expectError "-time '5' selects none of the written times (0 0.01 0.02 0.03 0.04)" -postProcess -time 5
expectError "-time 'a:b'" -postProcess -time a:b
expectError "use it with -postProcess" -func probes
[ ! -e "$case/postProcessing" ] || fail "a refused -postProcess wrote postProcessing/"
sed -i '/^functions/,$d' "$case/system/controlDict"
expectError "names no function object" -postProcess
echo "spindrift -postProcess: OK"
