#!/usr/bin/env bash
# Interruptions lose nothing: SIGINT/SIGTERM/SIGHUP write the current time and exit 0; during
# set-up they stop at once with a message naming the signal (status 128 + signal); a fatal
# signal (a plugin that dereferences null) leaves its last words, naming the last completed
# step, in the log and on stderr and the status of the signal (139); a changed controlDict is
# re-read during the run; SIGKILL in the middle of a write leaves only complete time directories
# (and a .pvd listing only those), and the run continues from the latest.
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
