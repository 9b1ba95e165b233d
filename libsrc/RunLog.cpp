#include "RunLog.hpp"

#include "CaseWriter.hpp"
#include "Log.hpp"
#include "Parallel.hpp"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <iomanip>
#include <limits>
#include <sstream>

namespace spindrift {

DensityError densityError(const Scene& s) {
    DensityError e;
    std::size_t count = 0;
    e.min = std::numeric_limits<double>::infinity();
    e.max = -e.min;
    for (const ParticleSystem* f : s.ofRole(SystemRole::fluid)) {
        const auto& rho = f->particles.density();
        const double rho0 = f->rho0;
        const std::size_t n = f->ownedSize();
        e.min = std::min(e.min, parallelMin(n, [&](std::size_t i) { return (rho[i] - rho0) / rho0; }));
        e.max = std::max(e.max, parallelMax(n, [&](std::size_t i) { return (rho[i] - rho0) / rho0; }));
        e.avg += deterministicSum(n, [&](std::size_t i) { return (rho[i] - rho0) / rho0; });
        count += n;
    }
    if (count == 0) return {};
    e.avg /= double(count);
    return e;
}

std::string formatDuration(double s) {
    std::ostringstream o;
    if (s < 60) o << std::fixed << std::setprecision(1) << s << " s";
    else if (s < 3600) o << int(s / 60) << " min " << int(s) % 60 << " s";
    else o << int(s / 3600) << " h " << int(s / 60) % 60 << " min";
    return o.str();
}

long automaticLogInterval(double estimatedSteps) {
    constexpr double lines = 250;
    estimatedSteps = std::min(estimatedSteps, 1e15); // also for a step size that is not finite
    for (long decade = 1;; decade *= 10)
        for (long mantissa : {1, 2, 5})
            if (double(mantissa * decade) * lines >= estimatedSteps) return mantissa * decade;
}

std::string localTime(const char* format) {
    const std::time_t now = std::time(nullptr);
    std::tm local{};
    localtime_r(&now, &local);
    char text[64];
    return std::strftime(text, sizeof text, format, &local) ? text : "";
}

RunLog::RunLog(const TimeControl& time, double startTime, long startStep)
    : time_(time), startTime_(startTime), startStep_(startStep) {}

double RunLog::wallSeconds() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

std::string RunLog::eta(double time) const {
    const double done = (time - startTime_) / (time_.endTime() - startTime_);
    return formatDuration(wallSeconds() * (1 - done) / std::max(done, 1e-9));
}

void RunLog::wrote(double time, long step) const {
    std::ostringstream o;
    o << "Wrote time " << CaseWriter::timeName(time) << " (step " << step << ") at " << localTime() << ", "
      << formatDuration(wallSeconds()) << " wall";
    if (time > startTime_ && !time_.finished(time)) o << ", ETA " << eta(time);
    log::info(o.str());
}

bool RunLog::stepLineDue(double time, long step, double dt, long logInterval, bool mustLog) {
    typicalDeltaT_ = typicalDeltaT_ > 0 ? 0.9 * typicalDeltaT_ + 0.1 * dt : dt;
    const double estimatedSteps = double(step - startStep_) + (time_.endTime() - time) / std::max(dt, typicalDeltaT_);
    const long interval = logInterval > 0 ? logInterval : automaticLogInterval(estimatedSteps);
    const bool due = logNext_ || step % interval == 0 || time_.finished(time) || mustLog;
    if (due) logNext_ = false;
    return due;
}

void RunLog::stepLine(double time, long step, double dt, double maxSpeed, const DensityError& err,
                      const SolverStats* solver) const {
    std::ostringstream line;
    line << "Time = " << std::setprecision(6) << time << "  step " << step << "  deltaT " << std::setprecision(3) << dt
         << "  maxU " << maxSpeed << "  rhoErr min " << 100 * err.min << "% max " << 100 * err.max << "% avg "
         << 100 * err.avg << "%";
    if (solver)
        line << "  iterations " << solver->iterations
             << (solver->converged ? "" : " (not converged: maxIterations reached)");
    log::info(line.str());
}

void RunLog::progress(double time, long step) const {
    if (!log::stdoutIsTerminal()) return;
    std::ostringstream p;
    const double endTime = time_.endTime();
    p << "[" << std::fixed << std::setprecision(1) << 100 * (time - startTime_) / (endTime - startTime_)
      << "%] t = " << std::setprecision(4) << time << " / " << endTime << "  step " << step << "  ETA " << eta(time);
    log::progress(p.str());
}

} // namespace spindrift
