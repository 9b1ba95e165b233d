// Spindrift — time integrator interface (plugins/integrators).
//
// step() advances fluid positions and velocities by dt. It starts on the neighbour lists of the
// current fluid positions, the moving walls placed at scene.time (the core makes them so, also
// after a restart, a re-sort or a blow-up's roll-back). It calls evaluate(t) whenever it needs
// accelerations at the current positions and velocities, t being the time of that state (moving
// walls are placed there): evaluate() rebuilds the neighbour lists and fills fluid.acceleration()
// (density, boundary, non-pressure, pressure). So multi-stage and multi-step schemes fit one
// interface. Per-particle state that must survive between steps (history) lives in fields
// registered on the fluid set in initialise(), so it is re-sorted with the particles and written
// for restarts. applies() says which results (ModelContext.hpp: ResultKind) the scheme applies
// exactly; the core refuses a model whose result the integrator cannot apply.
#pragma once

#include "DensityDiffusion.hpp"
#include "ModelContext.hpp"

#include <functional>

namespace spindrift {

class Integrator {
public:
    using Evaluate = std::function<void(double time)>;
    virtual ~Integrator() = default;
    virtual void initialise(Scene&) {}
    // The state (every restart field, scene.step and scene.time) was just read from a time
    // directory: restore any non-field state so the run continues as if never interrupted.
    virtual void restarted(Scene&) {}
    virtual void step(Scene& scene, Scalar dt, const Evaluate& evaluate) = 0;
    virtual bool applies(ResultKind kind) const { return kind == ResultKind::acceleration; }
    // The global order of accuracy for smooth forces: the error at a fixed time shrinks as
    // Δt^order (the contract tests measure it on a harmonic oscillator). 0: inconsistent.
    virtual int order() const { return 1; }
};

// The integrators that take the accelerations evaluated at the end of one step as the next
// step's a_n (leapfrog, velocityVerlet, pereaCordero: one evaluation a step). At the first step,
// and after a restart from step 0, they evaluate first; after a later restart the accelerations
// come back with the other restart fields, and the step's lists (which the integrated fields'
// rates are taken on before the step's evaluation) are the core's to make.
class CarriedAccelerationIntegrator : public Integrator {
public:
    void restarted(Scene& s) override { haveAcceleration_ = s.step > 0; }

protected:
    // Evaluates a_n at the start of the step unless the last step left it.
    void startStep(const Scene& s, const Evaluate& evaluate) {
        if (!haveAcceleration_) evaluate(s.time);
    }
    // Evaluates at the step's end state (time t + Δt); it is the next step's a_n.
    void evaluateAtEnd(const Scene& s, Scalar dt, const Evaluate& evaluate) {
        evaluate(s.time + dt);
        haveAcceleration_ = true;
    }
    // How kickDriftKick's forces at x_{n+1} see the velocity.
    enum class EvaluationVelocity {
        halfStep,  // v_{n+½} (leapfrog)
        predicted, // v* = v_n + Δt a_n (velocity Verlet)
    };
    // The kick–drift–kick step on the carried a_n: v_{n+½} = v_n + ½Δt a_n; the integrated fields
    // advanced with v_{n+½} at x_n; x_{n+1} = x_n + Δt v_{n+½}; a_{n+1} evaluated at x_{n+1} with
    // the velocity `seen`; v_{n+1} = v_{n+½} + ½Δt a_{n+1}.
    void kickDriftKick(Scene& s, Scalar dt, const Evaluate& evaluate, EvaluationVelocity seen);

private:
    bool haveAcceleration_ = false;
    std::vector<Vec3> halfStepVelocity_; // v_{n+½} while the forces see v* (scratch within a step)
};

// f(i) for every fluid particle, in parallel: the integrators' kick and drift loops.
template <class F> void forEachFluidParticle(const Scene& s, F&& f) {
    const std::size_t n = s.fluid.size();
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i) f(i);
}

// The velocity particle i moves with: its own, plus the shifting model's transport correction δv
// when the case names one (Scene::shiftingVelocity).
inline Vec3 advectionVelocity(const Scene& s, const std::vector<Vec3>& v, std::size_t i) {
    return s.shiftingVelocity ? Vec3(v[i] + (*s.shiftingVelocity)[i]) : v[i];
}

// Advances every integrated field (continuity density) over a step dt: its rate from the
// fluid's current velocities — those the particles move with over the step — at the positions
// the step starts from (call it before the drift, while the lists are those of these positions),
// plus a density-diffusion term for the density, then value += dt · rate.
void advanceIntegratedFields(Scene& s, Scalar dt);

} // namespace spindrift
