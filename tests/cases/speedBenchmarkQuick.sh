#!/usr/bin/env bash
# The speed benchmark of issue 7 (tutorials/benchmarks/Allrun) on a few steps: every method
# runs on 1 and 2 threads and prints a complete row; the incompressible solvers do at least the
# 3 iterations of the reference; a run gives the same max density error on 1 and 2 threads
# (results do not depend on the thread count); -compare prints a row for each build and their
# ratio; -scaling a row per method with its speed-up against spindriftParallelCeiling's;
# -instructions (valgrind) the same count a step for the same build twice, or, for a build valgrind
# cannot decode (AVX-512 of -march=native), a message saying so. Times are printed, never asserted.
#   speedBenchmarkQuick.sh <bin dir>
set -euo pipefail
export SPINDRIFT_BIN=$1
here=$(cd "$(dirname "$0")" && pwd)
fail() { echo "FAIL: $*"; exit 1; }
[ -x "$SPINDRIFT_BIN/spindrift" ] || fail "no solver in $SPINDRIFT_BIN (the build's bin directory is expected)"
out=$("$here/../../tutorials/benchmarks/Allrun" -methods "wcsph pcisph pbf relaxedPbf dfsph" -threads "1 2" -endTime 0.006 -startupTime 0.002)
echo "$out"
! grep -q failed <<< "$out" || fail "a run failed"
for method in wcsph pcisph pbf relaxedPbf dfsph; do
    rows=$(awk -v m="$method" '$1 == m' <<< "$out")
    [ "$(wc -l <<< "$rows")" -eq 2 ] || fail "$method: expected rows for 1 and 2 threads"
    awk -v m="$method" '
        $3 != 6859 { print "FAIL: " m ": particles " $3; bad = 1 }
        # a few steps less a start-up of about the same time: a number, of either sign at this length
        $5 !~ /^-?[0-9.]+$/ || $6 !~ /^-?[0-9.]+$/ || !($10 > 0) || !($11 > 0) { print "FAIL: " m ": no time or memory: " $0; bad = 1 }
        m != "wcsph" && !($8 >= 3) { print "FAIL: " m ": fewer than 3 iterations: " $8; bad = 1 }
        { err[NR] = $9 }
        END { if (err[1] != err[2]) { print "FAIL: " m ": max density error differs with the thread count: " err[1] " vs " err[2]; bad = 1 }
              exit bad }' <<< "$rows" || exit 1
done
# paired rounds against another build (here the same one): a row each and the ratio
out=$("$here/../../tutorials/benchmarks/Allrun" -methods wcsph -threads 1 -endTime 0.004 -startupTime 0.002 -repeat 2 -compare "$SPINDRIFT_BIN")
echo "$out"
[ "$(awk '$1 == "wcsph" || $1 == "wcsph*"' <<< "$out" | wc -l)" -eq 2 ] || fail "-compare: expected a row for each build"
# (two steps less a start-up of about the same time: a ratio of either sign on a loaded host)
grep -qE "this build / the other \(\*\): -?[0-9.]+ \(means of 2 paired rounds\)" <<< "$out" || fail "-compare: no ratio"
# -scaling: a row per method with both thread counts' times, the ratios, the ceiling's and the efficiency
out=$("$here/../../tutorials/benchmarks/Allrun" -scaling -methods wcsph -endTime 0.004 -startupTime 0.002 -repeat 2)
echo "$out"
# (a few steps less a start-up of about the same time: numbers of either sign at this length)
awk '$1 == "wcsph" { found = 1
        if ($2 != 2 || $3 !~ /^-?[0-9.]+$/ || $4 !~ /^-?[0-9.]+$/ || $8 !~ /^-?[0-9.]+$/) { print "FAIL: -scaling row: " $0; exit 1 }
        for (i = 5; i <= 7; ++i) if ($i !~ /^-?[0-9.]+x$/) { print "FAIL: -scaling ratio: " $i; exit 1 } }
     END { if (!found) { print "FAIL: -scaling printed no row"; exit 1 } }' <<< "$out" || exit 1
# -instructions: deterministic, so the same build against itself reads 1 (to the start-up's few
# thousand instructions that depend on the environment)
if command -v valgrind > /dev/null; then
    out=$("$here/../../tutorials/benchmarks/Allrun" -instructions -methods wcsph -endTime 0.004 -startupTime 0.002 -compare "$SPINDRIFT_BIN")
    echo "$out"
    if grep -q "valgrind cannot decode this build's instructions" <<< "$out"; then
        echo "(a build with instructions valgrind cannot decode: counted nothing, said why)"
    else
        ratio=$(sed -nE 's/.*instructions per step, this build \/ the other \(\*\): ([0-9.]+) .*/\1/p' <<< "$out")
        [ -n "$ratio" ] || fail "-instructions: no ratio"
        awk -v r="$ratio" 'BEGIN { exit !(r >= 0.998 && r <= 1.002) }' || fail "-instructions: the same build counted $ratio times itself"
        awk '$1 == "wcsph" && $5 > 1 { found = 1 } END { exit !found }' <<< "$out" || fail "-instructions: no count a step"
    fi
fi
echo "speed benchmark quick: OK"
