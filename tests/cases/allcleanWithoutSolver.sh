#!/usr/bin/env bash
# A tutorial's Allclean, in a copy outside the tree, with no spindrift on PATH and no SPINDRIFT_DIR
# (a fresh shell): it removes the results (time directories, unfinished .<time>.tmp ones,
# postProcessing/, the .pvd, logs; plots for a validation case) and keeps the input — cleaning
# needs no solver. And the same through etc/RunFunctions (SPINDRIFT_DIR set).
#   allcleanWithoutSolver.sh <tutorials dir>
set -euo pipefail
tutorials=$(cd "$1" && pwd)
fail() { echo "FAIL: $*"; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
results() { # results <case>: what a run leaves
    mkdir -p "$1/0" "$1/0.01/uniform" "$1/1e-05" "$1/.0.02.tmp" "$1/postProcessing/stats/0"
    touch "$1/0/fluid.vtp" "$1/$(basename "$1").pvd" "$1/log.spindrift" "$1/postProcessing/stats/0/stats.dat"
}
check() { # check <case> <what>
    local left
    left=$(cd "$1" && ls -A | grep -vxE 'Allrun|Allclean|README.md|system|constant|[A-Za-z0-9_]+\.(py|csv)' || true)
    [ -z "$left" ] || fail "$2: left $(tr '\n' ' ' <<< "$left")"
    [ -f "$1/system/controlDict" ] && [ -d "$1/constant" ] || fail "$2: removed the input"
}
for t in damBreak2D validation/hydrostaticTank2D; do
    c=$work/$(basename "$t")
    cp -r "$tutorials/$t" "$c"
    rm -rf "$c"/[0-9]* "$c"/postProcessing "$c"/log.* "$c"/*.pvd "$c"/*.png
    results "$c"
    touch "$c/plot.png"
    env -i HOME="$HOME" PATH=/usr/bin:/bin bash -c '"$1/Allclean"' _ "$c" > "$work/log" 2>&1 \
        || fail "$t: Allclean without spindrift on PATH: $(cat "$work/log")"
    [ -f "$c/plot.png" ] && [ "$t" != damBreak2D ] && fail "$t: the plot was left"
    rm -f "$c/plot.png"
    check "$c" "$t without spindrift"
    results "$c"
    env -i HOME="$HOME" PATH=/usr/bin:/bin SPINDRIFT_DIR="$tutorials/.." bash -c '"$1/Allclean"' _ "$c" > "$work/log" 2>&1 \
        || fail "$t: Allclean with SPINDRIFT_DIR: $(cat "$work/log")"
    check "$c" "$t through RunFunctions"
    echo "ok $t: Allclean with and without a solver"
done
echo "Allclean without a solver: OK"
