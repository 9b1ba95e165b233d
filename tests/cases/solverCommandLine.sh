#!/usr/bin/env bash
# The solver's command line: -help, -version, -listModels [kind], -dryRun, OpenFOAM spellings
# (-case) with the GNU ones (--case, --case=DIR) as aliases, bad arguments (exit status 1, the
# message on stderr, "did you mean" for a misspelt option).
#   solverCommandLine.sh <spindrift> <tutorials dir>
set -euo pipefail
. "$(dirname "$0")/../../etc/RunFunctions" # cloneCase: a tutorial's input, never its results
solver=$1 tutorials=$2
fail() { echo "FAIL: $*"; exit 1; }

help=$("$solver" -help)
echo "$help"
grep -q -- "^  -case <dir> " <<< "$help" || fail "-help does not describe -case <dir>"
if grep -q -- "^  --" <<< "$help"; then fail "-help describes GNU-style --options"; fi
for o in dryRun force threads postProcess func time listModels version help; do
    grep -q -- "^  -$o\b" <<< "$help" || fail "-help does not describe -$o"
done
[ "$("$solver" --help)" = "$help" ] || fail "--help differs from -help"
# every model kind -listModels knows is named in -help
kinds=$("$solver" -listModels | grep -B1 '^($' | grep -v '^(' | grep -v '^--')
[ "$(wc -w <<< "$kinds")" -ge 7 ] || fail "-listModels lists fewer than 7 kinds: $kinds"
for k in $kinds; do grep -qw "$k" <<< "$help" || fail "-help does not name the model kind $k"; done

version=$("$solver" -version)
echo "$version"
projectVersion=$(sed -n 's/^project(Spindrift VERSION \([0-9.]*\).*/\1/p' "$tutorials/../CMakeLists.txt")
grep -q "^spindrift $projectVersion\b" <<< "$version" || fail "-version does not start with 'spindrift $projectVersion'"
if git -C "$tutorials/.." rev-parse --show-toplevel > /dev/null 2>&1; then
    grep -q "^spindrift $projectVersion (git [0-9a-zA-Z.-]*)$" <<< "$version" || fail "-version lacks the git describe"
fi
grep -Eq "^Precision *: (double|float)$" <<< "$version" || fail "-version lacks the precision"
grep -Eq "^Build type *: [A-Za-z]+" <<< "$version" || fail "-version lacks the build type"
grep -Eq "^Flags *: .*-O" <<< "$version" || fail "-version lacks the compiler flags"
grep -Eq "^OpenMP *: (on|off)" <<< "$version" || fail "-version lacks OpenMP on/off"
grep -Eq "^Sanitizers *: " <<< "$version" || fail "-version lacks the sanitizers"

# bad command lines: status 1, nothing on stdout, the message on stderr
expectError() { # expectError <stderr pattern> <arguments...>
    local pattern=$1 status=0; shift
    "$solver" "$@" > "$work/out" 2> "$work/err" || status=$?
    [ $status -eq 1 ] || fail "'spindrift $*': exit status $status, not 1"
    [ ! -s "$work/out" ] || fail "'spindrift $*' wrote to stdout: $(cat "$work/out")"
    grep -q -- "$pattern" "$work/err" || fail "'spindrift $*': stderr '$(cat "$work/err")' lacks '$pattern'"
    echo "ok 'spindrift $*': $(head -n 1 "$work/err")"
}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
expectError "unknown option '-dryrun'; did you mean '-dryRun'?" -dryrun
expectError "unknown option '--dryRn'; did you mean '-dryRun'?" --dryRn
expectError "did you mean '-listModels'?" -listModles kernel
expectError "did you mean '-case'?" -csae .
expectError "did you mean '-version'?" -verison
expectError "unknown option '-frobnicate'" -frobnicate
if grep -q "did you mean" "$work/err"; then fail "a suggestion for an option nothing is close to"; fi
expectError "-case" -case
expectError "-threads" -threads many
# more threads than cores: refused with a message (100000 crashed in set-up, 2000 died in libgomp)
cores=$(env -u OMP_NUM_THREADS -u OMP_THREAD_LIMIT nproc) # the CPUs of its affinity mask
expectError "spindrift: error: -threads 100000: this process may use $cores core" -threads 100000
expectError "use -threads $cores or fewer" -threads $((cores + 1))
expectError "unexpected argument" some/case

models=$("$solver" -listModels)
for m in cubicSpline wendlandC2 wcsph artificial laminar symplecticEuler leapfrog akinci; do
    grep -qw "$m" <<< "$models" || fail "-listModels does not list $m"
done
"$solver" -listModels kernel | grep -qw cubicSpline || fail "-listModels kernel"
if "$solver" -listModels kernel | grep -qw wcsph; then fail "-listModels kernel lists a pressure model"; fi
if "$solver" -listModels nonsense 2>/dev/null; then fail "-listModels with an unknown kind must fail"; fi

