#include "Motion.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>

namespace spindrift {
namespace {

using V3 = Eigen::Vector3d;
constexpr double pi = std::numbers::pi;
constexpr double degree = pi / 180;

std::string vectorText(const V3& v) {
    std::ostringstream s;
    s << "(" << v[0] << " " << v[1] << " " << v[2] << ")";
    return s.str();
}

V3 readVector(const Dictionary& d, const std::string& keyword, int dimension) {
    Vec3 v = d.get<Vec3>(keyword);
    if (!v.allFinite()) throw InputError(d.locationOf(keyword), keyword + " must be finite", keyword);
    if (dimension == 2 && v[2] != 0)
        throw InputError(d.locationOf(keyword), keyword + " must have z = 0 in two dimensions", keyword);
    return v.cast<double>();
}

// A direction (normalised); must not be zero.
V3 readDirection(const Dictionary& d, const std::string& keyword, int dimension, std::optional<V3> defaultValue = {}) {
    if (defaultValue && !d.found(keyword)) return *defaultValue;
    const V3 v = readVector(d, keyword, dimension);
    if (!(v.cwiseAbs().maxCoeff() > 0))
        throw InputError(d.locationOf(keyword), "motion " + keyword + " must not be zero", keyword);
    return v.stableNormalized(); // (1e308 1e308 0): its norm overflows, not its direction
}

// A rotation axis: any direction in 3D, along z in 2D (default (0 0 1) there).
V3 readAxis(const Dictionary& d, int dimension) {
    if (dimension == 2) {
        if (!d.found("axis")) return V3::UnitZ();
        const Vec3 v = d.get<Vec3>("axis");
        if (!v.allFinite() || v[0] != 0 || v[1] != 0 || v[2] == 0)
            throw InputError(d.locationOf("axis"), "in two dimensions a wall rotates about z: axis must be (0 0 1)",
                             "axis");
        return V3(0, 0, v[2] > 0 ? 1 : -1);
    }
    return readDirection(d, "axis", dimension);
}

// A number that must be finite (required when there is no default).
double readFinite(const Dictionary& d, const std::string& keyword, std::optional<double> defaultValue = {}) {
    const double value = defaultValue ? d.getOrDefault<double>(keyword, *defaultValue) : d.get<double>(keyword);
    if (!std::isfinite(value)) throw InputError(d.locationOf(keyword), "motion " + keyword + " must be finite", keyword);
    return value;
}

double readPositive(const Dictionary& d, const std::string& keyword, std::optional<double> defaultValue = {}) {
    const double value = readFinite(d, keyword, defaultValue);
    if (!(value > 0)) {
        std::ostringstream s;
        s << "motion " << keyword << " must be positive, not " << value;
        throw InputError(d.locationOf(keyword), s.str(), keyword);
    }
    return value;
}

double readNonNegative(const Dictionary& d, const std::string& keyword, double defaultValue) {
    const double value = readFinite(d, keyword, defaultValue);
    if (!(value >= 0)) {
        std::ostringstream s;
        s << "motion " << keyword << " must not be negative, not " << value;
        throw InputError(d.locationOf(keyword), s.str(), keyword);
    }
    return value;
}

// A motion starting so long before the run, or oscillating so fast, that the time since its
// start (or its phase) loses its precision in double: its positions would be noise (or NaN).
constexpr double maxPeriods = 1e9;

// Reads `period` of an oscillation starting at 'start' with 'amplitude' (of 'amplitudeKeyword', in
// the units of the signal) for a run from runStart to runEnd: a positive normal number, at most
// maxPeriods periods over the run, and a finite peak acceleration.
double readPeriod(const Dictionary& d, double start, double amplitude, const std::string& amplitudeKeyword,
                  double runStart, double runEnd) {
    const double period = d.get<double>("period");
    if (!(period >= std::numeric_limits<double>::min()) || !std::isfinite(period)) {
        std::ostringstream s;
        s << "motion period must be a positive normal number (at least " << std::numeric_limits<double>::min()
          << "), not " << period;
        throw InputError(d.locationOf("period"), s.str(), "period");
    }
    const double span = std::max(runEnd, start) - start;
    if (span / period > maxPeriods) {
        std::ostringstream s;
        const bool startFar = start < runStart - (runEnd - runStart);
        s << std::setprecision(3) << "the oscillation would make ";
        if (std::isfinite(span / period)) s << span / period;
        else s << "more than " << std::numeric_limits<double>::max();
        s << " periods from its startTime " << start << " to the run's endTime " << runEnd << ", more than "
          << maxPeriods << " (its phase would lose all precision): "
          << (startFar ? "start it nearer the run" : "use a longer period");
        const std::string keyword = startFar ? "startTime" : "period";
        throw InputError(d.locationOf(keyword), s.str(), keyword);
    }
    const double omega = 2 * pi / period;
    const double peakAcceleration = std::abs(amplitude) * omega * omega;
    if (!std::isfinite(peakAcceleration) || !std::isfinite(double(Scalar(peakAcceleration)))) {
        std::ostringstream s;
        s << "the oscillation's peak acceleration amplitude (2 pi/period)^2 is not a finite number (" << amplitudeKeyword
          << " " << amplitude << ", period " << period << ")";
        throw InputError(d.locationOf(amplitudeKeyword), s.str(), amplitudeKeyword);
    }
    return period;
}

// A scalar signal and its first two time derivatives.
struct Signal {
    double f = 0, df = 0, ddf = 0;
};

// The product of two signals (Leibniz).
Signal operator*(const Signal& a, const Signal& b) {
    return {a.f * b.f, a.df * b.f + a.f * b.df, a.ddf * b.f + 2 * a.df * b.df + a.f * b.ddf};
}

// The ramp from 0 at 'start' to 1 at start + duration: the quintic smoothstep s³(10 − 15 s + 6 s²),
// whose first two derivatives vanish at both ends (1 throughout for a duration of 0).
Signal ramp(double t, double start, double duration) {
    if (t < start) return {0, 0, 0};
    if (!(duration > 0) || t >= start + duration) return {1, 0, 0};
    const double s = (t - start) / duration;
    const double f = s * s * s * (10 + s * (-15 + 6 * s));
    const double df = 30 * s * s * (1 - s) * (1 - s) / duration;
    const double ddf = 60 * s * (1 - s) * (1 - 2 * s) / (duration * duration);
    return {f, df, ddf};
}

// amplitude (sin(ω τ + φ) − sin φ), τ = t − start ≥ 0 (zero before start)
Signal sinusoid(double t, double start, double amplitude, double omega, double phase) {
    if (t < start) return {};
    const double arg = omega * (t - start) + phase;
    return {amplitude * (std::sin(arg) - std::sin(phase)), amplitude * omega * std::cos(arg),
            -amplitude * omega * omega * std::sin(arg)};
}

// ---- translations: d(t) = direction · signal(t) ------------------------------------------------
class Translation : public Motion {
public:
    RigidState state(double t) const override {
        const Signal s = signal(t);
        RigidState r;
        r.translation = direction_ * s.f;
        r.velocity = direction_ * s.df;
        r.acceleration = direction_ * s.ddf;
        return r;
    }

protected:
    virtual Signal signal(double t) const = 0;
    V3 direction_ = V3::UnitX();
};

class LinearMotion final : public Translation {
public:
    LinearMotion(const Dictionary& d, int dimension)
        : velocity_(readVector(d, "velocity", dimension)), start_(readFinite(d, "startTime", 0.0)),
          end_(d.getOrDefault<double>("endTime", 1e300)) {
        if (!(end_ > start_))
            throw InputError(d.locationOf("endTime"), "motion endTime must exceed its startTime", "endTime");
    }
    RigidState state(double t) const override {
        RigidState r;
        r.translation = velocity_ * (std::clamp(t, start_, end_) - start_);
        if (t >= start_ && t < end_) r.velocity = velocity_;
        return r;
    }
    std::string describe() const override { return "linear, velocity " + vectorText(velocity_); }

private:
    Signal signal(double) const override { return {}; }
    V3 velocity_;
    double start_, end_;
};

class OscillatingMotion final : public Translation {
public:
    OscillatingMotion(const Dictionary& d, const MotionContext& c)
        : amplitude_(readFinite(d, "amplitude")), phase_(readFinite(d, "phase", 0.0)),
          start_(readFinite(d, "startTime", 0.0)) {
        direction_ = readDirection(d, "direction", c.dimension);
        period_ = readPeriod(d, start_, amplitude_, "amplitude", c.runStart, c.runEnd);
    }
    std::string describe() const override {
        std::ostringstream s;
        s << "oscillating, amplitude " << amplitude_ << " along " << vectorText(direction_) << ", period " << period_;
        return s.str();
    }

private:
    Signal signal(double t) const override { return sinusoid(t, start_, amplitude_, 2 * pi / period_, phase_); }
    double amplitude_, period_ = 1, phase_, start_;
};

// ---- rotations about a fixed axis through c: R = R(θ(t) n) -------------------------------------
class AxisRotation : public Motion {
public:
    RigidState state(double t) const override {
        const Signal s = angle(t);
        RigidState r;
        r.rotation = Eigen::AngleAxisd(s.f, axis_).toRotationMatrix();
        r.omega = axis_ * s.df;
        r.alpha = axis_ * s.ddf;
        return r;
    }

protected:
    virtual Signal angle(double t) const = 0; // radians
    V3 axis_ = V3::UnitZ();
};

class RotatingMotion final : public AxisRotation {
public:
    RotatingMotion(const Dictionary& d, const MotionContext& c)
        : rate_(readFinite(d, "rate")), start_(readFinite(d, "startTime", 0.0)), ramp_(readNonNegative(d, "rampTime", 0)) {
        axis_ = readAxis(d, c.dimension);
        centre_ = readVector(d, "centre", c.dimension);
        // the angle over the run loses its precision beyond 1e9 turns
        if (std::abs(rate_) * (std::max(c.runEnd, start_) - start_) / (2 * pi) > maxPeriods)
            throw InputError(d.locationOf("rate"), "the rotation would make more than 1e9 turns over the run", "rate");
    }
    std::string describe() const override {
        std::ostringstream s;
        s << "rotating about " << vectorText(axis_) << " through " << vectorText(centre_) << " at " << rate_
          << " rad/s";
        if (ramp_ > 0) s << " (spun up over " << ramp_ << " s)";
        return s.str();
    }

private:
    Signal angle(double t) const override {
        if (t < start_) return {};
        return ramp(t, start_, ramp_) * Signal{rate_ * (t - start_), rate_, 0};
    }
    double rate_, start_, ramp_;
};

// rolling (about a centre) and flap (about a hinge): θ = amplitude (sin(ωτ + φ) − sin φ)
class SinusoidalRotation final : public AxisRotation {
public:
    SinusoidalRotation(const Dictionary& d, const MotionContext& c, std::string type, const std::string& pointKeyword)
        : type_(std::move(type)), amplitude_(readFinite(d, "amplitude") * degree), phase_(readFinite(d, "phase", 0.0)),
          start_(readFinite(d, "startTime", 0.0)), ramp_(readNonNegative(d, "rampTime", 0)) {
        axis_ = readAxis(d, c.dimension);
        centre_ = readVector(d, pointKeyword, c.dimension);
        period_ = readPeriod(d, start_, amplitude_, "amplitude", c.runStart, c.runEnd);
    }
    std::string describe() const override {
        std::ostringstream s;
        s << type_ << " about " << vectorText(axis_) << " through " << vectorText(centre_) << ", amplitude "
          << amplitude_ / degree << " deg, period " << period_ << " s";
        return s.str();
    }

private:
    Signal angle(double t) const override {
        return ramp(t, start_, ramp_) * sinusoid(t, start_, amplitude_, 2 * pi / period_, phase_);
    }
    std::string type_;
    double amplitude_, period_ = 1, phase_, start_, ramp_;
};

// ---- wave makers ---------------------------------------------------------------------------------
struct WaveTarget {
    double height, period, depth, omega, k, stroke, ramp, start;
};

WaveTarget readWaveTarget(const Dictionary& d, const MotionContext& c, bool piston) {
    WaveTarget w{};
    w.height = readPositive(d, "waveHeight");
    w.start = readFinite(d, "startTime", 0.0);
    w.period = readPeriod(d, w.start, w.height, "waveHeight", c.runStart, c.runEnd);
    w.depth = readPositive(d, "depth");
    w.ramp = readNonNegative(d, "rampTime", 2 * w.period);
    const double g = c.gravity.norm();
    if (!(g > 0)) throw InputError(d.where(), "a wave maker needs gravity (constant/fluidProperties)", "type");
    w.omega = 2 * pi / w.period;
    w.k = waveMaker::waveNumber(w.omega, w.depth, g);
    const double kd = w.k * w.depth;
    // Miche's limit of a progressive wave's steepness: H/L ≤ 0.142 tanh(kd)
    const double L = 2 * pi / w.k, limit = 0.142 * std::tanh(kd) * L;
    if (w.height > limit) {
        std::ostringstream s;
        s << std::setprecision(4) << "a wave of height " << w.height << " m and period " << w.period << " s in depth "
          << w.depth << " m (wavelength " << L << " m) would break: Miche's limit 0.142 L tanh(kd) is " << limit << " m";
        throw InputError(d.locationOf("waveHeight"), s.str(), "waveHeight");
    }
    w.stroke = w.height / (piston ? waveMaker::pistonRatio(kd) : waveMaker::flapRatio(kd));
    return w;
}

std::string describeWave(const std::string& type, const WaveTarget& w) {
    std::ostringstream s;
    const double kd = w.k * w.depth;
    s << std::setprecision(4) << type << ", target H " << w.height << " m, T " << w.period << " s in depth " << w.depth
      << " m: wavelength " << 2 * pi / w.k << " m, k " << w.k << " 1/m, kd " << kd << ", stroke " << w.stroke
      << " m (H/S " << w.height / w.stroke << "), ramp " << w.ramp << " s";
    return s.str();
}

V3 upOf(const Dictionary& d, const MotionContext& c) {
    const double g = c.gravity.norm();
    if (!(g > 0)) throw InputError(d.where(), "a wave maker needs gravity (constant/fluidProperties)", "type");
    return -c.gravity / g;
}

class PistonWaveMaker final : public Translation {
public:
    PistonWaveMaker(const Dictionary& d, const MotionContext& c) : w_(readWaveTarget(d, c, true)) {
        direction_ = readDirection(d, "direction", c.dimension, V3::UnitX());
        if (std::abs(direction_.dot(upOf(d, c))) > 1e-9)
            throw InputError(d.locationOf("direction"), "a piston moves horizontally: direction must be normal to gravity",
                             "direction");
        secondOrder_ = d.getOrDefault<bool>("secondOrder", false);
        if (secondOrder_) second_ = waveMaker::madsenSecondHarmonic(w_.height, w_.k, w_.depth);
    }
    std::string describe() const override {
        std::ostringstream s;
        s << describeWave("pistonWaveMaker", w_) << ", along " << vectorText(direction_);
        if (secondOrder_) s << ", second order (Madsen 1971): second harmonic " << second_ << " m";
        return s.str();
    }

private:
    Signal signal(double t) const override {
        if (t < w_.start) return {};
        const double tau = t - w_.start, o = w_.omega, a = w_.stroke / 2;
        Signal x{a * std::sin(o * tau), a * o * std::cos(o * tau), -a * o * o * std::sin(o * tau)};
        if (secondOrder_) {
            const double o2 = 2 * o;
            x.f += second_ * std::sin(o2 * tau);
            x.df += second_ * o2 * std::cos(o2 * tau);
            x.ddf -= second_ * o2 * o2 * std::sin(o2 * tau);
        }
        return ramp(t, w_.start, w_.ramp) * x;
    }
    WaveTarget w_;
    bool secondOrder_ = false;
    double second_ = 0;
};

class FlapWaveMaker final : public AxisRotation {
public:
    FlapWaveMaker(const Dictionary& d, const MotionContext& c) : w_(readWaveTarget(d, c, false)) {
        if (d.getOrDefault<bool>("secondOrder", false))
            throw InputError(d.locationOf("secondOrder"),
                             "flapWaveMaker is first order only (Madsen's second-order correction is for a piston): "
                             "use secondOrder no, or a pistonWaveMaker",
                             "secondOrder");
        centre_ = readVector(d, "hinge", c.dimension);
        const V3 direction = readDirection(d, "direction", c.dimension, V3::UnitX());
        const V3 up = upOf(d, c);
        if (std::abs(direction.dot(up)) > 1e-9)
            throw InputError(d.locationOf("direction"), "the waves run horizontally: direction must be normal to gravity",
                             "direction");
        axis_ = up.cross(direction).normalized(); // a positive angle swings the top along 'direction'
        amplitude_ = std::atan(w_.stroke / (2 * w_.depth));
    }
    std::string describe() const override {
        std::ostringstream s;
        s << describeWave("flapWaveMaker", w_) << " at the still-water level, flap amplitude " << amplitude_ / degree
          << " deg about the hinge " << vectorText(centre_);
        return s.str();
    }

private:
    Signal angle(double t) const override {
        return ramp(t, w_.start, w_.ramp) * sinusoid(t, w_.start, amplitude_, w_.omega, 0.0);
    }
    WaveTarget w_;
    double amplitude_ = 0;
};

// ---- a table of (t, translation, angle) ----------------------------------------------------------
class TableMotion final : public Motion {
public:
    TableMotion(const Dictionary& d, const MotionContext& c) {
        axis_ = readAxis(d, c.dimension);
        centre_ = d.found("centre") ? readVector(d, "centre", c.dimension) : V3::Zero();
        spline_ = d.getWordOrDefault("interpolation", {"linear", "spline"}, "linear") == "spline";
        const std::string name = d.get<std::string>("file");
        path_ = std::filesystem::path(name).is_absolute() || c.caseDir.empty() ? std::filesystem::path(name)
                                                                               : c.caseDir / name;
        std::ifstream in(path_);
        if (!in) throw InputError(d.locationOf("file"), "cannot open the motion table '" + path_.string() + "'", "file");
        std::string line;
        int number = 0;
        while (std::getline(in, line)) {
            ++number;
            const auto first = line.find_first_not_of(" \t\r");
            if (first == std::string::npos || line[first] == '#' || line.compare(first, 2, "//") == 0) continue;
            std::istringstream row(line);
            double v[5];
            int n = 0;
            while (n < 5 && row >> v[n]) ++n;
            std::string rest;
            const SourceLocation where{path_.string(), number, 0};
            if (n < 5 || (row >> rest) || !row.eof())
                throw InputError(where,
                                 "a row of the motion table must hold 5 numbers: t dx dy dz angle[deg] (read: '" +
                                     line.substr(first) + "')",
                                 "file");
            for (double x : v)
                if (!std::isfinite(x)) throw InputError(where, "the motion table holds a number that is not finite", "file");
            if (c.dimension == 2 && v[3] != 0)
                throw InputError(where, "in two dimensions the table's dz must be 0", "file");
            if (!times_.empty() && !(v[0] > times_.back())) {
                std::ostringstream s;
                s << "the motion table's times must increase: " << v[0] << " follows " << times_.back();
                throw InputError(where, s.str(), "file");
            }
            times_.push_back(v[0]);
            for (int k = 0; k < 4; ++k) values_[k].push_back(k < 3 ? v[k + 1] : v[k + 1] * degree);
        }
        if (times_.size() < 2)
            throw InputError(d.locationOf("file"),
                             "the motion table '" + path_.string() + "' must hold at least 2 rows (t dx dy dz angle)",
                             "file");
        if (spline_)
            for (int k = 0; k < 4; ++k) second_[k] = naturalSpline(values_[k]);
    }
    RigidState state(double t) const override {
        Signal s[4];
        for (int k = 0; k < 4; ++k) s[k] = interpolate(k, t);
        RigidState r;
        r.translation = V3(s[0].f, s[1].f, s[2].f);
        r.velocity = V3(s[0].df, s[1].df, s[2].df);
        r.acceleration = V3(s[0].ddf, s[1].ddf, s[2].ddf);
        r.rotation = Eigen::AngleAxisd(s[3].f, axis_).toRotationMatrix();
        r.omega = axis_ * s[3].df;
        r.alpha = axis_ * s[3].ddf;
        return r;
    }
    std::string describe() const override {
        std::ostringstream s;
        s << "table '" << path_.string() << "' (" << times_.size() << " rows from t = " << times_.front() << " to "
          << times_.back() << ", " << (spline_ ? "cubic spline" : "linear")
          << "), angles about " << vectorText(axis_) << " through " << vectorText(centre_);
        return s.str();
    }

private:
    // second derivatives of the natural cubic spline through (times_, y)
    std::vector<double> naturalSpline(const std::vector<double>& y) const {
        const std::size_t n = y.size();
        std::vector<double> m(n, 0.0), c(n, 0.0), r(n, 0.0);
        // tridiagonal system for m[1..n-2] (Thomas algorithm), m[0] = m[n-1] = 0
        for (std::size_t i = 1; i + 1 < n; ++i) {
            const double h0 = times_[i] - times_[i - 1], h1 = times_[i + 1] - times_[i];
            const double a = h0 / 6, b = (h0 + h1) / 3, cc = h1 / 6;
            const double rhs = (y[i + 1] - y[i]) / h1 - (y[i] - y[i - 1]) / h0;
            const double denom = b - a * c[i - 1];
            c[i] = cc / denom;
            r[i] = (rhs - a * r[i - 1]) / denom;
        }
        for (std::size_t i = n - 1; i-- > 1;) m[i] = r[i] - c[i] * m[i + 1];
        return m;
    }
    Signal interpolate(int k, double t) const {
        const auto& y = values_[k];
        if (t <= times_.front()) return {y.front(), 0, 0};
        if (t >= times_.back()) return {y.back(), 0, 0};
        const std::size_t i = std::size_t(std::upper_bound(times_.begin(), times_.end(), t) - times_.begin()) - 1;
        const double h = times_[i + 1] - times_[i], a = (times_[i + 1] - t) / h, b = (t - times_[i]) / h;
        const double slope = (y[i + 1] - y[i]) / h;
        if (!spline_) return {a * y[i] + b * y[i + 1], slope, 0};
        const auto& m = second_[k];
        return {a * y[i] + b * y[i + 1] + ((a * a * a - a) * m[i] + (b * b * b - b) * m[i + 1]) * h * h / 6,
                slope - (3 * a * a - 1) / 6 * h * m[i] + (3 * b * b - 1) / 6 * h * m[i + 1], a * m[i] + b * m[i + 1]};
    }
    std::filesystem::path path_;
    V3 axis_ = V3::UnitZ();
    bool spline_ = false;
    std::vector<double> times_, values_[4], second_[4];
};

} // namespace

namespace waveMaker {
double waveNumber(double omega, double depth, double g) {
    // Newton on f(k) = ω² − g k tanh(kd) from the deep- or shallow-water estimate, whichever larger
    const double o2 = omega * omega;
    double k = std::max(o2 / g, omega / std::sqrt(g * depth));
    for (int it = 0; it < 100; ++it) {
        const double th = std::tanh(k * depth);
        const double f = g * k * th - o2, df = g * (th + k * depth * (1 - th * th));
        const double next = k - f / df;
        if (std::abs(next - k) <= 1e-15 * k) return next;
        k = next;
    }
    return k;
}
double pistonRatio(double kd) { return 2 * (std::cosh(2 * kd) - 1) / (std::sinh(2 * kd) + 2 * kd); }
double flapRatio(double kd) {
    return 4 * (std::sinh(kd) / kd) * (kd * std::sinh(kd) - std::cosh(kd) + 1) / (std::sinh(2 * kd) + 2 * kd);
}
double madsenSecondHarmonic(double H, double k, double depth) {
    const double kd = k * depth, s = std::sinh(kd);
    return H * H / (32 * depth) * (3 * std::cosh(kd) / (s * s * s) - 2 / pistonRatio(kd));
}
} // namespace waveMaker

void Motion::sweptRange(double t0, double t1, const Vec3& wallLo, const Vec3& wallHi, Vec3& lo, Vec3& hi) const {
    std::vector<V3> corners;
    for (int k = 0; k < 8; ++k)
        corners.emplace_back(double(k & 1 ? wallHi[0] : wallLo[0]), double(k & 2 ? wallHi[1] : wallLo[1]),
                             double(k & 4 ? wallHi[2] : wallLo[2]));
    constexpr int samples = 1024;
    V3 l = V3::Constant(std::numeric_limits<double>::max()), h = -l;
    std::vector<V3> previous(corners.size());
    double pad = 0;
    for (int k = 0; k <= samples; ++k) {
        const RigidState s = state(t0 + (t1 - t0) * k / samples);
        for (std::size_t c = 0; c < corners.size(); ++c) {
            const V3 x = position(s, corners[c]);
            l = l.cwiseMin(x);
            h = h.cwiseMax(x);
            if (k > 0) pad = std::max(pad, (x - previous[c]).norm());
            previous[c] = x;
        }
    }
    // between two samples a corner strays from the chord joining them by at most half its length
    // (the sagitta of an arc of up to half a turn; the overshoot of an oscillation's peak)
    lo = (l - V3::Constant(pad / 2)).cast<Scalar>();
    hi = (h + V3::Constant(pad / 2)).cast<Scalar>();
}

std::unique_ptr<Motion> Motion::read(const Dictionary& d, const MotionContext& c) {
    const std::string type = d.getWord(
        "type", {"linear", "oscillating", "rotating", "rolling", "flap", "table", "pistonWaveMaker", "flapWaveMaker"});
    std::unique_ptr<Motion> m;
    if (type == "linear") m = std::make_unique<LinearMotion>(d, c.dimension);
    else if (type == "oscillating") m = std::make_unique<OscillatingMotion>(d, c);
    else if (type == "rotating") m = std::make_unique<RotatingMotion>(d, c);
    else if (type == "rolling") m = std::make_unique<SinusoidalRotation>(d, c, "rolling", "centre");
    else if (type == "flap") m = std::make_unique<SinusoidalRotation>(d, c, "flap", "hinge");
    else if (type == "table") m = std::make_unique<TableMotion>(d, c);
    else if (type == "pistonWaveMaker") m = std::make_unique<PistonWaveMaker>(d, c);
    else m = std::make_unique<FlapWaveMaker>(d, c);
    d.checkAllKeywordsUsed();
    // what the run will ask of it: finite, at the start, the end and 256 times between
    constexpr int samples = 256;
    for (int k = 0; k <= samples; ++k) {
        const double t = c.runStart + (c.runEnd - c.runStart) * k / samples;
        const RigidState s = m->state(t);
        if (s.translation.allFinite() && s.velocity.allFinite() && s.acceleration.allFinite() &&
            s.rotation.allFinite() && s.omega.allFinite() && s.alpha.allFinite() &&
            s.translation.cast<Scalar>().allFinite() && s.velocity.cast<Scalar>().allFinite())
            continue;
        std::ostringstream msg;
        msg << std::setprecision(6) << "the " << type << " motion is not finite at time " << t << " (displacement "
            << vectorText(s.translation) << ", velocity " << vectorText(s.velocity) << ")";
        throw InputError(d.where(), msg.str(), "motion");
    }
    return m;
}

} // namespace spindrift
