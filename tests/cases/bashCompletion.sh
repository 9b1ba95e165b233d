#!/usr/bin/env bash
# Bash completion of spindrift (etc/bash-completion/spindrift): the options the solver's -help
# describes, directories after -case, model kinds after -listModels; a fixed list of options
# (each a real one) when the solver cannot be run.
#   bashCompletion.sh <spindrift> <completion file>
set -euo pipefail
solver=$1
. "$2"
fail() { echo "FAIL: $*"; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/caseA/system" "$work/caseB"
touch "$work/caseFile"

complete -p spindrift | grep -q _spindrift || fail "no completion registered for spindrift"
# the completions of the last word of a command line
completions() {
    COMP_WORDS=("$@")
    COMP_CWORD=$(($# - 1))
    COMPREPLY=()
    _spindrift
    printf '%s\n' "${COMPREPLY[@]}" | sort | tr '\n' ' '
}
expect() { # expected words, command line words...
    local want=$1; shift
    local got
    got=$(completions "$@")
    [ "$got" = "$want" ] || fail "'$*<TAB>' gave '$got', not '$want'"
}
helpOptions=$("$solver" -help | sed -n 's/^  -\([A-Za-z][A-Za-z0-9]*\).*/-\1/p' | sort | tr '\n' ' ')
[ "$(wc -w <<< "$helpOptions")" -ge 6 ] || fail "fewer than 6 options in spindrift -help: $helpOptions"
[ -n "$helpOptions" ] || fail "no options in spindrift -help"
expect "$helpOptions" "$solver" ""
expect "-case " "$solver" "-ca"
expect "-dryRun " "$solver" -case "$work/caseA" "-d"
expect "$work/caseA $work/caseB " "$solver" -case "$work/case"
expect "boundary densityDiffusion force functionObject integrator kernel passive pressure shifting surfaceTension viscosity " "$solver" -listModels ""
expect "boundary densityDiffusion force functionObject integrator kernel passive pressure shifting surfaceTension viscosity " "$work/noSolver" -listModels ""
expect "pressure " "$solver" -listModels "pr"
expect "$(seq 1 "$(nproc)" | sort | tr '\n' ' ')" "$solver" -threads ""
# the solver cannot be run: the fixed list, whose every option the solver has
fallback=$(completions "$work/noSolver" "-")
[ -n "$fallback" ] || fail "no options without a runnable solver"
for o in $fallback; do
    grep -qw -- "$o" <<< "$helpOptions" || fail "the fixed list offers $o, which spindrift -help does not describe"
done
echo "bash completion: OK"