cloneCase "$tutorials/damBreak2D" "$work/case"
out=$("$solver" -case "$work/case" -dryRun -threads 1)
echo "$out"
grep -q "3200 fluid" <<< "$out" || fail "-dryRun does not report the 3200 fluid particles"
grep -q "pressure wcsph" <<< "$out" || fail "-dryRun does not report the schemes"
grep -q "libspindrift_kernel_cubicSpline.so" <<< "$out" || fail "-dryRun does not list the loaded plugins"
if grep -q "wendlandC2" <<< "$out"; then fail "-dryRun opened a plugin the case does not name"; fi
[ -f "$work/case/0/fluid.vtp" ] || fail "-dryRun did not write 0/"
[ ! -d "$work/case/0.01" ] || fail "-dryRun ran time steps"
# OMP_NUM_THREADS beyond the cores: capped, with a warning
out=$(OMP_NUM_THREADS=100000 "$solver" -case "$work/case" -dryRun)
grep -q "^--> Warning: OMP_NUM_THREADS asks for 100000 threads; this process may use $cores core" <<< "$out" \
    || fail "no warning for OMP_NUM_THREADS=100000: $(grep -i thread <<< "$out")"
grep -q "^Threads   : $cores (OpenMP wait: " <<< "$out" || fail "OMP_NUM_THREADS=100000 not capped: $(grep Threads <<< "$out")"
rm -rf "$work/case/0"
# the OpenMP wait: bounded by default (the runtime, OMP_DISPLAY_ENV, says what it runs with), the
# user's choice kept; a run on one thread (OMP_NUM_THREADS=1, as here) is left alone
if "$solver" -version | grep -q "^OpenMP *: on" && [ "$cores" -gt 1 ]; then
    unset OMP_NUM_THREADS
    [ "$(env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT bash -c 'OMP_DISPLAY_ENV=verbose "$1" -version 2>&1 >/dev/null' _ "$solver" \
         | grep "GOMP_SPINCOUNT =" | tail -n 1)" = "  GOMP_SPINCOUNT = '1000'" ] || fail "the default wait is not GOMP_SPINCOUNT 1000"
    env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT "$solver" -version | grep -q "wait: GOMP_SPINCOUNT 1000 (spindrift's default)" \
        || fail "-version does not name the default wait"
    [ "$(OMP_WAIT_POLICY=active OMP_DISPLAY_ENV=verbose "$solver" -version 2>&1 >/dev/null | grep -c "GOMP_SPINCOUNT = '1000'")" = 0 ] \
        || fail "OMP_WAIT_POLICY=active was overridden"
    OMP_WAIT_POLICY=active "$solver" -version | grep -q "wait: OMP_WAIT_POLICY active (environment)" \
        || fail "-version does not name the user's OMP_WAIT_POLICY"
    GOMP_SPINCOUNT=500 "$solver" -version | grep -q "wait: GOMP_SPINCOUNT 500 (environment)" || fail "GOMP_SPINCOUNT=500 not kept"
    for one in "env OMP_NUM_THREADS=1 $solver -version" "$solver -threads 1 -version"; do
        [ "$(env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT OMP_DISPLAY_ENV=verbose $one 2>&1 >/dev/null | grep -c "GOMP_SPINCOUNT =")" = 1 ] \
            || fail "'$one' started itself again (one thread never waits)"
    done
    export OMP_NUM_THREADS=1
    echo "ok OpenMP wait: GOMP_SPINCOUNT 1000 by default, OMP_WAIT_POLICY / GOMP_SPINCOUNT of the user kept"
fi
# the GNU spellings still work
rm -rf "$work/case/0"
"$solver" --case "$work/case" --dryRun --threads 1 > /dev/null || fail "--case DIR --dryRun"
[ -f "$work/case/0/fluid.vtp" ] || fail "--case DIR --dryRun did not write 0/"
rm -rf "$work/case/0"
"$solver" --case="$work/case" --dryRun > /dev/null || fail "--case=DIR --dryRun"
[ -f "$work/case/0/fluid.vtp" ] || fail "--case=DIR --dryRun did not write 0/"

if "$solver" -case "$work/doesNotExist" 2> "$work/err"; then fail "a missing case must fail"; fi
grep -q "does not exist" "$work/err" || fail "missing case message: $(cat "$work/err")"

sed -i 's/type        wcsph;/type        wcsp;/' "$work/case/system/sphSchemes"
if "$solver" -case "$work/case" 2> "$work/err"; then fail "an unknown pressure type must fail"; fi
grep -q "Unknown pressure type 'wcsp'. Valid pressure types are: (.*wcsph.*)" "$work/err" \
    || fail "unknown type message: $(cat "$work/err")"
grep -q "sphSchemes:[0-9]*:[0-9]*" "$work/err" || fail "the message names file:line:column: $(cat "$work/err")"
# -force: past the memory estimate (refused without it), not past the particle index's range
cloneCase "$tutorials/hydrostaticTank2D" "$work/huge"
sed -i -E "s/^particleSpacing .*/particleSpacing 2e-6;/" "$work/huge/constant/fluidProperties"
if "$solver" -case "$work/huge" > /dev/null 2> "$work/err"; then fail "a case of 1.5e10 particles ran"; fi
grep -q "needing about .* GiB (.* B a fluid particle with these models, .* B a wall particle); there is .* GiB .*(or -force)" "$work/err" \
    || fail "memory estimate: $(cat "$work/err")"
if "$solver" -case "$work/huge" -force > "$work/log" 2> "$work/err"; then fail "-force ran 1.5e10 particles"; fi
grep -q "running anyway (-force)" "$work/log" || fail "-force: no warning: $(cat "$work/log")"
grep -q "more than the 4294967295 a particle index can number" "$work/err" || fail "-force: $(cat "$work/err")"
if ls "$work/huge" | grep -q '^[0-9]'; then fail "a refused case wrote a time"; fi
echo "solver command line: OK"
