// Spindrift — the run's log: a step line every logInterval-th step (automatic: from the number
// of steps the run is estimated to take) and at the steps that matter, a line for each written
// time with the wall time and the ETA, and the progress line on a terminal.
#pragma once

#include "Scene.hpp"
#include "TimeControl.hpp"

#include <chrono>
#include <string>

namespace spindrift {

// The density error e_i = (ρ_i − ρ0)/ρ0, signed (> 0 compressed; a free surface with a summed
// density shows as a negative minimum): its min, max and average over the fluid systems. One
// definition for the step line's "rhoErr min/max/avg" (in %), fieldStats' rhoErrMin/Max/Avg
// columns (in %) and the End line's "max density error" (the largest max of the run).
struct DensityError {
    double min = 0, max = 0, avg = 0;
};
DensityError densityError(const Scene& s);

// "12.3 s", "4 min 5 s", "1 h 2 min".
std::string formatDuration(double seconds);
// The automatic logInterval: every step for a run of up to 250 steps; a longer one gets the
// smallest of 1, 2, 5, 10, 20, 50, ... steps that keeps it to at most 250 step lines (a
// 10,000-step run logs every 50th step: 200 lines).
long automaticLogInterval(double estimatedSteps);
// The local wall-clock time in a strftime format (the default: the time of day, hh:mm:ss).
std::string localTime(const char* format = "%H:%M:%S");

class RunLog {
public:
    // A run from startTime (at step startStep) to time.endTime(), read at each use: a run-time
    // edit of controlDict may change it.
    RunLog(const TimeControl& time, double startTime, long startStep);

    double wallSeconds() const;
    // The wall time still to go, from the simulated time still to go at the pace so far.
    std::string eta(double time) const;

    // "Wrote time <name> (step N) at hh:mm:ss, <wall> wall[, ETA ...]" (no ETA at the start or the end).
    void wrote(double time, long step) const;

    // The step line is due at every logInterval-th step (0: automatic), and always at the first
    // step of the run, the step after logNextStep() (a blow-up's retry), the last step and a step
    // that 'mustLog' (a pressure solver that did not converge, a signal).
    bool stepLineDue(double time, long step, double dt, long logInterval, bool mustLog);
    void logNextStep() { logNext_ = true; }
    // "Time = t  step N  deltaT dt  maxU u  rhoErr min ..% max ..% avg ..%[  iterations k ...]";
    // 'solver' only for an iterative pressure solver.
    void stepLine(double time, long step, double dt, double maxSpeed, const DensityError& error,
                  const SolverStats* solver) const;

    // "[12.3%] t = ... / end  step N  ETA ..." redrawn in place (a terminal only).
    void progress(double time, long step) const;

private:
    using Clock = std::chrono::steady_clock;
    Clock::time_point start_ = Clock::now();
    const TimeControl& time_;
    double startTime_;
    long startStep_;
    double typicalDeltaT_ = 0; // moving average: landing on a write time shortens a step or two
    bool logNext_ = true;
};

} // namespace spindrift
