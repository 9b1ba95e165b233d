// Spindrift — time integrator interface (plugins/integrators).
//
// step() advances the positions and velocities of every fluid system by dt. It starts on the
// neighbour lists of the current positions, the moving walls placed at scene.time (the core
// makes them so, also after a restart, a re-sort or a blow-up's roll-back). It calls
// evaluate(t, dt) whenever it needs accelerations at the current positions and velocities, t
// being the time of that state (moving walls are placed there) and dt the step it is taken for
// (iterative solvers predict with it): evaluate() rebuilds the neighbour lists and fills each
// fluid's acceleration() (density, boundary, non-pressure, pressure). So multi-stage and
// multi-step schemes fit one interface. The particles move with the core's drift
// (StepServices::drift: the shifting model's transport velocity and the periodic wrap are the
// core's), and an integrated density advances with the core's advanceDensity (continuity, with a
// density diffusion's term). Per-particle state that must survive between steps (history)
// lives in fields registered on the fluid systems in initialise(), so it is re-sorted with the
// particles and written for restarts. applies() says which results (ModelContext.hpp:
// ResultKind) the scheme applies exactly; the core refuses a model whose result the integrator
// cannot apply. Bodies are advanced by the core after the step (RigidBody.hpp).
#pragma once

#include "Model.hpp"
#include "Parallel.hpp"
#include "Step.hpp"

#include <functional>

namespace spindrift {

class Integrator : public Model {
public:
    using Evaluate = std::function<void(double time, Scalar dt)>;
    // The state (every restart field, scene.step and scene.time) was just read from a time
    // directory: restore any non-field state so the run continues as if never interrupted.
    virtual void restarted(Scene&) {}
    virtual void step(Scene& scene, const StepServices& core, Scalar dt, const Evaluate& evaluate) = 0;
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
    void initialise(Scene& s) override;

protected:
    // Evaluates a_n at the start of the step unless the last step left it.
    void startStep(const Scene& s, Scalar dt, const Evaluate& evaluate) {
        if (!haveAcceleration_) evaluate(s.time, dt);
    }
    // Evaluates at the step's end state (time t + Δt); it is the next step's a_n.
    void evaluateAtEnd(const Scene& s, Scalar dt, const Evaluate& evaluate) {
        evaluate(s.time + dt, dt);
        haveAcceleration_ = true;
    }
    // How kickDriftKick's forces at x_{n+1} see the velocity.
    enum class EvaluationVelocity {
        halfStep,  // v_{n+½} (leapfrog)
        predicted, // v* = v_n + Δt a_n (velocity Verlet)
    };
    // The kick–drift–kick step on the carried a_n: v_{n+½} = v_n + ½Δt a_n; the integrated density
    // advanced with v_{n+½} at x_n; x_{n+1} = x_n + Δt v_{n+½}; a_{n+1} evaluated at x_{n+1} with
    // the velocity `seen`; v_{n+1} = v_{n+½} + ½Δt a_{n+1}.
    void kickDriftKick(Scene& s, const StepServices& core, Scalar dt, const Evaluate& evaluate, EvaluationVelocity seen);

    // kickDriftKick with EvaluationVelocity::predicted keeps v_{n+½} in a scratch field of each
    // fluid (registered by initialise when this is set)
    explicit CarriedAccelerationIntegrator(bool keepsHalfStepVelocity = false)
        : keepsHalfStepVelocity_(keepsHalfStepVelocity) {}

private:
    static constexpr const char* halfStepField = "halfStepVelocity";
    std::vector<Vec3>& halfStepVelocity(ParticleSystem& fluid);
    bool haveAcceleration_ = false;
    bool keepsHalfStepVelocity_;
};

// f(i) for every particle of a system (its own, not its ghosts), in parallel: the integrators'
// kick and drift loops.
template <class F> void forEachParticleOf(const ParticleSystem& system, F&& f) {
    forEachIndex(system.ownedSize(), std::forward<F>(f));
}

} // namespace spindrift
