#!/usr/bin/env bash
# A full disk while writing a time (issue 21, item 10): one line "no space left on device
# (<path>)" and exit status 1, never VTK's own error text; every time written before is kept
# complete (its fluid.vtp whole, uniform/time present, listed in the .pvd), no partial or hidden
# time directory is left, and the case restarts from the newest time once there is room.
# Runs on a 448 KiB tmpfs (room for three times of fluid and wall files, about 112 KiB each);
# skipped (exit 77) where one cannot be mounted (not root, a container without CAP_SYS_ADMIN).
#   fullDisk.sh <spindrift> <tutorials dir>
set -uo pipefail
. "$(dirname "$0")/../../etc/RunFunctions" # cloneCase: a tutorial's input, never its results
solver=$1 tutorials=$2
work=$(mktemp -d)
disk="$work/disk"
mkdir -p "$disk"
if ! mount -t tmpfs -o size=448k tmpfs "$disk" 2> "$work/mount.err"; then
    echo "SKIP: cannot mount a small tmpfs to fill ($(head -c 200 "$work/mount.err")): needs root (CAP_SYS_ADMIN)"
    rm -rf "$work"
    exit 77
fi
trap 'umount "$disk"; rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

case="$disk/tank"
cloneCase "$tutorials/hydrostaticTank2D" "$case"
sed -i -E "s/^endTime .*/endTime 0.5;/; s/^writeInterval .*/writeInterval 0.01;/" "$case/system/controlDict"
status=0
"$solver" -case "$case" > "$work/log" 2> "$work/stderr" || status=$?
echo "stderr: $(cat "$work/stderr")"
[ $status -eq 1 ] || fail "exit status $status, not 1 (the disk did not fill? $(df -k "$disk" | tail -1))"
[ "$(wc -l < "$work/stderr")" -eq 1 ] || fail "not one line on stderr"
grep -qE "^spindrift: error: no space left on device \($case/[^)]*\): time [0-9.e-]+ not written; the times written before it are complete$" "$work/stderr" \
    || fail "message"
! grep -qiE "vtk|ERROR: In " "$work/stderr" "$work/log" || fail "VTK's own error text"

# what was written before is intact
times=$(cd "$case" && ls -d [0-9]* 2> /dev/null | sort -g)
[ "$(echo "$times" | wc -w)" -ge 3 ] || fail "fewer than 3 times written before the disk filled: $times"
leftovers=$(cd "$case" && ls -A | grep -E '^\..*\.(tmp|old)$|\.tmp$' || true)
[ -z "$leftovers" ] || fail "partial files left: $leftovers"
for t in $times; do
    [ -f "$case/$t/uniform/time" ] || fail "time $t: no uniform/time"
    tail -c 64 "$case/$t/fluid.vtp" | grep -q "</VTKFile>" || fail "time $t: fluid.vtp cut short"
    grep -q "file=\"$t/fluid.vtp\"" "$case/tank.pvd" || fail "time $t not in the .pvd"
done
echo "ok the disk filled after times: $(echo $times)"

# ... and loadable: restarted from the newest elsewhere, the run goes on
latest=$(echo "$times" | tail -1)
cp -a "$case" "$work/copy"
rm -f "$work/copy/.spindrift.lock"
sed -i -E "s/^startFrom .*/startFrom latestTime;/; s/^endTime .*/endTime $(python3 -c "print($latest + 0.02)");/" \
    "$work/copy/system/controlDict"
"$solver" -case "$work/copy" > "$work/restart.log" 2>&1 || fail "the restart from $latest failed: $(tail -3 "$work/restart.log")"
grep -q "Restarting from time $latest " "$work/restart.log" || fail "did not restart from $latest: $(grep -i restart "$work/restart.log")"
grep -q "Warning" "$work/restart.log" && fail "warnings on restart: $(grep Warning "$work/restart.log")"
echo "ok restarted from $latest and ran to the end"
