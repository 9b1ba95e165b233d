#!/usr/bin/env bash
# The solver's command line: -help, -listModels [kind], -dryRun, bad arguments.
#   solverCommandLine.sh <spindrift> <tutorials dir>
set -euo pipefail
. "$(dirname "$0")/../../etc/RunFunctions" # cloneCase: a tutorial's input, never its results
solver=$1 tutorials=$2
fail() { echo "FAIL: $*"; exit 1; }

"$solver" -help | grep -q -- "-case" || fail "-help does not describe -case"

models=$("$solver" -listModels)
for m in cubicSpline wendlandC2 wcsph artificial laminar symplecticEuler leapfrog akinci; do
    grep -qw "$m" <<< "$models" || fail "-listModels does not list $m"
done
"$solver" -listModels kernel | grep -qw cubicSpline || fail "-listModels kernel"
if "$solver" -listModels kernel | grep -qw wcsph; then fail "-listModels kernel lists a pressure model"; fi
if "$solver" -listModels nonsense 2>/dev/null; then fail "-listModels with an unknown kind must fail"; fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cloneCase "$tutorials/damBreak2D" "$work/case"
out=$("$solver" -case "$work/case" -dryRun -threads 1)
echo "$out"
grep -q "3200 fluid" <<< "$out" || fail "-dryRun does not report the 3200 fluid particles"
grep -q "pressure wcsph" <<< "$out" || fail "-dryRun does not report the schemes"
grep -q "libspindrift_kernel_cubicSpline.so" <<< "$out" || fail "-dryRun does not list the loaded plugins"
if grep -q "wendlandC2" <<< "$out"; then fail "-dryRun opened a plugin the case does not name"; fi
[ -f "$work/case/0/fluid.vtp" ] || fail "-dryRun did not write 0/"
[ ! -d "$work/case/0.01" ] || fail "-dryRun ran time steps"

if "$solver" -case "$work/doesNotExist" 2> "$work/err"; then fail "a missing case must fail"; fi
grep -q "does not exist" "$work/err" || fail "missing case message: $(cat "$work/err")"

sed -i 's/type        wcsph;/type        wcsp;/' "$work/case/system/sphSchemes"
if "$solver" -case "$work/case" 2> "$work/err"; then fail "an unknown pressure type must fail"; fi
grep -q "Unknown pressure type 'wcsp'. Valid pressure types are: (.*wcsph.*)" "$work/err" \
    || fail "unknown type message: $(cat "$work/err")"
grep -q "sphSchemes:[0-9]*:[0-9]*" "$work/err" || fail "the message names file:line:column: $(cat "$work/err")"
echo "solver command line: OK"
