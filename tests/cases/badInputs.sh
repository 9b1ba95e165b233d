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
# The memory a case may take is what `ulimit -v` leaves too (and a cgroup's memory.max: unit-tested
# with a made-up /proc and /sys in CaseSetUpTest), not only /proc/meminfo's: about 1.1 GiB of
# particles is refused under a limit of 800 MB, with the limit named.
case="$work/ulimit"
cloneCase "$tutorials/hydrostaticTank2D" "$case"
sed -i 's/^particleSpacing .*/particleSpacing 0.0002;/' "$case/constant/fluidProperties"
count=$((count+1))
if (ulimit -v 800000; "$solver" -case "$case" > "$case/stdout" 2> "$case/stderr"); then
    echo "FAIL ulimit: exit status 0"; failures=$((failures+1))
elif ! grep -qE "geometry:14:5: error: the geometry makes about 1.52e\+06 particles .* there is [0-9.]+ GiB of address space left under ulimit -v 800000 \(kB\): use a larger particleSpacing" "$case/stderr"; then
    echo "FAIL ulimit: message: $(cat "$case/stderr")"; failures=$((failures+1))
elif [ -d "$case/0" ]; then
    echo "FAIL ulimit: a time directory was written"; failures=$((failures+1))
else
    echo "ok   ulimit: $(head -c 160 "$case/stderr")"
fi
echo "$((count - failures)) passed, $failures failed"
[ "$failures" -eq 0 ] && [ "$count" -ge 25 ]
