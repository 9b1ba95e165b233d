#include "Motion.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
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

class LinearMotion final : public Motion {
public:
    LinearMotion(const Dictionary& d, int dimension)
        : velocity_(readVector(d, "velocity", dimension)), start_(d.getOrDefault<double>("startTime", 0.0)),
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
    OscillatingMotion(const Dictionary& d, int dimension)
        : amplitude_(d.get<double>("amplitude")), period_(d.get<double>("period")),
          phase_(d.getOrDefault<double>("phase", 0.0)), start_(d.getOrDefault<double>("startTime", 0.0)) {
        const Vec3 direction = readVector(d, "direction", dimension);
        if (!(direction.norm() > 0))
            throw InputError(d.locationOf("direction"), "motion direction must not be zero", "direction");
        direction_ = direction.normalized();
        if (!(period_ > 0)) throw InputError(d.locationOf("period"), "motion period must be positive", "period");
        if (!std::isfinite(amplitude_))
            throw InputError(d.locationOf("amplitude"), "motion amplitude must be finite", "amplitude");
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

std::unique_ptr<Motion> Motion::read(const Dictionary& d, int dimension) {
    const std::string type = d.getWord("type", {"linear", "oscillating"});
    std::unique_ptr<Motion> m;
    if (type == "linear") m = std::make_unique<LinearMotion>(d, dimension);
    else m = std::make_unique<OscillatingMotion>(d, dimension);
    d.checkAllKeywordsUsed();
    return m;
}

} // namespace spindrift
