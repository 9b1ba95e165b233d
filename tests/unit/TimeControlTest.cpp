// system/controlDict's time semantics (libsrc/TimeControl.hpp): how the steps land on write times.
#include "Dictionary.hpp"
#include "TimeControl.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace spindrift;

namespace {
// The steps of a run from 'start' to its endTime at a constant stability limit 'stable', and the
// times it wrote at.
struct Steps {
    std::vector<double> dt, writes;
};
Steps run(const char* controlDict, double start, double stable) {
    TimeControl time(Dictionary::fromString(controlDict, "controlDict"));
    time.begin(start, stable);
    Steps steps;
    double t = start;
    for (long step = 1; !time.finished(t) && step < 100000; ++step) {
        const double dt = time.nextDeltaT(t, stable);
        t += dt;
        steps.dt.push_back(dt);
        if (time.writeDue(t, step)) steps.writes.push_back(t);
    }
    return steps;
}
} // namespace

// adjustableRunTime evens out the steps before a write time (OpenFOAM's Time::adjustDeltaT) rather
// than taking a short step to land on it: a run at Δt = 1 ms that is 0.3 ms off the write times'
// grid took a 0.3 ms step before each write, and the step's change rang the iterative pressure
// solvers' pressure (pcisph's still tank at ±65 % of hydrostatic after each write; issue 35)
TEST(TimeControl, AdjustableRunTimeLandsOnEveryWriteTimeWithEvenSteps) {
    const char* control = "endTime 2; deltaT 1e-3; adjustTimeStep yes; maxDeltaT 1e-3; maxCo 0.2; "
                          "writeControl adjustableRunTime; writeInterval 0.5;";
    const Steps s = run(control, 0.0003, 1e-3);
    ASSERT_EQ(s.writes.size(), 4u);
    for (std::size_t k = 0; k < s.writes.size(); ++k) EXPECT_NEAR(s.writes[k], 0.5 * double(k + 1), 1e-12);
    // no step shorter than the limit by more than one part in the steps to the next write (the
    // first interval: 0.4997 s in 500 steps), and none longer
    for (double dt : s.dt) {
        EXPECT_LE(dt, 1e-3 * (1 + 1e-12));
        EXPECT_GE(dt, 1e-3 * (1 - 1.0 / 499));
    }
    EXPECT_EQ(s.dt.size(), 2000u);
}

// The same at a step that divides the interval: every step the limit's, as before.
TEST(TimeControl, AStepThatDividesTheWriteIntervalIsKept) {
    const char* control = "endTime 0.1; deltaT 1e-3; adjustTimeStep yes; maxDeltaT 1e-3; maxCo 0.2; "
                          "writeControl adjustableRunTime; writeInterval 0.01;";
    const Steps s = run(control, 0, 1e-3);
    ASSERT_EQ(s.writes.size(), 10u);
    EXPECT_EQ(s.dt.size(), 100u);
    for (double dt : s.dt) EXPECT_NEAR(dt, 1e-3, 1e-15);
}

// endTime that is not a write time, and a fixed deltaT that does not divide the write interval:
// the steps still land on both, evened out.
TEST(TimeControl, AFixedStepIsEvenedOutToTheWriteTimesAndTheEnd) {
    const char* control = "endTime 0.25; deltaT 0.03; writeControl adjustableRunTime; writeInterval 0.1;";
    const Steps s = run(control, 0, 0.03);
    ASSERT_EQ(s.writes.size(), 2u);
    EXPECT_NEAR(s.writes[0], 0.1, 1e-12);
    EXPECT_NEAR(s.writes[1], 0.2, 1e-12);
    // 0.1 in four steps of 0.025 (not three of 0.03 and one of 0.01), twice; 0.05 in two
    EXPECT_EQ(s.dt.size(), 10u);
    EXPECT_NEAR(*std::min_element(s.dt.begin(), s.dt.end()), 0.025, 1e-12);
    EXPECT_NEAR(*std::max_element(s.dt.begin(), s.dt.end()), 0.025, 1e-12);
}
