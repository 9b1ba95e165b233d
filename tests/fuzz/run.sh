#!/usr/bin/env bash
# Builds the dictionary-parser fuzzer with clang (libFuzzer + AddressSanitizer + UBSan) and runs
# it for a bounded time on a corpus made of the tutorials' dictionaries.
#   tests/fuzz/run.sh [seconds=60]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
seconds=${1:-60}
out=${FUZZ_DIR:-$root/build-fuzz}
mkdir -p "$out/corpus" "$out/crashes"
command -v clang++ > /dev/null || { echo "clang++ is needed (apt-get install clang libclang-rt-14-dev)"; exit 1; }
clang++ -std=c++20 -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined \
    -I"$root/libsrc" -I/usr/include/eigen3 \
    "$here/FuzzDictionary.cpp" "$root/libsrc/Dictionary.cpp" "$root/libsrc/Error.cpp" "$root/libsrc/Log.cpp" \
    -o "$out/fuzzDictionary"
# seed corpus: every dictionary of every tutorial
find "$root/tutorials" -path '*/system/*' -o -path '*/constant/*' | while read -r f; do
    [ -f "$f" ] && cp "$f" "$out/corpus/$(echo "$f" | md5sum | cut -c1-16)"
done
cd "$out"
ASAN_OPTIONS=detect_leaks=1 ./fuzzDictionary -max_total_time="$seconds" -timeout=5 -rss_limit_mb=2048 \
    -artifact_prefix="$out/crashes/" -print_final_stats=1 corpus 2>&1 | tee fuzz.log | grep -E "^(#[0-9]+ +DONE|Done|stat::number_of_executed_units|stat::average_exec_per_sec|INFO: seed corpus|==.*ERROR)" || true
if ls crashes/* > /dev/null 2>&1; then
    echo "fuzzDictionary found a problem: $(ls crashes)"; tail -n 40 fuzz.log; exit 1
fi
cov=$(grep -oE "cov: [0-9]+ ft: [0-9]+" fuzz.log | tail -n 1)
echo "fuzzDictionary: no crash, leak or hang in ${seconds} s ($cov)"
