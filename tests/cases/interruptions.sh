#!/usr/bin/env bash
# Interruptions lose nothing: SIGINT/SIGTERM/SIGHUP write the current time and exit 0; during
# set-up they stop at once with a message naming the signal (status 128 + signal) and leave no
# case lock; a fatal signal (a plugin that dereferences null) leaves its last words, naming the
# last completed step, in the log and on stderr and the status of the signal (139); a changed
# controlDict is re-read during the run; SIGKILL in the middle of a write leaves only complete
# time directories (and a .pvd listing only those), and the run continues from the latest;
# SIGKILL between a time directory's rename and the .pvd's leaves the .pvd behind by that time
# only, never ahead, until the next run; a restart of other particles is refused; a time
# directory the user cannot move or remove is named, never left hidden without a word.
#   interruptions.sh <spindrift> <tutorials dir> <libspindriftTestFaultyForce.so>
set -euo pipefail
. "$(dirname "$0")/../../etc/RunFunctions" # cloneCase: a tutorial's input, never its results
solver=$1 tutorials=$2 faultyForce=$3
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
# every numeric directory is complete, and the .pvd lists exactly those
checkComplete() {
    local c=$1 d
    for d in "$c"/[0-9]*; do
        [ -f "$d/fluid.vtp" ] && [ -f "$d/uniform/time" ] || fail "incomplete time directory $d"
        grep -q "file=\"$(basename "$d")/fluid.vtp\"" "$c/$(basename "$c").pvd" || fail "$d missing from the .pvd"
    done
    for f in $(grep -o 'file="[^"]*fluid.vtp"' "$c/$(basename "$c").pvd" | sed 's/file="//; s/"$//'); do
        [ -f "$c/$f" ] || fail ".pvd lists $f which does not exist"
    done
}

for sig in INT TERM HUP; do
    newCase sig$sig 10
    "$solver" -case "$work/sig$sig" > "$work/sig$sig/log" 2>&1 &
    pid=$!
    waitFor "$work/sig$sig/0.01" $pid || fail "SIG$sig run did not reach 0.01"
    kill -$sig $pid
    wait $pid || fail "SIG$sig: exit status $? (expected 0)"
    grep -q "SIG$sig received: wrote time" "$work/sig$sig/log" || fail "SIG$sig: no message"
    last=$(ls -d "$work/sig$sig"/[0-9]* | xargs -n1 basename | sort -g | tail -n 1)
    grep -q "wrote time $last " "$work/sig$sig/log" || fail "SIG$sig: the last time $last is not the one reported"
    checkComplete "$work/sig$sig"
    echo "ok SIG$sig: stopped with time $last written"
done

# a case with the test force that fails on purpose (tests/plugins/FaultyForce.cpp)
faultyCase() { # faultyCase <name> <entries of the force>
    newCase "$1" 10
    sed -i -E "s|^libs .*|libs (\"$faultyForce\");|" "$work/$1/system/controlDict"
    echo "forces { fault { type faulty; $2 } }" >> "$work/$1/system/sphSchemes"
}
waitForLine() { # waitForLine <text> <file> <pid>
    for _ in $(seq 1 600); do grep -q "$1" "$2" && return 0; kill -0 "$3" 2>/dev/null || return 1; sleep 0.1; done; return 1
}

# a signal during set-up: a message naming it, the process ends as killed by it, nothing written
for sig in INT TERM HUP; do
    faultyCase setUp$sig "setUpSeconds 60;"
    "$solver" -case "$work/setUp$sig" > "$work/setUp$sig/log" 2>&1 &
    pid=$!
    waitForLine "faulty: sleeping in set-up" "$work/setUp$sig/log" $pid || fail "SIG$sig: set-up not reached"
    kill -$sig $pid
    status=0
    wait $pid || status=$?
    [ $status -eq $((128 + $(kill -l $sig))) ] || fail "SIG$sig during set-up: exit status $status"
    grep -qx "spindrift: SIG$sig received during set-up (before the time loop): stopped" "$work/setUp$sig/log" \
        || fail "SIG$sig during set-up: no message: $(tail -n 3 "$work/setUp$sig/log")"
    if ls "$work/setUp$sig" | grep -q '^[0-9]'; then fail "SIG$sig during set-up: a time was written"; fi
    if ls -a "$work/setUp$sig" | grep -q '^\.spindrift\.lock'; then fail "SIG$sig during set-up: the case lock is left"; fi
    echo "ok SIG$sig during set-up: exit status $status, '$(tail -n 1 "$work/setUp$sig/log")'"
done

