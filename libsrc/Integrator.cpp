#include "Integrator.hpp"

namespace spindrift {

void advanceIntegratedFields(Scene& s, Scalar dt) {
    for (const IntegratedField& f : s.integratedFields) {
        auto& rate = *f.rate;
        f.computeRate(s, rate);
        auto& value = *f.value;
        forEachFluidParticle(s, [&](std::size_t i) { value[i] += dt * rate[i]; });
    }
}

void CarriedAccelerationIntegrator::kickDriftKick(Scene& s, Scalar dt, const Evaluate& evaluate, EvaluationVelocity seen) {
    startStep(s, evaluate);
    auto& x = s.fluid.position();
    auto& v = s.fluid.velocity();
    const auto& a = s.fluid.acceleration();
    const Scalar half = Scalar(0.5) * dt;
    const bool predicted = seen == EvaluationVelocity::predicted;
    if (predicted) halfStepVelocity_.resize(s.fluid.size());
    forEachFluidParticle(s, [&](std::size_t i) {
        v[i] += half * a[i]; // v_{n+½}
        if (predicted) halfStepVelocity_[i] = v[i];
    });
    advanceIntegratedFields(s, dt); // ρ_{n+1} = ρ_n + Δt ρ̇(x_n, v_{n+½})
    forEachFluidParticle(s, [&](std::size_t i) {
        x[i] += dt * advectionVelocity(s, v, i);
        if (predicted) v[i] += half * a[i]; // v* = v_{n+½} + ½Δt a_n
    });
    evaluateAtEnd(s, dt, evaluate);
    forEachFluidParticle(s, [&](std::size_t i) { v[i] = (predicted ? halfStepVelocity_[i] : v[i]) + half * a[i]; });
}

} // namespace spindrift
