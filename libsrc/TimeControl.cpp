#include "TimeControl.hpp"

#include "CaseWriter.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <vector>

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
    if (!(maxDeltaT_ > 0)) throw InputError(d.locationOf("maxDeltaT"), "maxDeltaT must be positive", "maxDeltaT");
    // a name of 0 digits (or fewer) has no meaning; beyond 17 a double has no more digits
    timePrecision_ = d.getOrDefault<int>("timePrecision", 6);
    if (timePrecision_ < 1 || timePrecision_ > 17)
        throw InputError(d.locationOf("timePrecision"),
                         "timePrecision must be between 1 and 17 (significant digits of the time names), not " +
                             std::to_string(timePrecision_),
                         "timePrecision");
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
    checkStepCount(d);
    checkWriteTimeNames(d);
}

void TimeControl::checkStepCount(const Dictionary& d) const {
    const auto text = [](double x) {
        std::ostringstream s;
        s << std::setprecision(6) << x;
        return s.str();
    };
    // a denormal step (deltaT 1e-320) is no step size: 1.5/1e-320 overflows, and it vanishes
    // when added to any time but 0
    if (!std::isnormal(deltaT_))
        throw InputError(d.locationOf("deltaT"),
                         "deltaT " + text(deltaT_) + " is not a usable step size (a normal positive number, at least " +
                             text(std::numeric_limits<double>::min()) + ")",
                         "deltaT");
    // the step that bounds the count: deltaT when fixed, maxDeltaT (the largest a step may be)
    // when adjusted
    const std::string keyword = adjustTimeStep_ ? "maxDeltaT" : "deltaT";
    const double step = adjustTimeStep_ ? maxDeltaT_ : deltaT_;
    // (maxDeltaT left at its default of 1 s: the run itself is too long)
    const std::string at = d.found(keyword) ? keyword : "endTime";
    const auto where = [&] { return d.locationOf(at); };
    // the time the run ends at is the largest it adds a step to: a step below its resolution
    // leaves the time where it is, and the run never ends
    const double largest = std::max(std::abs(startTime_), std::abs(endTime_));
    if (largest + step == largest)
        throw InputError(where(),
                         keyword + " " + text(step) + " is below the resolution of the time " +
                             text(largest) + " in double precision (about " +
                             text(std::nextafter(largest, std::numeric_limits<double>::infinity()) - largest) +
                             "): the time would not advance and the run would never end",
                         at);
    const double steps = (endTime_ - startTime_) / step;
    if (!(steps <= maxSteps))
        throw InputError(where(),
                         "the run from startTime " + text(startTime_) + " to endTime " + text(endTime_) + " at " +
                             keyword + " " + text(step) + " takes " + (adjustTimeStep_ ? "at least " : "") +
                             text(steps) + " steps, more than the " + text(maxSteps) +
                             " a run may take; use a larger " + keyword + " or a shorter run",
                         at);
}

namespace {
// The first pair of consecutive scheduled times with the same name at 'precision' (false: none).
// The times a run writes: startTime, startTime + k·spacing, and endTime; names are monotonic in
// the time, so a collision is between neighbours. Of a long schedule only the first and the
// last 5·10^4 are looked at: the names of largest magnitude are at one of its ends, and a
// spacing shorter than their last digit collides among them.
bool collision(double start, double end, double spacing, int precision, double& a, double& b) {
    const long long count = (long long)std::min(std::floor((end - start) / spacing + 1e-9), 1e18), half = 50000;
    const auto check = [&](long long k0, long long k1, bool withEnd) {
        std::string previous;
        double previousTime = 0;
        for (long long k = k0; k <= k1 + (withEnd ? 1 : 0); ++k) {
            const double t = k <= k1 ? start + double(k) * spacing : end;
            if (k > k1 && end - previousTime <= 1e-9 * spacing) break; // endTime on the schedule
            std::string name = CaseWriter::timeName(t, precision);
            if (k > k0 && name == previous) {
                a = previousTime;
                b = t;
                return true;
            }
            previous = std::move(name);
            previousTime = t;
        }
        return false;
    };
    if (count <= 2 * half) return check(0, count, true);
    return check(0, half, false) || check(count - half, count, true);
}
} // namespace

void TimeControl::checkWriteTimeNames(const Dictionary& d) const {
    // the spacing of the writes; with timeStep control and a Δt that adjusts it is not known
    // before the run (the writer refuses a second time of an existing name then)
    double spacing = writeInterval_;
    if (writeControl_ == WriteControl::TimeStep) {
        if (adjustTimeStep_) return;
        spacing = writeInterval_ * deltaT_;
    }
    double a = 0, b = 0;
    if (!collision(startTime_, endTime_, spacing, timePrecision_, a, b)) return;
    int needed = timePrecision_ + 1;
    double a2 = 0, b2 = 0;
    while (needed <= 17 && collision(startTime_, endTime_, spacing, needed, a2, b2)) ++needed;
    std::ostringstream s;
    s << std::setprecision(std::min(timePrecision_ + 6, 17)) << "the write times " << a << " and " << b << " would both be written as '"
      << CaseWriter::timeName(a, timePrecision_) << "' at timePrecision " << timePrecision_ << " (one overwriting the other); ";
    if (needed <= 17) s << "raise timePrecision to " << needed << (d.found("timePrecision") ? "" : " (the default is 6)");
    else s << "writeInterval is too short for times of this size";
    const char* keyword = d.found("timePrecision") ? "timePrecision" : "writeInterval";
    throw InputError(d.locationOf(keyword), s.str(), keyword);
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

double TimeControl::nextDeltaT(double time, double stableDeltaT, double cap, bool* capped) {
    double dt = deltaT_;
    if (adjustTimeStep_) {
        dt = std::min({stableDeltaT, maxDeltaT_, 1.2 * previousDeltaT_});
        if (!(dt > 0)) dt = previousDeltaT_;
    }
    if (capped) *capped = cap < dt;
    dt = std::min(dt, cap);
    // the steps to the target made even, as OpenFOAM's Time::adjustDeltaT: n = ⌈remaining/Δt⌉ steps
    // of remaining/n. Δt changes by a fraction 1/n where the target is n steps away, not by a
    // short step before it, which kicked the iterative pressure solvers (pcisph's still tank rang
    // at ±65 % of ρ0 g (H − z) after each write, issue 35)
    auto landOn = [&](double target) {
        const double remaining = target - time;
        if (remaining <= timeTolerance_ || !(dt > 0)) return;
        const double steps = std::ceil((remaining - timeTolerance_) / dt);
        if (steps < maxSteps) dt = remaining / std::max(steps, 1.0);
    };
    // the nearer of the two (evening out the steps to the farther would miss the nearer)
    landOn(writeControl_ == WriteControl::AdjustableRunTime ? std::min(nextWriteTime_, endTime_) : endTime_);
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
