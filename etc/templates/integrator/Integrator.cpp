// Template integrator plugin: semi-implicit (symplectic) Euler for every fluid system,
// v_{n+1} = v_n + Δt a(x_n, v_n), x_{n+1} = x_n + Δt v_{n+1}. evaluate(t, Δt) fills the
// accelerations of the state at time t (moving walls are placed there). The core advances an
// integrated density (continuity, with a density diffusion's term) and moves the particles
// (with a shifting model's transport velocity, wrapped into a periodic domain): call both.
//   sphSchemes:  integrator { type <this folder's name>; }
#include "Integrator.hpp"
#include "Plugin.hpp"

namespace {
using namespace spindrift;

class TemplateIntegrator final : public Integrator {
public:
    explicit TemplateIntegrator(const ModelContext&) {}

    void step(Scene& s, const StepServices& core, Scalar dt, const Evaluate& evaluate) override {
        evaluate(s.time, dt);
        for (ParticleSystem* fluid : s.ofRole(SystemRole::fluid)) {
            auto& v = fluid->particles.velocity();
            const auto& a = fluid->particles.acceleration();
            forEachParticleOf(*fluid, [&](std::size_t i) { v[i] += dt * a[i]; });
            core.advanceDensity(s, *fluid, dt);                      // ρ += Δt ρ̇ (with v_{n+1}, at x_n)
            core.drift(s, *fluid, dt, v, fluid->particles.position()); // x += Δt (v_{n+1} + δv)
        }
    }
};
} // namespace

SPINDRIFT_PLUGIN(Integrator, TemplateIntegrator)
