#!/usr/bin/env bash
# End-to-end checks of the incompressible pressure solvers (pcisph, pbf, relaxedPbf, dfsph, iisph) through
# the real binary:
#   - the damBreak2D and damBreak3D tutorials swap solver by editing one word, and every
#     alternative reads and sets up (-dryRun);
#   - the -dryRun of a case with pcisph loads no position-based (PBF) library;
#   - a solver that hits maxIterations says so on the step line, and every step's iterations
#     and reached errors are in postProcessing/solverPerformance/0/solverPerformance.dat.
#   incompressibleSolvers.sh <spindrift> <tutorials dir>
set -euo pipefail
. "$(dirname "$0")/../../etc/RunFunctions" # cloneCase: a tutorial's input, never its results
solver=$1 tutorials=$2
fail() { echo "FAIL: $*"; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# swap <case> <solver>: the one word after "$pressureSolvers."
swap() { sed -i "s/^pressure \( *\)\$pressureSolvers\.[A-Za-z]*;/pressure \1\$pressureSolvers.$2;/" "$1/system/sphSchemes"; }

for tutorial in damBreak2D damBreak3D; do
    grep -q '^pressure *\$pressureSolvers\.wcsph;' "$tutorials/$tutorial/system/sphSchemes" \
        || fail "$tutorial: the default pressure solver must stay wcsph"
    [ -f "$tutorials/$tutorial/system/sphSolution" ] || fail "$tutorial has no system/sphSolution"
    for model in pcisph pbf relaxedPbf dfsph wcsph; do
        rm -rf "$work/case"
        cloneCase "$tutorials/$tutorial" "$work/case"
        swap "$work/case" $model
        [ "$(diff "$tutorials/$tutorial/system/sphSchemes" "$work/case/system/sphSchemes" | grep -c '^>')" -le 1 ] \
            || fail "$tutorial: swapping to $model changed more than one line"
        out=$("$solver" -case "$work/case" -dryRun -threads 1 2>&1) || fail "$tutorial with $model: $out"
        grep -q "pressure $model," <<< "$out" || fail "$tutorial: -dryRun does not report pressure $model"
        grep -q "libspindrift_pressure_$model.so" <<< "$out" || fail "$tutorial: $model plugin not loaded"
        if [ $model = pcisph ]; then
            if grep -i "^ *[^ ]*pbf[^ ]*\.so" <<< "$out"; then fail "-dryRun with pcisph loaded a PBF library"; fi
        fi
        echo "$tutorial: $model reads and sets up"
    done
done

# maxIterations reached: said on the step line and recorded
for model in pcisph relaxedPbf iisph; do
    rm -rf "$work/tank"
    cloneCase "$tutorials/hydrostaticTank2D" "$work/tank"
    sed -i '/^pressure/,/^}/c\pressure\n{\n    type        '$model';\n}' "$work/tank/system/sphSchemes"
    sed -i 's/^\(    alpha .*\)$/\1\n    soundSpeed  25;/' "$work/tank/system/sphSchemes"
    sed -i 's/^endTime .*/endTime 0.005;/; s/^deltaT .*/deltaT 5e-4;/; s/^adjustTimeStep .*/adjustTimeStep no;/; s/^writeInterval .*/writeInterval 0.005;/' \
        "$work/tank/system/controlDict"
    printf 'pressure\n{\n    maxDensityError 1e-9;\n    densityErrorNorm maximum;\n    minIterations 0;\n    maxIterations 2;\n}\n' \
        > "$work/tank/system/sphSolution"
    "$solver" -case "$work/tank" -threads 1 > "$work/log" 2>&1 || fail "$model tank run: $(tail -3 "$work/log")"
    steps=$(grep -c '^Time = ' "$work/log")
    [ "$steps" -ge 10 ] || fail "$model: only $steps steps"
    [ "$(grep -c 'iterations 2 (not converged: maxIterations reached)' "$work/log")" = "$steps" ] \
        || fail "$model: the log does not say that maxIterations was reached on every step: $(grep '^Time' "$work/log" | tail -2)"
    perf="$work/tank/postProcessing/solverPerformance/0/solverPerformance.dat"
    [ -f "$perf" ] || fail "$model: no $perf"
    head -1 "$perf" | grep -q "iterations" || fail "$model: solverPerformance.dat header: $(head -1 "$perf")"
    rows=$(awk '!/^#/ && $2 == 2 && $3 == 0 && $4 > 1e-9 { n++ } END { print n + 0 }' "$perf")
    [ "$rows" = "$steps" ] || fail "$model: solverPerformance.dat has $rows rows with 2 iterations, not converged, error > eta; expected $steps"
    echo "$model: maxIterations reached and reported on all $steps steps"
done
echo "incompressible solvers: OK"
