#!/usr/bin/env bash
# Seed 002 (Duan, Ren & Li 2019) §6: dam break with ~4500 fluid particles (r = 0.025 m),
# fixed dt = 0.005 s, iterations stopped on the average density error eta = 0.1 % and 0.01 %:
# average iterations of pbf against relaxedPbf (paper: 10.6 vs 6.2 and 29.0 vs 11.7), total
# speed-up (paper: 1.6x and 2.3x), and the effect of the relaxation factor omega from 0 to 0.9
# (paper Table 1: fewer iterations as omega grows, unstable above 0.5).
#
#   pbfConvergence.sh [-quick] [-etas "0.001 0.0001"] [-omegas "0 0.1 ... 0.9"] [-keep]
#
# The case is damBreakPbf3D/ beside this script (4500 fluid + 18612 wall particles, cubic
# spline, XSPH, vorticity confinement); -quick: endTime 0.2 s and omega 0 and 0.5 only, a
# smoke test; the full run stops at 1 s (collapse, impact on the far wall, run-up).
# maxIterations is raised to 200 so that the counts are hardly truncated; the table says how
# many steps still stopped there. Cost: CPU seconds (user + system) of one-thread
# runs ($THREADS).
set -euo pipefail
. "$(dirname "$0")/benchFunctions"

quick=0 keep=0 etas="0.001 0.0001" omegas="0 0.1 0.2 0.3 0.4 0.5 0.6 0.7 0.8 0.9"
while [ $# -gt 0 ]; do
    case $1 in
        -quick) quick=1 omegas="0 0.5" ;;
        -keep) keep=1 ;;
        -etas) etas=$2; shift ;;
        -omegas) omegas=$2; shift ;;
        *) echo "usage: $0 [-quick] [-etas \"0.001 0.0001\"] [-omegas \"0 0.5\"] [-keep]" >&2; exit 2 ;;
    esac
    shift
done

work=$(mktemp -d "${TMPDIR:-/tmp}/pbfConvergence.XXXXXX")
[ $keep = 1 ] && echo "cases kept in $work" || trap 'rm -rf "$work"' EXIT
endTime=1
[ $quick = 1 ] && endTime=0.2

# run <name> <pressure body> <eta>: prints "avgIt maxIt notConverged cpu maxErr%" or "failed <t>"
run() {
    local d="$work/$1"
    cp -r "$benchDir/damBreakPbf3D" "$d"
    rm -rf "$d"/[0-9]* "$d"/postProcessing "$d"/log.*
    setEntry "$d/system/controlDict" endTime $endTime
    setEntry "$d/system/controlDict" writeInterval $endTime
    setPressure "$d" "$2"
    setSolution "$d" "maxDensityError $3; densityErrorNorm average; minIterations 0; maxIterations 200;"
    local out
    out=$(runCase "$d")
    if [ "$out" = failed ]; then
        echo "failed $(grep -o 'time [0-9.e-]*' "$d/log.spindrift" | tail -1 | cut -d' ' -f2)"
        return
    fi
    read -r _ cpu err _ _ <<< "$out"
    echo "$(iterationStats "$d") $cpu $err"
}

echo
echo "pbf against relaxedPbf (dam break, 4500 fluid particles, dt 0.005 s, endTime $endTime s, $THREADS thread(s));"
echo "the middle rows add seed 002's changes to pbf one at a time:"
variants=(
    "pbf|type pbf;"
    "pbf sCorrK 0|type pbf; sCorrK 0;"
    "  + clampDensity|type pbf; sCorrK 0; clampDensity yes;"
    "  + adaptive walls|type relaxedPbf; omega 0; warmStart 0;"
    "  + warmStart 0.5|type relaxedPbf; omega 0;"
    "relaxedPbf|type relaxedPbf;"
)
printf '%-7s %-20s %9s %7s %13s %9s %10s\n' eta model "avg iter" "max it" "not converged" "cpu s" "max err %"
declare -A cpuOf itOf
for eta in $etas; do
    k=0
    for v in "${variants[@]}"; do
        name=${v%%|*} body=${v#*|}
        k=$((k + 1))
        read -r avg max nc cpu err <<< "$(run "variant$k-$eta" "$body" "$eta")"
        if [ "$avg" = failed ]; then
            printf '%-7s %-20s blew up at t = %s\n' "$eta" "$name" "$max"; continue
        fi
        printf '%-7s %-20s %9s %7s %13s %9s %10s\n' "$eta" "$name" "$avg" "$max" "$nc" "$cpu" "$err"
        cpuOf[$k-$eta]=$cpu itOf[$k-$eta]=$avg
    done
done
last=${#variants[@]}
for eta in $etas; do
    for base in 1 2 3; do
        [ -n "${cpuOf[$base-$eta]:-}" ] && [ -n "${cpuOf[$last-$eta]:-}" ] || continue
        v=${variants[$((base - 1))]}
        awk -v eta="$eta" -v name="${v%%|*}" -v ip="${itOf[$base-$eta]}" -v ir="${itOf[$last-$eta]}" \
            -v cp="${cpuOf[$base-$eta]}" -v cr="${cpuOf[$last-$eta]}" 'BEGIN {
            printf "eta %-7s %-20s %6.1f iterations vs relaxedPbf %5.1f: %.2fx fewer, total speed-up %.2fx\n",
                   eta, name, ip, ir, ip / ir, cp / cr }'
    done
done
echo "(paper: pbf 10.6 vs 6.2 and 29.0 vs 11.7 iterations; total speed-up 1.6x and 2.3x for eta 0.1 % / 0.01 %)"

echo
echo "relaxedPbf: effect of omega (paper Table 1, max iterations at 0.01 % / 0.1 %: 47/17 at 0, 17/10 at 0.5, 13/7 at 0.9):"
printf '%-7s' omega
for eta in $etas; do printf ' | eta %-7s %8s %6s %8s %10s' "$eta" "avg it" "max it" "cpu s" "max err %"; done
echo
for omega in $omegas; do
    printf '%-7s' "$omega"
    for eta in $etas; do
        read -r avg max nc cpu err <<< "$(run "omega-$omega-$eta" "type relaxedPbf; omega $omega;" "$eta" 2>/dev/null)"
        if [ "$avg" = failed ]; then
            printf ' | %-11s %-37s' "" "blew up at t = $max"
        else
            printf ' | %-11s %8s %6s %8s %10s' "" "$avg" "$max" "$cpu" "$err"
        fi
    done
    echo
done
