// velocityVerlet — velocity Verlet in the form usual for SPH, where forces depend on velocity
// (viscosity) as well as position:
//   x_{n+1} = x_n + Δt v_n + ½Δt² a_n
//   v*      = v_n + Δt a_n                       (predicted velocity for the force evaluation)
//   a_{n+1} = a(x_{n+1}, v*)
//   v_{n+1} = v_n + ½Δt (a_n + a_{n+1})
// One evaluation per step (a_{n+1} is the next step's a_n). Second order for position- and
// velocity-dependent forces alike (v* is first-order accurate, which a ½Δt factor makes a
// third-order local error); identical to leapfrog when forces depend on position only. An
// integrated field (continuity density) takes the rate of the mid-step velocities at x_n:
// ρ_{n+1} = ρ_n + Δt ρ̇(x_n, v_n + ½Δt a_n).
#include "Integrator.hpp"
#include "Plugin.hpp"

namespace {
using namespace spindrift;

class VelocityVerlet final : public CarriedAccelerationIntegrator {
public:
    explicit VelocityVerlet(const ModelContext&) : CarriedAccelerationIntegrator(true) {}
    int order() const override { return 2; }

    void step(Scene& s, const StepServices& core, Scalar dt, const Evaluate& evaluate) override {
        kickDriftKick(s, core, dt, evaluate, EvaluationVelocity::predicted);
    }
};
} // namespace

SPINDRIFT_PLUGIN(Integrator, VelocityVerlet)
