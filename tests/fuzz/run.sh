#!/usr/bin/env bash
# Builds the fuzzers with clang (libFuzzer + AddressSanitizer + UBSan) and runs each for a
# bounded time (or number of executions) on a corpus made of the tutorials' dictionaries:
#   fuzzDictionary  the dictionary parser (any file of a case)
#   fuzzCaseSetUp   constant/fluidProperties and constant/geometry semantics: the particle
#                   estimate, the sampling, the walls' motions (FuzzCaseSetUp.cpp)
#   tests/fuzz/run.sh [seconds=60]        each fuzzer for that long (CI)
#   tests/fuzz/run.sh -runs N             each fuzzer for N executions (a bench run: 1000000)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
limit=(-max_total_time="${1:-60}") what="${1:-60} s"
if [ "${1:-}" = "-runs" ]; then limit=(-runs="$2"); what="$2 executions"; fi
out=${FUZZ_DIR:-$root/build-fuzz}
command -v clang++ > /dev/null || { echo "clang++ is needed (apt-get install clang libclang-rt-14-dev)"; exit 1; }
flags=(-std=c++20 -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined
       -I"$root/libsrc" -I/usr/include/eigen3)
core=("$root/libsrc/Dictionary.cpp" "$root/libsrc/Error.cpp" "$root/libsrc/Log.cpp")
mkdir -p "$out"
clang++ "${flags[@]}" "$here/FuzzDictionary.cpp" "${core[@]}" -o "$out/fuzzDictionary" &
clang++ "${flags[@]}" "$here/FuzzCaseSetUp.cpp" "${core[@]}" "$root/libsrc/Case.cpp" "$root/libsrc/Geometry.cpp" \
    "$root/libsrc/Motion.cpp" -o "$out/fuzzCaseSetUp" &
wait %1 && wait %2

# seed corpora: every dictionary of every tutorial; each tutorial's fluidProperties and
# geometry, separated by a NUL byte
mkdir -p "$out/corpusDictionary" "$out/corpusCaseSetUp"
find "$root/tutorials" -path '*/system/*' -o -path '*/constant/*' | while read -r f; do
    [ -f "$f" ] && cp "$f" "$out/corpusDictionary/$(echo "$f" | md5sum | cut -c1-16)"
done
find "$root/tutorials" -name fluidProperties -path '*/constant/*' | while read -r f; do
    c=$(dirname "$f")
    [ -f "$c/geometry" ] && { cat "$f"; printf '\0'; cat "$c/geometry"; } > "$out/corpusCaseSetUp/$(echo "$c" | md5sum | cut -c1-16)"
done

status=0
for target in Dictionary CaseSetUp; do
    mkdir -p "$out/crashes$target"
    (cd "$out" && ASAN_OPTIONS=detect_leaks=1 "./fuzz$target" "${limit[@]}" -timeout=5 -rss_limit_mb=2048 \
        -artifact_prefix="$out/crashes$target/" -print_final_stats=1 "corpus$target" > "fuzz$target.log" 2>&1) || true
    grep -E "^(#[0-9]+ +DONE|Done|stat::number_of_executed_units|stat::average_exec_per_sec|INFO: seed corpus|==.*ERROR)" \
        "$out/fuzz$target.log" || true
    if ls "$out/crashes$target"/* > /dev/null 2>&1; then
        echo "fuzz$target found a problem: $(ls "$out/crashes$target")"; tail -n 40 "$out/fuzz$target.log"; status=1
        continue
    fi
    cov=$(grep -oE "cov: [0-9]+ ft: [0-9]+" "$out/fuzz$target.log" | tail -n 1)
    runs=$(grep -oE "stat::number_of_executed_units: [0-9]+" "$out/fuzz$target.log" | grep -oE "[0-9]+$" || echo "?")
    if [ "${1:-}" = "-runs" ]; then echo "fuzz$target: no crash, leak or hang in $what ($cov)"
    else echo "fuzz$target: no crash, leak or hang in $what ($runs executions, $cov)"; fi
done
exit $status
