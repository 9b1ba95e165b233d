// Spindrift — system/controlDict time semantics (as OpenFOAM): start/end time, Δt (fixed or
// adjusted by a stability limit and maxCo), and when to write.
//
//   startFrom      startTime | latestTime;      startTime 0;   endTime 0.3;
//   deltaT         1e-4;                         adjustTimeStep yes;  maxCo 0.2;  maxDeltaT 1e-3;
//   writeControl   timeStep | runTime | adjustableRunTime;         writeInterval 0.01;
//   timePrecision  6;   // significant digits of the time directories' names (1 to 17)
//
// adjustableRunTime evens out the steps so that they land exactly on write times (and endTime).
#pragma once

#include "Dictionary.hpp"

#include <limits>
#include <string>

namespace spindrift {

class TimeControl {
public:
    enum class WriteControl { TimeStep, RunTime, AdjustableRunTime };

    explicit TimeControl(const Dictionary& controlDict);

    // Re-reads the entries that may change during a run (endTime, writeInterval, maxCo, ...).
    void read(const Dictionary& controlDict);

    double startTime() const { return startTime_; }
    double endTime() const { return endTime_; }
    bool startFromLatest() const { return startFromLatest_; }
    bool adjustTimeStep() const { return adjustTimeStep_; }
    double maxCo() const { return maxCo_; }
    double initialDeltaT() const { return deltaT_; }
    WriteControl writeControl() const { return writeControl_; }
    double writeInterval() const { return writeInterval_; }
    int timePrecision() const { return timePrecision_; }

    // Sets the time the run starts from (startTime, or the latest time when restarting) and
    // the previous step's Δt (for the growth limit; 0 = the initial deltaT).
    void begin(double time, double previousDeltaT = 0);
    // Recomputes the next write time after the write settings changed during a run.
    void scheduleNextWrite(double time);
    // The step actually taken was shorter (a retried step): limits the next growth.
    void setPreviousDeltaT(double dt) { previousDeltaT_ = dt; }
    double previousDeltaT() const { return previousDeltaT_; }

    // Δt for the next step: 'stableDeltaT' is the stability limit (used when adjustTimeStep),
    // never more than maxDeltaT nor 1.2× the previous step nor 'cap' (a blow-up retry's), then
    // shortened so that even steps land on the next write time (adjustableRunTime) and on
    // endTime. 'capped' (optional) tells whether the cap was below the step otherwise taken.
    double nextDeltaT(double time, double stableDeltaT, double cap = std::numeric_limits<double>::infinity(),
                      bool* capped = nullptr);

    // After a step that ended at 'time' (step count 'step'): is this a write time?
    bool writeDue(double time, long step);
    bool finished(double time) const { return time >= endTime_ - timeTolerance_; }

    // The most steps a run may take (with a fixed deltaT, or at least with maxDeltaT): 10^9, a
    // day of the smallest case at 100 µs a step; more is a step size typed wrong (1e-320).
    static constexpr double maxSteps = 1e9;

private:
    // Refuses a step size that is not a normal number, that is below the resolution of the
    // run's times (t + deltaT == t: the run never ends) or that takes more than maxSteps steps.
    void checkStepCount(const Dictionary& controlDict) const;
    // Refuses write times whose names at timePrecision coincide (each would overwrite the one
    // before: the results lost without a word), naming the timePrecision that separates them.
    void checkWriteTimeNames(const Dictionary& controlDict) const;

    int timePrecision_ = 6;
    double startTime_ = 0, endTime_ = 0, deltaT_ = 0, maxDeltaT_ = 0, maxCo_ = 0.2;
    double writeInterval_ = 0;
    bool startFromLatest_ = false, adjustTimeStep_ = false;
    WriteControl writeControl_ = WriteControl::AdjustableRunTime;
    double previousDeltaT_ = 0;
    double nextWriteTime_ = 0;
    double timeTolerance_ = 1e-12;
};

} // namespace spindrift
