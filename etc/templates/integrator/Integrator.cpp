// Template integrator plugin: semi-implicit (symplectic) Euler,
// v_{n+1} = v_n + Δt a(x_n, v_n), x_{n+1} = x_n + Δt v_{n+1}. evaluate(t) fills the accelerations
// of the state at time t (moving walls are placed there).
//   sphSchemes:  integrator { type <this folder's name>; }
#include "Integrator.hpp"
#include "Plugin.hpp"

namespace {
using namespace spindrift;

class TemplateIntegrator final : public Integrator {
public:
    explicit TemplateIntegrator(const ModelContext&) {}

    void step(Scene& s, Scalar dt, const Evaluate& evaluate) override {
        evaluate(s.time);
        auto& x = s.fluid.position();
        auto& v = s.fluid.velocity();
        const auto& a = s.fluid.acceleration();
        for (std::size_t i = 0; i < x.size(); ++i) {
            v[i] += dt * a[i];
            x[i] += dt * v[i];
        }
    }
};
} // namespace

SPINDRIFT_PLUGIN(Integrator, TemplateIntegrator)
