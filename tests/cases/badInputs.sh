#!/usr/bin/env bash
# The real solver on every row of tests/data/badInputs.table: exit status != 0, the expected
# one-line message on stderr, and no time directory written or touched.
#   badInputs.sh <spindrift> <tutorials dir> <table>
set -uo pipefail
. "$(dirname "$0")/../../etc/RunFunctions" # cloneCase: a tutorial's input, never its results
solver=$1 tutorials=$2 table=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0 count=0
while IFS= read -r line; do
    [[ -z "$line" || "$line" == \#* ]] && continue
    name=${line%% | *}; rest=${line#* | }
    file=${rest%% | *}; rest=${rest#* | }
    find=${rest%% | *}; rest=${rest#* | }
    if [[ "$rest" == "| "* ]]; then replace=""; expected=${rest#| }; else replace=${rest%% | *}; expected=${rest#* | }; fi
    case="$work/$name"
    cloneCase "$tutorials/hydrostaticTank2D" "$case"
    FIND="$find" REPLACE="$replace" python3 - "$case/$file" <<'PY' || { echo "FAIL $name: edit"; failures=$((failures+1)); continue; }
import os, sys
p = sys.argv[1]; s = open(p).read()
find = os.environ["FIND"].replace("\\n", "\n"); rep = os.environ["REPLACE"].replace("\\n", "\n")
if find not in s: sys.exit(1)
open(p, "w").write(s.replace(find, rep, 1))
PY
    mkdir -p "$case/0.5" && echo sentinel > "$case/0.5/fluid.vtp"
    count=$((count+1))
    if "$solver" -case "$case" > "$case/stdout" 2> "$case/stderr"; then
        echo "FAIL $name: exit status 0"; failures=$((failures+1)); continue
    fi
    if ! grep -qE -- "$expected" "$case/stderr"; then
        echo "FAIL $name: message: $(cat "$case/stderr")"; echo "     expected: $expected"; failures=$((failures+1)); continue
    fi
    if [ -d "$case/0" ] || [ "$(cat "$case/0.5/fluid.vtp")" != sentinel ]; then
        echo "FAIL $name: a time directory was written or touched"; failures=$((failures+1)); continue
    fi
    echo "ok   $name: $(head -c 160 "$case/stderr")"
done < "$table"
echo "$((count - failures)) passed, $failures failed"
[ "$failures" -eq 0 ] && [ "$count" -ge 25 ]
