#!/usr/bin/env bash
# A tutorial as a user runs it (its input cloned, the solver run), then its own check script run
# in the case: ParaView opens every time with a block per particle system (pvpython_check.py),
# and <script> (the tutorial's, run with pvpython) asserts the case's physics.
#   tutorialScript.sh <spindrift> <tutorial dir> <pvpython> <edits> <script> [script arguments...]
# <edits>: ','-separated 'file:keyword=value' set in the clone first (a top-level keyword or any
# line starting with the keyword: a quick mode), '' for the tutorial as shipped.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
. "$here/../../etc/RunFunctions"
solver=$1 tutorial=$2 pvpython=$3 edits=$4 script=$5
shift 5
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
case=$work/$(basename "$tutorial")
cloneCase "$tutorial" "$case"
cp "$tutorial/$script" "$case/"
IFS=',' read -ra list <<< "$edits"
for edit in "${list[@]}"; do
    [ -n "$edit" ] || continue
    file=${edit%%:*} setting=${edit#*:}
    keyword=${setting%%=*} value=${setting#*=}
    before=$(cat "$case/$file")
    sed -i -E "s|^( *)$keyword( +)[^;]*;|\\1$keyword\\2$value;|" "$case/$file"
    [ "$before" != "$(cat "$case/$file")" ] || { echo "edit '$edit' changed nothing"; exit 1; }
done
cd "$case"
"$solver" -case . > log.spindrift 2>&1 || { tail -n 20 log.spindrift; exit 1; }
grep '^End' log.spindrift
grep -i 'moves:' log.spindrift || true
times=$(find . -maxdepth 2 -name fluid.vtp | wc -l)
first=$(dirname "$(find . -maxdepth 2 -name fluid.vtp | sort -t/ -k2 -g | head -1)")
systems=$(find "$first" -maxdepth 1 -name '*.vtp' | wc -l)
"$pvpython" "$here/pvpython_check.py" --blocks "$systems" "$(basename "$case").pvd" "$times" velocity pressure density id
"$pvpython" "$script" "$@"
