// The run's log (libsrc/RunLog.hpp): how many step lines a run writes and which steps they are.
#include "Dictionary.hpp"
#include "RunLog.hpp"
#include "TimeControl.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <vector>

using namespace spindrift;

TEST(RunLog, TheAutomaticIntervalKeepsARunToAtMost250StepLinesWithTheSmallestRoundInterval) {
    EXPECT_EQ(automaticLogInterval(1), 1);
    EXPECT_EQ(automaticLogInterval(250), 1);
    EXPECT_EQ(automaticLogInterval(251), 2);
    EXPECT_EQ(automaticLogInterval(10000), 50);
    EXPECT_EQ(automaticLogInterval(12501), 100);
    const std::vector<long> round = {1, 2, 5, 10, 20, 50, 100, 200, 500, 1000, 2000, 5000};
    for (double steps : {3.0, 400.0, 777.0, 2600.0, 99999.0, 1e6}) {
        const long interval = automaticLogInterval(steps);
        EXPECT_LE(steps / double(interval), 250.0) << steps;
        // the next smaller round interval would log more than 250 lines
        for (std::size_t k = 1; k < round.size(); ++k) {
            if (round[k] == interval) {
                EXPECT_GT(steps / double(round[k - 1]), 250.0) << steps;
            }
        }
    }
    // a step that is not finite (a run estimated to take forever) still gives an interval
    EXPECT_GT(automaticLogInterval(std::numeric_limits<double>::infinity()), 0);
}

TEST(RunLog, StepLinesAtTheFirstStepEveryIntervalAfterARetryAtForcedStepsAndAtTheEnd) {
    const Dictionary control = Dictionary::fromString("endTime 1; deltaT 0.01; writeInterval 0.1;", "controlDict");
    const TimeControl time(control);
    RunLog runLog(time, 0.0, 0);
    std::vector<long> logged;
    for (long step = 1; step <= 100; ++step) {
        const double t = 0.01 * double(step);
        if (step == 37) runLog.logNextStep();                  // a blow-up's retry: the next step is shown
        const bool forced = step == 61;                        // not converged, or a signal
        if (runLog.stepLineDue(t, step, 0.01, 30, forced)) logged.push_back(step);
    }
    EXPECT_EQ(logged, (std::vector<long>{1, 30, 37, 60, 61, 90, 100})); // 100: the last
}