# a fatal signal: the last words name the last completed step, in the log (flushed up to them)
# and on stderr, and the exit status stays that of the signal
faultyCase segfault "segfaultAfterStep 5;"
echo "logInterval 1;" >> "$work/segfault/system/controlDict"
status=0
(ulimit -c 0; exec "$solver" -case "$work/segfault" > "$work/segfault/log" 2> "$work/segfault/err") || status=$?
[ $status -eq 139 ] || fail "segfault: exit status $status, not 139 (SIGSEGV)"
last=$(tail -n 1 "$work/segfault/log")
[[ "$last" =~ ^spindrift:\ fatal\ signal\ SIGSEGV\ at\ step\ 5,\ time\ ([0-9.e-]+)\ \(last\ completed\ step\)$ ]] \
    || fail "segfault: the log's last line is '$last'"
grep -q "^Time = ${BASH_REMATCH[1]}  step 5 " "$work/segfault/log" || fail "segfault: the time named is not step 5's"
[ "$(grep -c '^Time = ' "$work/segfault/log")" -eq 5 ] || fail "segfault: the log lacks step lines written before"
[ "$(cat "$work/segfault/err")" = "$last" ] || fail "segfault: stderr is '$(cat "$work/segfault/err")'"
# a log taking stdout and stderr gets the message once
status=0
(ulimit -c 0; exec "$solver" -case "$work/segfault" > "$work/segfault/log2" 2>&1) || status=$?
[ $status -eq 139 ] || fail "segfault (2>&1): exit status $status"
[ "$(grep -c "fatal signal" "$work/segfault/log2")" -eq 1 ] || fail "segfault (2>&1): not one message"
echo "ok fatal signal: exit status 139, '$last'"

# runTimeModifiable: shorten endTime while running
newCase modify 10
"$solver" -case "$work/modify" > "$work/modify/log" 2>&1 &
pid=$!
waitFor "$work/modify/0.005" $pid || fail "modify run did not reach 0.005"
sed -i -E "s/^endTime .*/endTime 0.02;/" "$work/modify/system/controlDict"
wait $pid || fail "modified run failed"
grep -q "Re-read system/controlDict" "$work/modify/log" || fail "controlDict change not noticed"
[ -d "$work/modify/0.02" ] && [ ! -d "$work/modify/0.025" ] || fail "the run did not stop at the new endTime 0.02"
echo "ok runTimeModifiable: stopped at the new endTime"

# SIGKILL in the middle of the 4th write, then continue from the latest complete time
newCase kill 0.03
set +e
SPINDRIFT_FAULT_INJECTION=killDuringWrite:4 "$solver" -case "$work/kill" > "$work/kill/log" 2>&1
status=$?
set -e
[ $status -eq 137 ] || fail "expected the solver to be killed (137), got $status"
ls -a "$work/kill" | grep -q '^\.0\.015\.tmp$' || fail "the kill did not happen during the write of 0.015"
[ ! -d "$work/kill/0.015" ] || fail "a half-written time became visible"
checkComplete "$work/kill"
sed -i -E "s/^startFrom .*/startFrom latestTime;/" "$work/kill/system/controlDict"
"$solver" -case "$work/kill" > "$work/kill/log2" 2>&1 || fail "restart after the kill failed"
grep -q "Restarting from time 0.01 " "$work/kill/log2" || fail "did not restart from 0.01"
checkComplete "$work/kill"
[ -d "$work/kill/0.03" ] || fail "the restarted run did not reach 0.03"
if ls -a "$work/kill" | grep -q '\.tmp$'; then fail "temporary directories left after the restart"; fi
echo "ok SIGKILL during a write: only complete times, restart continued to 0.03"

# SIGKILL between the rename of time 0.01 (the 3rd write) and that of the .pvd: the .pvd, whose
# new text was ready in <case>.pvd.tmp, is behind by 0.01 only and lists nothing that is not
# complete; the next run (a restart) lists it again
newCase window 0.02
set +e
SPINDRIFT_FAULT_INJECTION=killAfterRename:3 "$solver" -case "$work/window" > "$work/window/log" 2>&1
status=$?
set -e
[ $status -eq 137 ] || fail "window: expected the solver to be killed (137), got $status"
[ -f "$work/window/0.01/fluid.vtp" ] || fail "window: 0.01 was not renamed before the kill"
pvd="$work/window/window.pvd"
grep -q 'file="0.005/fluid.vtp"' "$pvd" || fail "window: the .pvd lost 0.005"
if grep -q 'file="0.01/' "$pvd"; then fail "window: the kill did not happen before the .pvd's rename"; fi
for f in $(grep -o 'file="[^"]*"' "$pvd" | sed 's/file="//; s/"$//'); do
    [ -f "$work/window/$f" ] || fail "window: the .pvd lists $f which does not exist"
done
grep -q 'file="0.01/fluid.vtp"' "$pvd.tmp" || fail "window: the .pvd's next text was not ready before the rename"
sed -i -E "s/^startFrom .*/startFrom latestTime;/" "$work/window/system/controlDict"
"$solver" -case "$work/window" > "$work/window/log2" 2>&1 || fail "window: the restart failed"
grep -q "Restarting from time 0.01 " "$work/window/log2" || fail "window: did not restart from 0.01"
checkComplete "$work/window"
echo "ok SIGKILL between the renames: the .pvd behind by 0.01 only (never ahead), listed again by the restart"

