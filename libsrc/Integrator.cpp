#include "Integrator.hpp"

namespace spindrift {

void CarriedAccelerationIntegrator::initialise(Scene& s) {
    if (keepsHalfStepVelocity_)
        for (ParticleSystem* fluid : s.ofRole(SystemRole::fluid))
            fluid->particles.addVector(halfStepField, {false, false, true});
}

std::vector<Vec3>& CarriedAccelerationIntegrator::halfStepVelocity(ParticleSystem& fluid) {
    return *fluid.particles.findVector(halfStepField);
}

void CarriedAccelerationIntegrator::kickDriftKick(Scene& s, const StepServices& core, Scalar dt,
                                                  const Evaluate& evaluate, EvaluationVelocity seen) {
    startStep(s, dt, evaluate);
    const Scalar half = Scalar(0.5) * dt;
    const bool predicted = seen == EvaluationVelocity::predicted;
    for (ParticleSystem* fluid : s.ofRole(SystemRole::fluid)) {
        auto& x = fluid->particles.position();
        auto& v = fluid->particles.velocity();
        const auto& a = fluid->particles.acceleration();
        forEachParticleOf(*fluid, [&](std::size_t i) { v[i] += half * a[i]; }); // v_{n+½}
        core.advanceDensity(s, *fluid, dt); // ρ_{n+1} = ρ_n + Δt ρ̇(x_n, v_{n+½})
        core.drift(s, *fluid, dt, v, x);
        if (predicted) { // v* = v_{n+½} + ½Δt a_n, v_{n+½} kept
            auto& kept = halfStepVelocity(*fluid);
            forEachParticleOf(*fluid, [&](std::size_t i) {
                kept[i] = v[i];
                v[i] += half * a[i];
            });
        }
    }
    evaluateAtEnd(s, dt, evaluate);
    for (ParticleSystem* fluid : s.ofRole(SystemRole::fluid)) {
        auto& v = fluid->particles.velocity();
        const auto& a = fluid->particles.acceleration();
        const Vec3* vHalf = predicted ? halfStepVelocity(*fluid).data() : v.data();
        forEachParticleOf(*fluid, [&](std::size_t i) { v[i] = vHalf[i] + half * a[i]; });
    }
}

} // namespace spindrift
