// leapfrog — kick–drift–kick leapfrog (velocity form): v_{n+½} = v_n + ½Δt a_n,
// x_{n+1} = x_n + Δt v_{n+½}, a_{n+1} = a(x_{n+1}, v_{n+½}), v_{n+1} = v_{n+½} + ½Δt a_{n+1}.
// Second order for velocity-independent forces; one evaluation per step (a_{n+1} is reused as
// the next step's a_n). An integrated field (continuity density) takes the rate of the half-step
// velocities at x_n: ρ_{n+1} = ρ_n + Δt ρ̇(x_n, v_{n+½}).
#include "Integrator.hpp"
#include "Plugin.hpp"

namespace {
using namespace spindrift;

class Leapfrog final : public CarriedAccelerationIntegrator {
public:
    explicit Leapfrog(const ModelContext&) {}
    int order() const override { return 2; }

    void step(Scene& s, const StepServices& core, Scalar dt, const Evaluate& evaluate) override {
        kickDriftKick(s, core, dt, evaluate, EvaluationVelocity::halfStep);
    }
};
} // namespace

SPINDRIFT_PLUGIN(Integrator, Leapfrog)
