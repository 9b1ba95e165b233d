#include "Motion.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>

namespace spindrift {
namespace {

std::string vectorText(const Vec3& v) {
    std::ostringstream s;
    s << "(" << v[0] << " " << v[1] << " " << v[2] << ")";
    return s.str();
}

Vec3 readVector(const Dictionary& d, const std::string& keyword, int dimension) {
    Vec3 v = d.get<Vec3>(keyword);
    if (!v.allFinite()) throw InputError(d.locationOf(keyword), keyword + " must be finite", keyword);
    if (dimension == 2 && v[2] != 0)
        throw InputError(d.locationOf(keyword), keyword + " must have z = 0 in two dimensions", keyword);
    return v;
}

// A number that must be finite (required when there is no default).
double readFinite(const Dictionary& d, const std::string& keyword, std::optional<double> defaultValue = {}) {
    const double value = defaultValue ? d.getOrDefault<double>(keyword, *defaultValue) : d.get<double>(keyword);
    if (!std::isfinite(value)) throw InputError(d.locationOf(keyword), "motion " + keyword + " must be finite", keyword);
    return value;
}

// A motion starting so long before the run, or oscillating so fast, that the time since its
// start (or its phase) loses its precision in double: its positions would be noise (or NaN).
constexpr double maxPeriods = 1e9;

class LinearMotion final : public Motion {
public:
    LinearMotion(const Dictionary& d, int dimension)
        : velocity_(readVector(d, "velocity", dimension)), start_(readFinite(d, "startTime", 0.0)),
          end_(d.getOrDefault<double>("endTime", 1e300)) {
        if (!(end_ > start_))
            throw InputError(d.locationOf("endTime"), "motion endTime must exceed its startTime", "endTime");
    }
    Vec3 displacement(double t) const override { return velocity_ * Scalar(std::clamp(t, start_, end_) - start_); }
    Vec3 velocity(double t) const override { return t >= start_ && t < end_ ? velocity_ : Vec3::Zero(); }
    Vec3 acceleration(double) const override { return Vec3::Zero(); }
    std::string describe() const override { return "linear, velocity " + vectorText(velocity_); }

private:
    Vec3 velocity_;
    double start_, end_;
};

class OscillatingMotion final : public Motion {
public:
    OscillatingMotion(const Dictionary& d, int dimension, double runStart, double runEnd)
        : amplitude_(readFinite(d, "amplitude")), period_(d.get<double>("period")),
          phase_(readFinite(d, "phase", 0.0)), start_(readFinite(d, "startTime", 0.0)) {
        const Vec3 direction = readVector(d, "direction", dimension);
        if (!(direction.cwiseAbs().maxCoeff() > 0))
            throw InputError(d.locationOf("direction"), "motion direction must not be zero", "direction");
        direction_ = direction.stableNormalized(); // (1e308 1e308 0): its norm overflows, not its direction
        if (!(period_ >= std::numeric_limits<double>::min()) || !std::isfinite(period_)) {
            std::ostringstream s;
            s << "motion period must be a positive normal number (at least " << std::numeric_limits<double>::min()
              << "), not " << period_;
            throw InputError(d.locationOf("period"), s.str(), "period");
        }
        // the phase over the run, from the motion's start: at most maxPeriods periods
        const double span = std::max(runEnd, start_) - start_;
        if (span / period_ > maxPeriods) {
            std::ostringstream s;
            const bool startFar = start_ < runStart - (runEnd - runStart);
            s << std::setprecision(3) << "the oscillation would make ";
            if (std::isfinite(span / period_)) s << span / period_;
            else s << "more than " << std::numeric_limits<double>::max();
            s << " periods from its startTime " << start_ << " to the run's endTime " << runEnd << ", more than "
              << maxPeriods << " (its phase would lose all precision): "
              << (startFar ? "start it nearer the run" : "use a longer period");
            const std::string keyword = startFar ? "startTime" : "period";
            throw InputError(d.locationOf(keyword), s.str(), keyword);
        }
        const double peakAcceleration = std::abs(amplitude_) * omega() * omega();
        if (!std::isfinite(peakAcceleration) || !std::isfinite(double(Scalar(peakAcceleration)))) {
            std::ostringstream s;
            s << "the oscillation's peak acceleration amplitude (2 pi/period)^2 is not a finite number (amplitude "
              << amplitude_ << ", period " << period_ << ")";
            throw InputError(d.locationOf("amplitude"), s.str(), "amplitude");
        }
    }
    Vec3 displacement(double t) const override {
        return t < start_ ? Vec3::Zero() : Vec3(direction_ * Scalar(amplitude_ * (std::sin(arg(t)) - std::sin(phase_))));
    }
    Vec3 velocity(double t) const override {
        return t < start_ ? Vec3::Zero() : Vec3(direction_ * Scalar(amplitude_ * omega() * std::cos(arg(t))));
    }
    Vec3 acceleration(double t) const override {
        return t < start_ ? Vec3::Zero()
                          : Vec3(direction_ * Scalar(-amplitude_ * omega() * omega() * std::sin(arg(t))));
    }
    std::string describe() const override {
        std::ostringstream s;
        s << "oscillating, amplitude " << amplitude_ << " along " << vectorText(direction_) << ", period " << period_;
        return s.str();
    }

private:
    double omega() const { return 2 * std::numbers::pi / period_; }
    double arg(double t) const { return omega() * (t - start_) + phase_; }
    Vec3 direction_;
    double amplitude_, period_, phase_, start_;
};

} // namespace

void Motion::sweptRange(double t0, double t1, Vec3& lo, Vec3& hi) const {
    lo = hi = displacement(t0);
    constexpr int samples = 256;
    for (int k = 1; k <= samples; ++k) {
        const Vec3 d = displacement(t0 + (t1 - t0) * k / samples);
        lo = lo.cwiseMin(d);
        hi = hi.cwiseMax(d);
    }
}

std::unique_ptr<Motion> Motion::read(const Dictionary& d, int dimension, double runStart, double runEnd) {
    const std::string type = d.getWord("type", {"linear", "oscillating"});
    std::unique_ptr<Motion> m;
    if (type == "linear") m = std::make_unique<LinearMotion>(d, dimension);
    else m = std::make_unique<OscillatingMotion>(d, dimension, runStart, runEnd);
    d.checkAllKeywordsUsed();
    // what the run will ask of it: finite, at the start, the end and 256 times between
    constexpr int samples = 256;
    for (int k = 0; k <= samples; ++k) {
        const double t = runStart + (runEnd - runStart) * k / samples;
        if (m->displacement(t).allFinite() && m->velocity(t).allFinite() && m->acceleration(t).allFinite()) continue;
        std::ostringstream s;
        s << std::setprecision(6) << "the " << type << " motion is not finite at time " << t << " (displacement "
          << vectorText(m->displacement(t)) << ", velocity " << vectorText(m->velocity(t)) << ")";
        throw InputError(d.where(), s.str(), "motion");
    }
    return m;
}

} // namespace spindrift
