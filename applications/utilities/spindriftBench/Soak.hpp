// spindriftBench -soak N — kills and restarts, compared bit for bit (issue 21).
//
// The case (with the -quick and -combination overrides, and `startFrom latestTime`) is run once
// uninterrupted. Then N times: a fresh copy is started, killed with SIGKILL at a random moment
// (from the start to 0.95 of the uninterrupted run's duration, the shortest measured: during
// set-up, a step, a write), restarted and run to the end. Each end state must equal the uninterrupted run's byte
// for byte: the same time names, the newest time's fluid.vtp and uniform/time, the .pvd. A run
// that differs is kept as <output>/soak/failed-<k>. Prints "soak: K/N bit-identical"; exit
// status 0 when K = N.
//
//   spindriftBench -case tutorials/hydrostaticTank2D -soak 200 -combination "endTime=0.1 writeInterval=0.01"
#pragma once

#include "BenchSupport.hpp"

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace spindrift::bench {

struct SoakSettings {
    int count = 200;
    std::uint64_t seed = 1;
    std::filesystem::path caseDir, output, solver;
    Combination overrides;               // applied to every copy (quick ones first)
    const Dictionary* presets = nullptr; // benchDict presets
    std::vector<std::string> env;        // the solver's extra environment
    int threads = 1;
};

// Returns the exit status (0: every restart bit-identical).
int runSoak(const SoakSettings& settings);

} // namespace spindrift::bench
