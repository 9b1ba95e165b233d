#include "TimeControl.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace spindrift {

TimeControl::TimeControl(const Dictionary& d) { read(d); }

void TimeControl::read(const Dictionary& d) {
    startFromLatest_ = d.getWordOrDefault("startFrom", {"startTime", "latestTime"}, "startTime") == "latestTime";
    startTime_ = d.getOrDefault<double>("startTime", 0.0);
    endTime_ = d.get<double>("endTime");
    if (!(endTime_ > startTime_)) {
        std::ostringstream s;
        s << "endTime (" << endTime_ << ") must be greater than startTime (" << startTime_ << ")";
        throw InputError(d.locationOf("endTime"), s.str(), "endTime");
    }
    deltaT_ = d.get<double>("deltaT");
    if (!(deltaT_ > 0)) throw InputError(d.locationOf("deltaT"), "deltaT must be positive", "deltaT");
    adjustTimeStep_ = d.getOrDefault<bool>("adjustTimeStep", false);
    maxCo_ = d.getOrDefault<double>("maxCo", 0.2);
    if (!(maxCo_ > 0)) throw InputError(d.locationOf("maxCo"), "maxCo must be positive", "maxCo");
    maxDeltaT_ = d.getOrDefault<double>("maxDeltaT", adjustTimeStep_ ? 1.0 : deltaT_);
    const std::string wc = d.getWordOrDefault("writeControl", {"timeStep", "runTime", "adjustableRunTime"},
                                              "adjustableRunTime");
    writeControl_ = wc == "timeStep" ? WriteControl::TimeStep
                    : wc == "runTime" ? WriteControl::RunTime
                                      : WriteControl::AdjustableRunTime;
    writeInterval_ = d.get<double>("writeInterval");
    if (!(writeInterval_ > 0))
        throw InputError(d.locationOf("writeInterval"), "writeInterval must be positive", "writeInterval");
    if (writeControl_ == WriteControl::TimeStep && writeInterval_ != std::floor(writeInterval_))
        throw InputError(d.locationOf("writeInterval"),
                         "writeInterval must be a whole number of steps with writeControl timeStep", "writeInterval");
    timeTolerance_ = 1e-9 * std::max({std::abs(endTime_), std::abs(startTime_), 1e-3});
}

void TimeControl::begin(double time, double previousDeltaT) {
    previousDeltaT_ = previousDeltaT > 0 ? previousDeltaT : deltaT_;
    scheduleNextWrite(time);
}

void TimeControl::scheduleNextWrite(double time) {
    if (writeControl_ != WriteControl::TimeStep) {
        // next multiple of writeInterval after 'time'
        const double k = std::floor((time - startTime_) / writeInterval_ + 1e-9) + 1;
        nextWriteTime_ = startTime_ + k * writeInterval_;
    }
}

double TimeControl::nextDeltaT(double time, double stableDeltaT) {
    double dt = deltaT_;
    if (adjustTimeStep_) {
        dt = std::min({stableDeltaT, maxDeltaT_, 1.2 * previousDeltaT_});
        if (!(dt > 0)) dt = previousDeltaT_;
    }
    auto landOn = [&](double target) {
        const double remaining = target - time;
        if (remaining <= timeTolerance_) return;
        if (dt >= remaining - timeTolerance_) dt = remaining;
        else if (dt > 0.5 * remaining) dt = 0.5 * remaining; // two even steps, not a sliver
    };
    if (writeControl_ == WriteControl::AdjustableRunTime) landOn(nextWriteTime_);
    landOn(endTime_);
    previousDeltaT_ = adjustTimeStep_ ? dt : previousDeltaT_;
    return dt;
}

bool TimeControl::writeDue(double time, long step) {
    if (writeControl_ == WriteControl::TimeStep) return step % long(writeInterval_) == 0;
    if (time >= nextWriteTime_ - timeTolerance_) {
        scheduleNextWrite(time); // a function of the time only, so a restart continues identically
        return true;
    }
    return false;
}

} // namespace spindrift
