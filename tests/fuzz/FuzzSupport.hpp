// What the fuzzers share: a broken invariant reported as a crash, and a quiet log.
#pragma once

#include "Log.hpp"

namespace spindrift::fuzz {

// A broken invariant: the fuzzer reports the input that broke it.
inline void check(bool ok) {
    if (!ok) __builtin_trap();
}

// The solver's progress and information lines off (called at the start of every input; acts once).
inline void quietLog() {
    static const bool quiet = (log::setQuiet(true), true);
    (void)quiet;
}

} // namespace spindrift::fuzz
