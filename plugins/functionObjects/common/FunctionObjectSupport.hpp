// Spindrift — helpers shared by the function-object plugins (plugins/functionObjects):
//
//  * SamplingFunctionObject: the base of an object that writes a row of samples at the times
//    its SampleControl gives, to postProcessing/<name>/<startTime>/, of one particle system:
//        system fluid;            // the system sampled (default: the fluid, when there is one)
//  * SampleControl: when an object samples, from its dictionary
//        writeControl  timeStep | runTime | writeTime;   // default timeStep
//        writeInterval 10;        // steps (timeStep, default 1) or seconds (runTime, required)
//    runTime samples at the first step ending at or after each multiple of writeInterval
//    (counted from the start time); writeTime samples when the solver writes a time directory.
//  * forEachSampledWithin(): the particles of the sampled system within the support radius of a
//    point, at their current positions (the neighbour search's point query, which builds its
//    grid again whenever the particles have moved: after an integrator moved them past the
//    step's search, and in start() before the first force evaluation). Periodic axes use the
//    minimum image.
//  * shepardSum(): Shepard-normalised SPH interpolation at a point,
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
        : name_(c.name), dim_(c.physics.dimension), caseDir_(c.caseDirectory), control_(c.dict),
          systemName_(c.dict.getOrDefault<std::string>("system", "")),
          systemWhere_(c.dict.found("system") ? c.dict.locationOf("system") : c.dict.where()) {}
    // Opens the output (call it from start(); it selects the sampled system if not yet done).
    void open(const Scene& s, double startTime, const std::vector<PostProcessingColumn>& columns) {
        select(s);
        file_ = PostProcessingFile(caseDir_, name_, startTime, columns);
        control_.start(startTime);
    }
    // Resolves the sampled system: `system <name>;`, or the one fluid system.
    const ParticleSystem& select(const Scene& s) {
        system_ = &resolveSystem(s);
        return *system_;
    }
    // One row at the scene's time; listsValid: the neighbour lists are the step's (false at start()).
    virtual void sample(const Scene& s, bool listsValid) = 0;
    // The system sampled (resolved by open()).
    const ParticleSystem& sampled() const { return *system_; }

    // f(j, r) for every particle j of the sampled system within the support radius of p, at the
    // particles' current positions.
    template <class F> void forEachSampledWithin(const Scene& s, const Vec3& p, F&& f) const {
        s.search.forEachWithin(system_->index, p, s.constants.supportRadius, s.stateVersion, std::forward<F>(f));
    }
    // Kernel sum Σ_j V_j W(x − x_j) at a point over the sampled system (≈ 1 inside the fluid, ≈ ½
    // at a free surface); 'accumulate(j, weight)' is called for every neighbour with weight V_j W.
    template <class F> Scalar shepardSum(const Scene& s, const Vec3& p, F&& accumulate) const {
        const auto& rho = system_->particles.density();
        const Scalar m = system_->particles.particleMass();
        Scalar sum = 0;
        forEachSampledWithin(s, p, [&](Index j, Scalar r) {
            const Scalar w = m / rho[j] * s.kernel.W(r);
            sum += w;
            accumulate(j, w);
        });
        return sum;
    }

    std::string name_;
    int dim_;
    PostProcessingFile file_;

private:
    // `system <name>;`, or the one fluid system; an InputError names the entry otherwise.
    const ParticleSystem& resolveSystem(const Scene& s) const {
        if (!systemName_.empty()) {
            if (const ParticleSystem* p = s.find(systemName_)) return *p;
            std::string names;
            for (const auto& p : s.systems) names += (names.empty() ? "" : " ") + p->name();
            throw InputError(systemWhere_, "function object '" + name_ + "': no particle system '" + systemName_ +
                                               "'; systems: (" + names + ")", "system");
        }
        const auto fluids = s.ofRole(SystemRole::fluid);
        if (fluids.size() != 1)
            throw InputError(systemWhere_, "function object '" + name_ + "': the case has " +
                                               std::to_string(fluids.size()) +
                                               " fluid systems; name the one to sample with 'system <name>;'",
                             "system");
        return *fluids.front();
    }

    std::filesystem::path caseDir_;
    SampleControl control_;
    std::string systemName_;
    SourceLocation systemWhere_;
    const ParticleSystem* system_ = nullptr;
};

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
