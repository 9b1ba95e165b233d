#!/usr/bin/env bash
# One solver per case (<case>/.spindrift.lock, "pid host"): a second solver on a case in use
# stops with exit status 1 naming the first's pid and writes nothing; the first finishes
# undisturbed and removes the lock; a lock whose process is gone (a killed run) is taken over
# with a warning; a failed start leaves no lock behind.
#   caseLock.sh <spindrift> <tutorials dir>
set -euo pipefail
. "$(dirname "$0")/../../etc/RunFunctions" # cloneCase: a tutorial's input, never its results
solver=$1 tutorials=$2
work=$(mktemp -d)
trap 'kill $(jobs -p) 2>/dev/null || true; rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
newCase() { # newCase <name> <endTime>
    cloneCase "$tutorials/damBreak2D" "$work/$1"
    sed -i -E "s/^endTime .*/endTime $2;/; s/^writeInterval .*/writeInterval 0.005;/" "$work/$1/system/controlDict"
}
waitFor() { # waitFor <path> <pid>
    for _ in $(seq 1 600); do [ -e "$1" ] && return 0; kill -0 "$2" 2>/dev/null || return 1; sleep 0.1; done; return 1
}
lock=.spindrift.lock

# two solvers on one case: the second refused while the first runs
newCase two 10
"$solver" -case "$work/two" > "$work/two/log1" 2>&1 &
first=$!
waitFor "$work/two/0.005" $first || fail "the first run did not reach 0.005"
[ "$(cat "$work/two/$lock")" = "$first $(hostname)" ] || fail "lock holds '$(cat "$work/two/$lock")', not '$first $(hostname)'"
ls "$work/two" | grep -E '^[0-9]' > "$work/before"
status=0
"$solver" -case "$work/two" > "$work/two/log2" 2> "$work/two/err2" || status=$?
[ $status -eq 1 ] || fail "second solver: exit status $status, not 1"
[ "$(wc -l < "$work/two/err2")" -eq 1 ] || fail "second solver: not one line: $(cat "$work/two/err2")"
grep -qE "^$work/two/\.spindrift\.lock: error: the case is in use by spindrift pid $first on host $(hostname)" "$work/two/err2" \
    || fail "second solver: message '$(cat "$work/two/err2")'"
[ "$(cat "$work/two/$lock")" = "$first $(hostname)" ] || fail "the second solver changed the lock"
kill -INT $first
wait $first || fail "the first run: exit status $? after SIGINT (expected 0)"
grep -q "SIGINT received: wrote time" "$work/two/log1" || fail "the first run did not stop as asked"
[ ! -e "$work/two/$lock" ] || fail "the lock is left after the run"
echo "ok second solver refused: '$(cat "$work/two/err2")'"

# a stale lock (a pid that is gone) is taken over with a warning; the run completes, no lock left
newCase stale 0.01
sh -c 'exit 0' &
dead=$!
wait $dead
echo "$dead $(hostname)" > "$work/stale/$lock"
"$solver" -case "$work/stale" > "$work/stale/log" 2>&1 || fail "stale lock: the run failed: $(tail -n 3 "$work/stale/log")"
grep -q "stale lock .* of pid $dead (no longer running): taken over" "$work/stale/log" || fail "stale lock: no warning"
[ -d "$work/stale/0.01" ] || fail "stale lock: the run did not reach 0.01"
[ ! -e "$work/stale/$lock" ] || fail "stale lock: a lock is left after the run"
echo "ok stale lock of pid $dead taken over"

# a live lock of another process (not a solver: any live pid): refused, nothing written
newCase live 0.01
sleep 60 &
sleeper=$!
echo "$sleeper $(hostname)" > "$work/live/$lock"
status=0
"$solver" -case "$work/live" > /dev/null 2> "$work/live/err" || status=$?
[ $status -eq 1 ] || fail "live lock: exit status $status"
grep -q "in use by spindrift pid $sleeper " "$work/live/err" || fail "live lock: message '$(cat "$work/live/err")'"
if ls "$work/live" | grep -qE '^[0-9]|\.pvd$'; then fail "live lock: something was written"; fi
kill $sleeper
echo "ok live lock refused, nothing written"

# a bad input after the lock is taken: no lock left behind
newCase bad 0.01
sed -i -E "s/^endTime .*/endTime -1;/" "$work/bad/system/controlDict"
if "$solver" -case "$work/bad" > /dev/null 2>&1; then fail "bad input accepted"; fi
[ ! -e "$work/bad/$lock" ] || fail "bad input: a lock is left"
sed -i -E "s/^writeFields .*/writeFields (velocty);/; s/^endTime .*/endTime 0.01;/" "$work/bad/system/controlDict"
if "$solver" -case "$work/bad" > /dev/null 2>&1; then fail "bad writeFields accepted"; fi
[ ! -e "$work/bad/$lock" ] || fail "bad writeFields (after the lock): a lock is left"
echo "ok no lock left after a refused start"