# a restart of other particles than its time's: refused, one line naming the file, the keyword
# and both values, exit status 1, nothing written or moved
newCase spacing 0.01
"$solver" -case "$work/spacing" > "$work/spacing/log" 2>&1 || fail "spacing: the first run failed"
sed -i -E "s/^startFrom .*/startFrom latestTime;/; s/^endTime .*/endTime 0.02;/" "$work/spacing/system/controlDict"
sed -i -E "s/^particleSpacing .*/particleSpacing 0.0028575;/" "$work/spacing/constant/fluidProperties"
before=$(ls -a "$work/spacing" | tr '\n' ' '; cat "$work/spacing/spacing.pvd")
status=0
"$solver" -case "$work/spacing" > "$work/spacing.log2" 2> "$work/spacing.err" || status=$?
[ $status -eq 1 ] || fail "spacing: exit status $status, not 1"
[ "$(wc -l < "$work/spacing.err")" -eq 1 ] || fail "spacing: not one line: $(cat "$work/spacing.err")"
grep -qE "^$work/spacing/constant/fluidProperties:[0-9]+:1: error: particleSpacing 0.0028575 is not the 0.00142875 of time 0.01 \(.*0.01/uniform/particles\): a restart continues its particles; use particleSpacing 0.00142875, or 'startFrom startTime;' to start anew \(keyword 'particleSpacing'\)$" "$work/spacing.err" \
    || fail "spacing: message '$(cat "$work/spacing.err")'"
[ "$(ls -a "$work/spacing" | tr '\n' ' '; cat "$work/spacing/spacing.pvd")" = "$before" ] || fail "spacing: something was written or moved"
echo "ok restart with another particleSpacing: exit status 1, '$(cat "$work/spacing.err")'"

# another user (nobody) on a case of root's: a time directory it cannot move aside (a fresh run
# owns the case's times) stops the run naming it; one it cannot remove after rewriting the time
# (-dryRun from latestTime rewrites it) is named in a warning. Run as root only (setpriv), and
# only where nobody can run the build (a build inside a private directory, e.g. a mktemp -d
# clone, is not reachable by another user).
asNobody() { setpriv --reuid=65534 --regid=65534 --clear-groups "$@"; }
if [ "$(id -u)" -eq 0 ] && command -v setpriv > /dev/null && ! asNobody "$solver" -version > /dev/null 2>&1; then
    echo "skipped: the user nobody cannot run $solver here (a private directory on its path)"
elif [ "$(id -u)" -eq 0 ] && command -v setpriv > /dev/null; then
    chmod 755 "$work"
    newCase other 0.01
    "$solver" -case "$work/other" > "$work/other/log" 2>&1 || fail "other user: the first run failed"
    chmod 777 "$work/other"
    chmod -R a+rwX "$work/other/postProcessing" 2> /dev/null || true # (the function objects' files: not what is tried)
    chmod 000 "$work/other/0.01"
    status=0
    asNobody "$solver" -case "$work/other" > "$work/other/log2" 2> "$work/other/err" || status=$?
    [ $status -eq 1 ] || fail "other user: exit status $status, not 1: $(cat "$work/other/err")"
    grep -qE "^spindrift: error: cannot move '$work/other/0' \(an earlier run's time 0\) to '$work/other/previousRun': Permission denied; remove it \(or make it writable\): this run would mix it into its results$" "$work/other/err" \
        || fail "other user: message '$(cat "$work/other/err")'"
    [ -d "$work/other/0.01" ] || fail "other user: 0.01 is gone"
    if ls -a "$work/other" | grep -q '\.old$'; then fail "other user: a hidden .old is left"; fi
    echo "ok another user's time directory that cannot be moved: exit status 1, '$(cat "$work/other/err")'"
    chmod 755 "$work/other/0.01"
    sed -i -E "s/^startFrom .*/startFrom latestTime;/" "$work/other/system/controlDict"
    asNobody "$solver" -case "$work/other" -dryRun > "$work/other/log3" 2>&1 || fail "other user: -dryRun failed: $(tail -n 3 "$work/other/log3")"
    grep -q "Warning: time 0.01: the earlier contents could not be removed (Permission denied); they are kept in $work/other/.0.01.old: remove it by hand" "$work/other/log3" \
        || fail "other user: no warning for the .0.01.old left: $(grep -i warn "$work/other/log3")"
    [ -f "$work/other/0.01/fluid.vtp" ] && [ -d "$work/other/.0.01.old" ] || fail "other user: 0.01 not rewritten"
    echo "ok another user's time that cannot be removed after a rewrite: named in a warning"
else
    echo "skipped the other-user checks (need root and setpriv)"
fi
