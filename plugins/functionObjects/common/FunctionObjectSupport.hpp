// Spindrift — helpers shared by the function-object plugins (plugins/functionObjects):
//
//  * SamplingFunctionObject: the base of an object that writes a row of samples at the times
//    its SampleControl gives, to postProcessing/<name>/<startTime>/.
//  * SampleControl: when an object samples, from its dictionary
//        writeControl  timeStep | runTime | writeTime;   // default timeStep
//        writeInterval 10;        // steps (timeStep, default 1) or seconds (runTime, required)
//    runTime samples at the first step ending at or after each multiple of writeInterval
//    (counted from the start time); writeTime samples when the solver writes a time directory.
//  * SampleGrid: a uniform grid of the fluid particles built at sample time (cell = support
//    radius h), so interpolation at arbitrary points sees the current positions even after an
//    integrator moved the particles past the step's neighbour search, and works in start()
//    before the first force evaluation. Periodic axes use the minimum image.
//  * shepard(): Shepard-normalised SPH interpolation at a point,
//        f(x) = Σ_j f_j V_j W(x − x_j) / Σ_j V_j W(x − x_j),   V_j = m/ρ_j.
//  * columnLabel(): "p(0.1,0.05,0)"-style column names carrying the sample location.
//  * lengthUnit(), massUnit(): units of per-unit-depth quantities in 2D (a 2D case's particle
//    mass is per metre of depth: kg/m).
#pragma once

#include "Dictionary.hpp"
#include "FunctionObject.hpp"
#include "ModelContext.hpp"
#include "NeighbourSearch.hpp"
#include "PairLoop.hpp"

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace spindrift::functionObjects {

class SampleControl {
public:
    enum class Mode { TimeStep, RunTime, WriteTime };

    explicit SampleControl(const Dictionary& d) {
        const std::string mode = d.getWordOrDefault("writeControl", {"timeStep", "runTime", "writeTime"}, "timeStep");
        if (mode == "runTime") {
            mode_ = Mode::RunTime;
            interval_ = d.get<double>("writeInterval");
            if (!(interval_ > 0))
                throw InputError(d.locationOf("writeInterval"), "writeInterval must be positive", "writeInterval");
        } else if (mode == "writeTime") {
            mode_ = Mode::WriteTime;
        } else {
            mode_ = Mode::TimeStep;
            const int steps = d.getOrDefault<int>("writeInterval", 1);
            if (steps < 1)
                throw InputError(d.locationOf("writeInterval"), "writeInterval (steps) must be at least 1",
                                 "writeInterval");
            interval_ = steps;
        }
    }

    void start(double startTime) {
        startTime_ = startTime;
        next_ = 1;
        steps_ = 0;
    }

    // After a step ending at 'time': sample now?
    bool due(double time, bool writeTime) {
        switch (mode_) {
        case Mode::WriteTime: return writeTime;
        case Mode::TimeStep: return ++steps_ % long(interval_) == 0;
        case Mode::RunTime: {
            const double tolerance = 1e-9 * std::max(1.0, std::abs(time));
            if (time - startTime_ < next_ * interval_ - tolerance) return false;
            // skip every multiple this step passed
            next_ = std::floor((time - startTime_ + tolerance) / interval_) + 1;
            return true;
        }
        }
        return false;
    }

private:
    Mode mode_ = Mode::TimeStep;
    double interval_ = 1, startTime_ = 0, next_ = 1;
    long steps_ = 0;
};

// A function object that writes one row to postProcessing/<name>/<startTime>/<name>.dat at each
// time its SampleControl gives (fieldStats, probes, surgeFront, waterLevel). start() names the
// columns and calls open(); the object's sample() writes a row to file_.
class SamplingFunctionObject : public FunctionObject {
public:
    void execute(const Scene& s, bool writeTime) override {
        if (control_.due(s.time, writeTime)) sample(s, true);
    }

protected:
    explicit SamplingFunctionObject(const ModelContext& c)
        : name_(c.name), dim_(c.physics.dimension), caseDir_(c.caseDirectory), control_(c.dict) {}
    void open(double startTime, const std::vector<PostProcessingColumn>& columns) {
        file_ = PostProcessingFile(caseDir_, name_, startTime, columns);
        control_.start(startTime);
    }
    // One row at the scene's time; listsValid: the neighbour lists are the step's (false at start()).
    virtual void sample(const Scene& s, bool listsValid) = 0;

    std::string name_;
    int dim_;
    PostProcessingFile file_;

private:
    std::filesystem::path caseDir_;
    SampleControl control_;
};

// The fluid particles bucketed on a grid of cell size h over their current bounding box.
class SampleGrid {
public:
    void build(const Scene& s) {
        const auto& x = s.fluid.position();
        const int dim = s.physics.dimension;
        const Scalar h = s.physics.supportRadius;
        Vec3 lo = Vec3::Constant(std::numeric_limits<Scalar>::max()), hi = -lo;
        for (const auto& p : x) {
            lo = lo.cwiseMin(p);
            hi = hi.cwiseMax(p);
        }
        if (x.empty()) lo = hi = Vec3::Zero();
        lo -= Vec3::Constant(h);
        hi += Vec3::Constant(h);
        const Periodicity& periodic = s.search.periodicity();
        for (int a = 0; a < 3; ++a)
            if (periodic.axis[a]) {
                lo[a] = periodic.min[a];
                hi[a] = periodic.min[a] + periodic.length[a];
            }
        if (dim == 2) lo[2] = hi[2] = 0;
        grid_.setup(h, dim, lo, hi, periodic);
        grid_.build(x);
        periodic_ = periodic;
    }

    template <class F> void forEachWithin(const Scene& s, const Vec3& p, F&& f) const {
        const auto& x = s.fluid.position();
        grid_.forEachWithin(p, x, s.physics.supportRadius, [&](Index j) {
            Vec3 d = p - x[j];
            periodic_.minimumImage(d);
            f(j, d.norm());
        });
    }

private:
    UniformGrid grid_;
    Periodicity periodic_;
};

// Kernel sum Σ_j V_j W(x − x_j) at a point (≈ 1 inside the fluid, ≈ ½ at a free surface);
// 'accumulate(j, weight)' is called for every neighbour with weight V_j W.
template <class F> Scalar shepardSum(const Scene& s, const SampleGrid& grid, const Vec3& p, F&& accumulate) {
    const auto& rho = s.fluid.density();
    const Scalar m = s.fluid.particleMass();
    Scalar sum = 0;
    grid.forEachWithin(s, p, [&](Index j, Scalar r) {
        const Scalar w = m / rho[j] * s.kernel.W(r);
        sum += w;
        accumulate(j, w);
    });
    return sum;
}

// "name(x,y,z)" with the third coordinate left out in 2D.
inline std::string columnLabel(const std::string& name, const Vec3& p, int dimension) {
    std::ostringstream o;
    o << std::setprecision(6) << name << '(' << p[0] << ',' << p[1];
    if (dimension == 3) o << ',' << p[2];
    o << ')';
    return o.str();
}

// "kg" in 3D, "kg/m" (per metre of depth) in 2D; the other extensive units follow from it.
inline std::string massUnit(int dimension) { return dimension == 3 ? "kg" : "kg/m"; }

inline constexpr double notANumber = std::numeric_limits<double>::quiet_NaN();

} // namespace spindrift::functionObjects
