#!/usr/bin/env bash
# A tutorial as a user runs it (its input cloned, the solver run), then its physics checked on
# the times it wrote: ParaView opens every time with a block per particle system
# (pvpython_check.py), and tutorialPhysics.py checks hydrostatic start, density, walls, front,
# energy, volume as asked.
#   tutorialPhysics.sh <spindrift> <tutorial dir> <pvpython> <edits> [checks...]
# <edits>: ','-separated 'file:keyword=value' set in the clone first (a quick mode: a shorter
# endTime, a coarser spacing, another pressure solver), '' for the tutorial as shipped;
# 'file:block.keyword=value' sets the keyword of a named block (an indented entry).
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
    if [[ $keyword == *.* ]]; then
        # block.keyword: the first indented 'keyword' line after the line naming the block alone
        # (constant/geometry:box.min=(0.4 0.36 0) moves the body 'box')
        awk -v block="${keyword%.*}" -v key="${keyword##*.}" -v value="$value" '
            !done && $0 ~ "^[ \t]*" block "[ \t]*$" { inside = 1 }
            !done && inside && $1 == key { match($0, "^[ \t]*" key "[ \t]+"); $0 = substr($0, 1, RLENGTH) value ";"; done = 1 }
            { print }' "$case/$file" > "$case/$file.edited"
        mv "$case/$file.edited" "$case/$file"
    else
        sed -i -E "s|^$keyword( +).*|$keyword\\1$value;|" "$case/$file"
    fi
    [ "$before" != "$(cat "$case/$file")" ] || { echo "edit '$edit' changed nothing"; exit 1; }
done
cd "$case"
"$solver" -case . > log.spindrift 2>&1 || { tail -n 20 log.spindrift; exit 1; }
grep '^End' log.spindrift
# ParaView opens every written time with a block per particle system: the fluid and each wall
times=$(find . -maxdepth 2 -name fluid.vtp | wc -l)
first=$(dirname "$(find . -maxdepth 2 -name fluid.vtp | sort -t/ -k2 -g | head -1)")
systems=$(find "$first" -maxdepth 1 -name '*.vtp' | wc -l)
# a block without points at the first time (diffuse particles not generated yet) may stay empty
empty=()
for f in $(grep -l 'NumberOfPoints="0"' "$first"/*.vtp 2>/dev/null); do empty+=(--may-be-empty "$(basename "$f" .vtp)"); done
"$pvpython" "$here/pvpython_check.py" --blocks "$systems" "${empty[@]}" "$(basename "$case").pvd" "$times" velocity pressure density id
"$pvpython" "$here/tutorialPhysics.py" . "$@"
# a tutorial's own check, run in the case (e.g. "semiAxes.py . --tolerance 0.01"): $TUTORIAL_CHECK
if [ -n "${TUTORIAL_CHECK:-}" ]; then
    # shellcheck disable=SC2086 # (the script and its arguments)
    "$pvpython" $TUTORIAL_CHECK
fi
