#!/usr/bin/env bash
# spindriftStress -quick with the base models (wendlandC2, wcsph, artificial, symplecticEuler,
# akinci): every test runs and its figures stay within bounds measured for this resolution
# (docs/VALIDATION.md), and the plots are drawn.
#   stressQuick.sh <spindriftStress>
set -euo pipefail
stress=$1
fail() { echo "FAIL: $*"; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$stress" -quick -output "$work/out" -timeout 120
value() { # value <test> <column>
    local csv=$work/out/stress_$1.csv
    local c
    c=$(head -1 "$csv" | tr ',' '\n' | grep -nx "$2" | cut -d: -f1)
    sed -n 2p "$csv" | cut -d, -f"$c"
}
check() { # check <test> <column> <op> <bound>
    local v
    v=$(value "$1" "$2")
    awk -v v="$v" -v b="$4" -v op="$3" 'BEGIN { if (v == "") exit 1; if (op == "<") exit !(v + 0 < b); exit !(v + 0 > b) }' \
        || fail "$1 $2 = '$v', expected $3 $4"
    echo "$1 $2 = $v ($3 $4)"
}
for t in stillWater maxDeltaT jitter impact; do
    [ "$(value $t status)" = ok ] || fail "$t: status $(value $t status): $(sed -n 2p "$work/out/stress_$t.csv")"
    [ "$(head -c 4 "$work/out/stress_$t.png" | tail -c 3)" = PNG ] || fail "no stress_$t.png"
done
check stillWater rhoErrMaxLate_pct "<" 3        # measured 1.2 %
check stillWater maxSpeedLate "<" 0.35          # measured 0.17 m/s (0.12 sqrt(g H)) after 2 s
check stillWater levelDrift_dx "<" 0.5
check stillWater levelDrift_dx ">" -0.5         # measured -0.09 dx
check maxDeltaT courantOnH ">" 0.5              # measured 0.92 h/c0 (adaptive runs use 0.15)
check maxDeltaT courantOnH "<" 4
check jitter minPairEnd_dx ">" 0.7              # measured 0.86: the lattice relaxes, no pairing
check jitter clusterFractionEnd "<" 0.01
check impact kineticEnergyMaxAfterImpact "<" 1.0  # energy never grows (measured 0.95)
check impact rhoErrMax_pct "<" 20               # measured 10 % (water hammer ~ V/c0)
[ "$(value impact escaped)" = no ] || fail "particles escaped the tank"
echo "spindriftStress quick: OK"
