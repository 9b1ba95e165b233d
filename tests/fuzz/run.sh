#!/usr/bin/env bash
# Builds the fuzzers with clang (libFuzzer; the core and every plugin instrumented, with
# AddressSanitizer + UBSan: -DSPINDRIFT_FUZZ=ON into build-fuzz/) and runs each for a bounded
# time (or number of executions) on a corpus made of the tutorials' dictionaries:
#   fuzzDictionary  the dictionary parser (any file of a case)
#   fuzzCaseSetUp   constant/fluidProperties and constant/geometry semantics: the particle
#                   estimate, the sampling, the walls' motions (FuzzCaseSetUp.cpp)
#   fuzzSchemes     system/sphSchemes and system/sphSolution semantics: the models named, their
#                   parameters and combinations, run for three steps on a small case with a
#                   moving wall (FuzzSchemes.cpp)
#   tests/fuzz/run.sh [seconds=60]             each fuzzer for that long (CI)
#   tests/fuzz/run.sh -runs N [fuzzer...]      N executions each (a bench run: 1000000)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
limit=(-max_total_time="${1:-60}") what="${1:-60} s"
targets=(Dictionary CaseSetUp Schemes)
if [ "${1:-}" = "-runs" ]; then
    limit=(-runs="$2"); what="$2 executions"; shift 2
    [ $# -gt 0 ] && targets=("$@")
fi
out=${FUZZ_DIR:-$root/build-fuzz}
command -v clang++ > /dev/null || { echo "clang++ is needed (apt-get install clang libclang-rt-14-dev)"; exit 1; }
if [ ! -f "$out/CMakeCache.txt" ]; then
    mkdir -p "$out" # its configure log inside it, not beside it in the source tree
    CXX=clang++ cmake -S "$root" -B "$out" -DSPINDRIFT_FUZZ=ON -DSPINDRIFT_TESTS=OFF -DSPINDRIFT_OPENMP=OFF \
        -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" > "$out/configure.log" 2>&1 ||
        { cat "$out/configure.log"; exit 1; }
fi
cmake --build "$out" -j "$(nproc)" --target fuzzDictionary fuzzCaseSetUp fuzzSchemes > "$out/build.log" 2>&1 ||
    { tail -n 50 "$out/build.log"; exit 1; }

# seed corpora from the tutorials: every dictionary; each case's fluidProperties and geometry
# separated by a NUL byte; each case's sphSchemes, then a NUL byte and its sphSolution
corpus() { mkdir -p "$out/corpus$1"; cat > "$out/corpus$1/$(echo "$2" | md5sum | cut -c1-16)"; }
find "$root/tutorials" -path '*/system/*' -o -path '*/constant/*' | while read -r f; do
    [ -f "$f" ] && corpus Dictionary "$f" < "$f"
done
find "$root/tutorials" -name fluidProperties -path '*/constant/*' | while read -r f; do
    c=$(dirname "$f")
    [ -f "$c/geometry" ] && { cat "$f"; printf '\0'; cat "$c/geometry"; } | corpus CaseSetUp "$c"
done
find "$root/tutorials" -name sphSchemes -path '*/system/*' | while read -r f; do
    s=$(dirname "$f")/sphSolution
    { cat "$f"; if [ -f "$s" ]; then printf '\0'; cat "$s"; fi; } | corpus Schemes "$f"
done
# fuzzSchemes' mutations get the words that name models and their keywords: every plugin's name
# and every keyword of the tutorials' sphSchemes and sphSolution
{ ls "$out/lib/spindrift/plugins" | sed -n 's/^libspindrift_[A-Za-z]*_\(.*\)\.so$/\1/p'
  find "$root/tutorials" \( -name sphSchemes -o -name sphSolution \) -exec grep -ohE '^ *[A-Za-z][A-Za-z0-9_]*' {} + | tr -d ' '
} | sort -u | sed 's/.*/"&"/' > "$out/schemes.dict"

status=0
for target in "${targets[@]}"; do
    extra=()
    # the runs' warnings (stderr) are not kept; libFuzzer's own output and a sanitizer's report are
    [ "$target" = Schemes ] && extra=(-dict="$out/schemes.dict" -close_fd_mask=3)
    rm -rf "$out/crashes$target"; mkdir -p "$out/crashes$target"
    (cd "$out" && ASAN_OPTIONS=detect_leaks=1 "./bin/fuzz$target" "${limit[@]}" -timeout=10 -rss_limit_mb=2048 \
        -artifact_prefix="$out/crashes$target/" -print_final_stats=1 ${extra[@]+"${extra[@]}"} "corpus$target" \
        > "fuzz$target.log" 2>&1) || true
    if ls "$out/crashes$target"/* > /dev/null 2>&1; then
        echo "fuzz$target found a problem: $(ls "$out/crashes$target")"; tail -n 40 "$out/fuzz$target.log"; status=1
        continue
    fi
    cov=$(grep -oE "cov: [0-9]+ ft: [0-9]+" "$out/fuzz$target.log" | tail -n 1)
    runs=$(grep -oE "stat::number_of_executed_units: [0-9]+" "$out/fuzz$target.log" | grep -oE "[0-9]+$" || echo "?")
    rate=$(grep -oE "stat::average_exec_per_sec: +[0-9]+" "$out/fuzz$target.log" | grep -oE "[0-9]+$" || echo "?")
    echo "fuzz$target: no crash, leak or hang in $what ($runs executions, $rate/s, $cov)"
done
exit $status
