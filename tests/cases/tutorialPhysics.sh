#!/usr/bin/env bash
# A tutorial as a user runs it (its input cloned, the solver run), then its physics checked on
# the times it wrote (tutorialPhysics.py: hydrostatic start, density, walls, front, energy).
#   tutorialPhysics.sh <spindrift> <tutorial dir> <pvpython> <edits> [checks...]
# <edits>: ','-separated 'file:keyword=value' set in the clone first (a quick mode: a shorter
# endTime, a coarser spacing, another pressure solver), '' for the tutorial as shipped.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
. "$here/../../etc/RunFunctions"
solver=$1 tutorial=$2 pvpython=$3 edits=$4
shift 4
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
case=$work/$(basename "$tutorial")
cloneCase "$tutorial" "$case"
IFS=',' read -ra list <<< "$edits"
for edit in "${list[@]}"; do
    [ -n "$edit" ] || continue
    file=${edit%%:*} setting=${edit#*:}
    keyword=${setting%%=*} value=${setting#*=}
    before=$(cat "$case/$file")
    sed -i -E "s|^$keyword( +).*|$keyword\\1$value;|" "$case/$file"
    [ "$before" != "$(cat "$case/$file")" ] || { echo "edit '$edit' changed nothing"; exit 1; }
done
cd "$case"
"$solver" -case . > log.spindrift 2>&1 || { tail -n 20 log.spindrift; exit 1; }
grep '^End' log.spindrift
"$pvpython" "$here/tutorialPhysics.py" . "$@"
