// symplecticEuler — semi-implicit Euler: v_{n+1} = v_n + Δt a(x_n, v_n), x_{n+1} = x_n + Δt v_{n+1}
// (+ Δt δv of a shifting model), and an integrated field (continuity density) ρ_{n+1} = ρ_n + Δt ρ̇
// with the rate of v_{n+1} at x_n (symplectic, as x and v).
// First order, symplectic; the integrator PCISPH, PBF and DFSPH are formulated with, so the one
// that applies their Δx/Δt² and Δv/Δt results exactly (ResultKind).
#include "Integrator.hpp"
#include "Plugin.hpp"

namespace {
using namespace spindrift;

class SymplecticEuler final : public Integrator {
public:
    explicit SymplecticEuler(const ModelContext&) {}

    // the scheme position-based (Δx/Δt²) and velocity-based (Δv/Δt) results are formulated with
    bool applies(ResultKind) const override { return true; }

    void step(Scene& s, const StepServices& core, Scalar dt, const Evaluate& evaluate) override {
        evaluate(s.time, dt);
        for (ParticleSystem* fluid : s.ofRole(SystemRole::fluid)) {
            auto& v = fluid->particles.velocity();
            const auto& a = fluid->particles.acceleration();
            forEachParticleOf(*fluid, [&](std::size_t i) { v[i] += dt * a[i]; });
            core.advanceDensity(s, *fluid, dt); // with v_{n+1}, at x_n
            core.drift(s, *fluid, dt, v, fluid->particles.position());
        }
    }
};
} // namespace

SPINDRIFT_PLUGIN(Integrator, SymplecticEuler)
